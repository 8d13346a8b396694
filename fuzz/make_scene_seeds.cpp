// Writes the generated part of fuzz_scene's seeds: the project's own scene files, each behind
// the mode byte that fuzz_scene reads (see fuzz_scene.cpp), and two variants of the fixed
// bundle's glTF. The build runs it into build-fuzz/fuzz/seeds/scene/ whenever one of the files
// changes (fuzz/CMakeLists.txt holds the list); the hand-made bad files, which no project file
// gives, are committed in fuzz/corpus/scene-handmade/ instead.
//
//   make_scene_seeds DIR BUNDLE NAME=FILE...
//
// NAME=FILE: the seed DIR/NAME is FILE's bytes behind the mode byte of NAME's extension ('0'
// .json, '1' .obj, '2' .mtl, '3' .gltf and .glb: the file of the bundle the input replaces).
// BUNDLE: fuzz/scene_bundle/. Its triangle.gltf also gives textured.gltf (the bundle's
// checker.ppm as textures and as an external buffer) and triangle.glb (the binary container),
// which reach what the bundle's glTF lacks.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;  // keeps the file's key order

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

char modeOf(const fs::path& name) {
    const std::string ext = name.extension().string();
    if (ext == ".json") return '0';
    if (ext == ".obj") return '1';
    if (ext == ".mtl") return '2';
    if (ext == ".gltf" || ext == ".glb") return '3';
    throw std::runtime_error(name.string() + ": no mode for this extension");
}

std::string base64Decode(std::string_view text) {
    static constexpr std::string_view kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        if (c == '=') break;
        const std::size_t value = kAlphabet.find(c);
        if (value == std::string_view::npos) throw std::runtime_error("bad base64");
        bits = bits << 6 | static_cast<std::uint32_t>(value);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out.push_back(static_cast<char>(bits >> count & 0xff));
        }
    }
    return out;
}

void appendU32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(v >> 8 * i & 0xff));
}

/// The glTF with the bundle's checker.ppm as the base colour texture of the first material, the
/// emissive texture of the last, and as a second (external) buffer.
std::string texturedGltf(Json gltf, std::uintmax_t textureSize) {
    Json& materials = gltf.at("materials");
    if (materials.empty()) throw std::runtime_error("the bundle's glTF has no material");
    materials.front()["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    materials.back()["emissiveTexture"] = {{"index", 0}};
    gltf.at("buffers").push_back({{"byteLength", textureSize}, {"uri", "checker.ppm"}});
    // Last: a new key moves the others (an ordered_json object is a vector), `materials` too.
    gltf["images"] = Json::array({{{"uri", "checker.ppm"}}});
    gltf["textures"] = Json::array({{{"source", 0}}});
    return gltf.dump();
}

/// The glTF as a .glb: its first buffer, a data: URI, moves to the BIN chunk.
std::string glb(Json gltf) {
    const std::string uri = gltf.at("buffers").at(0).at("uri").get<std::string>();
    const std::size_t comma = uri.find(',');
    if (uri.rfind("data:", 0) != 0 || comma == std::string::npos)
        throw std::runtime_error("the bundle glTF's first buffer is not a data: URI");
    std::string data = base64Decode(std::string_view(uri).substr(comma + 1));
    gltf["buffers"] = Json::array({{{"byteLength", data.size()}}});
    std::string text = gltf.dump();
    text.append(-text.size() % 4, ' ');
    data.append(-data.size() % 4, '\0');
    std::string chunks;
    appendU32(chunks, static_cast<std::uint32_t>(text.size()));
    appendU32(chunks, 0x4E4F534A);  // JSON
    chunks += text;
    appendU32(chunks, static_cast<std::uint32_t>(data.size()));
    appendU32(chunks, 0x004E4942);  // BIN
    chunks += data;
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, static_cast<std::uint32_t>(12 + chunks.size()));
    return out + chunks;
}

void write(const fs::path& dir, const fs::path& bundle, int count, char** seeds) {
    fs::create_directories(dir);
    for (int i = 0; i < count; ++i) {
        const std::string arg = seeds[i];
        const std::size_t eq = arg.find('=');
        if (eq == std::string::npos || eq == 0) throw std::runtime_error("not NAME=FILE: " + arg);
        const fs::path name = arg.substr(0, eq);
        writeFile(dir / name, modeOf(name) + readFile(arg.substr(eq + 1)));
    }
    const Json gltf = Json::parse(readFile(bundle / "triangle.gltf"));
    writeFile(dir / "textured.gltf",
              '3' + texturedGltf(gltf, fs::file_size(bundle / "checker.ppm")));
    writeFile(dir / "triangle.glb", '3' + glb(gltf));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s DIR BUNDLE [NAME=FILE...]\n", argv[0]);
        return 2;
    }
    try {
        write(argv[1], argv[2], argc - 3, argv + 3);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "make_scene_seeds: %s\n", e.what());
        return 1;
    }
}
