// libFuzzer target: the scene-file parser (igi::parseScene) and the OBJ, MTL and glTF loaders
// it calls, on files a user (or a master) could hand over.
//
// The first byte of the input picks which file the rest of it replaces in a small fixed bundle
// (fuzz/scene_bundle/: scene.json naming box.obj, with box.mtl and checker.ppm, and
// triangle.gltf): 0 the scene JSON, 1 the OBJ, 2 the MTL, 3 the glTF (modulo 4, so the seed
// files start with a readable '0' .. '3'). The scene is parsed from memory through a
// BundleFileSource, as a client parses it.
// SceneError is the expected answer to a bad file. Anything else is a bug: another exception
// type, a sanitizer report, an allocation beyond libFuzzer's -malloc_limit_mb, a timeout.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <typeinfo>

#include <spdlog/spdlog.h>

#include "scene/FileSource.h"
#include "scene/SceneError.h"
#include "scene/SceneLoader.h"

#ifndef IGI_FUZZ_SCENE_BUNDLE
#error "IGI_FUZZ_SCENE_BUNDLE must name the folder of the fixed scene files"
#endif

namespace {

namespace fs = std::filesystem;

constexpr const char* kSceneName = "fuzz.json";
/// The file each mode replaces; the scene file itself is not in the bundle.
constexpr const char* kModeFiles[4] = {"scene.json", "box.obj", "box.mtl", "triangle.gltf"};

struct FixedBundle {
    std::string sceneText;
    std::map<std::string, std::string> files;
};

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "fuzz_scene: cannot read %s\n", path.string().c_str());
        std::exit(1);
    }
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return std::move(bytes).str();
}

/// IGI_FUZZ_SCENE_BUNDLE in the environment overrides the folder compiled in.
FixedBundle& fixedBundle() {
    static FixedBundle bundle = [] {
        const char* env = std::getenv("IGI_FUZZ_SCENE_BUNDLE");
        const fs::path dir = env ? env : IGI_FUZZ_SCENE_BUNDLE;
        FixedBundle b;
        b.sceneText = readFile(dir / "scene.json");
        for (const char* name : {"box.obj", "box.mtl", "checker.ppm", "triangle.gltf"})
            b.files[name] = readFile(dir / name);
        return b;
    }();
    return bundle;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // The loaders warn about what they tolerate (case-insensitive file names, energy clamped):
    // millions of lines of that would hide the fuzzer's own output.
    spdlog::set_level(spdlog::level::off);
    fixedBundle();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const int mode = data[0] % 4;
    const std::string fuzzed(reinterpret_cast<const char*>(data) + 1, size - 1);

    const FixedBundle& fixed = fixedBundle();
    std::string sceneText = fixed.sceneText;
    std::map<std::string, std::string> files = fixed.files;
    if (mode == 0)
        sceneText = fuzzed;
    else
        files[kModeFiles[mode]] = fuzzed;

    igi::BundleFileSource source(std::move(files));
    try {
        (void)igi::parseScene(sceneText, kSceneName, source);
    } catch (const igi::SceneError& e) {
        // A bad file, reported as such. IGI_FUZZ_VERBOSE=1 prints why (to check seeds).
        static const bool verbose = std::getenv("IGI_FUZZ_VERBOSE") != nullptr;
        if (verbose) std::fprintf(stderr, "fuzz_scene: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_scene: unexpected %s: %s\n", typeid(e).name(), e.what());
        std::abort();
    }
    return 0;
}
