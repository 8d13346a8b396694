#include "scene/TextureLoader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>
#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include <spdlog/spdlog.h>

#include "scene/SceneError.h"

namespace igi {

namespace {

namespace fs = std::filesystem;

constexpr int kMaxTextureSide = 32768;
// Colour comes from the first three channels and coverage from the alpha channel; more (depth,
// a TIFF claiming 65535) are never read.
constexpr int kColourChannels = 3;
constexpr int kMaxReadChannels = 4;

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
        return t;
    }();
    return table;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// The name's extension for a temporary file, lower case, or nothing when it holds anything
// but letters and digits (the name comes from a scene file).
std::string safeExtension(const std::string& name) {
    const std::string ext = lower(fs::path(name).extension().string());
    if (ext.size() < 2 || ext.size() > 8) return "";
    for (std::size_t i = 1; i < ext.size(); ++i) {
        if (!std::isalnum(static_cast<unsigned char>(ext[i]))) return "";
    }
    return ext;
}

// A temporary copy of the bytes for decoders that cannot read through an IOProxy; removed
// when it goes out of scope.
class TempImageFile {
  public:
    TempImageFile(const std::string& name, const std::string& bytes) {
        static std::atomic<int> counter{0};
        path_ = fs::temp_directory_path() / ("igi-texture-" + std::to_string(::getpid()) + "-" +
                                             std::to_string(counter++) + safeExtension(name));
        std::ofstream out(path_, std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) throw SceneError::inFile(name, "cannot write a temporary copy to decode it");
    }
    ~TempImageFile() {
        std::error_code ec;
        fs::remove(path_, ec);
    }
    TempImageFile(const TempImageFile&) = delete;
    TempImageFile& operator=(const TempImageFile&) = delete;
    std::string path() const { return path_.string(); }

  private:
    fs::path path_;
};

// Opens the image from memory when its decoder supports an IOProxy (JPEG, PNG, EXR, ...),
// else from a temporary file.
std::unique_ptr<OIIO::ImageInput> openImage(const std::string& name, const std::string& bytes,
                                            OIIO::Filesystem::IOMemReader& proxy,
                                            std::unique_ptr<TempImageFile>& temp) {
    // Colours as the file stores them: glTF base colours and PNGs are not premultiplied, and
    // OpenImageIO would otherwise multiply them by alpha as it reads.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::create(name, false, nullptr, &proxy);
    if (in && in->supports("ioproxy")) {
        OIIO::ImageSpec spec;
        if (in->set_ioproxy(&proxy) && in->open(name, spec, config)) return in;
    }
    OIIO::geterror();  // clear the failed attempt's message
    temp = std::make_unique<TempImageFile>(name, bytes);
    in = OIIO::ImageInput::open(temp->path(), &config);
    if (!in) throw SceneError::inFile(name, "cannot decode image: " + OIIO::geterror());
    return in;
}

bool isLinear(const OIIO::ImageSpec& spec) {
    if (spec.format.basetype == OIIO::TypeDesc::FLOAT ||
        spec.format.basetype == OIIO::TypeDesc::HALF ||
        spec.format.basetype == OIIO::TypeDesc::DOUBLE) {
        return true;
    }
    return lower(spec.get_string_attribute("oiio:ColorSpace")) == "linear";
}

// Pixel i of an interleaved buffer with `channels` channels, as RGB.
template <typename T, typename Decode>
glm::vec3 rgbAt(const std::vector<T>& pixels, std::size_t i, int channels, Decode decode) {
    const T* p = &pixels[i * channels];
    if (channels < 3) return glm::vec3(decode(p[0]));
    return {decode(p[0]), decode(p[1]), decode(p[2])};
}

// The channel that holds alpha among the first kMaxReadChannels, or -1: the one the file
// names, else the last of a grey-alpha or RGBA image.
int alphaChannelOf(const OIIO::ImageSpec& spec) {
    int a = spec.alpha_channel;
    if (a < 0 && (spec.nchannels == 2 || spec.nchannels == 4)) a = spec.nchannels - 1;
    return a >= 0 && a < kMaxReadChannels && a < spec.nchannels ? a : -1;
}

// Channels [0, channels) of every pixel as `type` (T's type). OpenImageIO 2.4 reads directly
// into the caller's buffer only when asked for the file's own format (TypeDesc::UNKNOWN); asked
// for any named format, even the file's, it converts through a scratch buffer of 64 MB whatever
// the image's size. So the pixels are read as the file stores them and converted here. That
// buffer took most of the scene fuzzer's time (under AddressSanitizer each one is mapped,
// poisoned and quarantined) and cost every texture decode a 64 MB allocation.
template <typename T>
std::vector<T> readPixels(OIIO::ImageInput& in, const std::string& name, std::size_t count,
                          int channels, OIIO::TypeDesc type) {
    const OIIO::ImageSpec& spec = in.spec();
    std::vector<T> pixels(count * channels);
    bool ok = false;
    // A value of no size would make the native buffer below too small to read into.
    if (spec.channelformats.empty() && spec.format.size() == 0)
        throw SceneError::inFile(name,
                                 std::string("unsupported pixel format ") + spec.format.c_str());
    if (!spec.channelformats.empty()) {
        // Per-channel formats: OpenImageIO's own conversion is the only one.
        ok = in.read_image(0, 0, 0, channels, type, pixels.data());
    } else if (spec.format == type) {
        ok = in.read_image(0, 0, 0, channels, OIIO::TypeDesc::UNKNOWN, pixels.data());
    } else {
        std::vector<unsigned char> native(pixels.size() * spec.format.size());
        ok = in.read_image(0, 0, 0, channels, OIIO::TypeDesc::UNKNOWN, native.data());
        // convert_pixel_values counts values in an int: convert in slices.
        constexpr std::size_t kSlice = std::size_t(1) << 24;
        for (std::size_t at = 0; ok && at < pixels.size(); at += kSlice) {
            const std::size_t n = std::min(kSlice, pixels.size() - at);
            ok = OIIO::convert_pixel_values(spec.format, native.data() + at * spec.format.size(),
                                            type, pixels.data() + at, static_cast<int>(n));
        }
    }
    if (!ok) throw SceneError::inFile(name, "cannot decode image: " + in.geterror());
    return pixels;
}

// Keeps texture.alpha only when some value is below one.
void finishAlpha(Texture& texture) {
    float least = 1.0f;
    for (float a : texture.alpha) least = std::min(least, a);
    texture.alphaMinimum = least;
    if (least >= 1.0f) std::vector<float>().swap(texture.alpha);
}

// The linear value of each 8-bit code as OpenImageIO converts UINT8 to FLOAT (a data map's
// values, or a colour image the file says is linear).
const std::array<float, 256>& linearTable() {
    static const std::array<float, 256> table = [] {
        std::array<unsigned char, 256> codes{};
        for (int i = 0; i < 256; ++i) codes[i] = static_cast<unsigned char>(i);
        std::array<float, 256> t{};
        OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, codes.data(), OIIO::TypeDesc::FLOAT,
                                   t.data(), 256);
        return t;
    }();
    return table;
}

// An 8-bit image: its codes, three per texel (a grey image's repeated), in Texture's tiles,
// decoded through the table that the float path's conversion would have computed for each code.
void readCodes(OIIO::ImageInput& in, const std::string& name, Texture& texture, int channels,
               int alphaChannel, bool linear) {
    const std::size_t count = static_cast<std::size_t>(texture.width) * texture.height;
    const auto pixels = readPixels<unsigned char>(in, name, count, channels, OIIO::TypeDesc::UINT8);
    texture.table = linear ? &linearTable() : &srgbTable();
    // Tiles pad the image to whole tiles: at most 3.8 times its texels once it is a tile wide
    // and high (33 x 33), 15 bytes a texel against the 12 of floats; narrower, rows.
    const bool tiled = texture.width >= 32 && texture.height >= 32;
    texture.tilesX = tiled ? (texture.width + 31) / 32 : 0;
    texture.codes.assign(
        tiled ? static_cast<std::size_t>(texture.tilesX) * ((texture.height + 31) / 32) * 1024
              : count,
        0u);
    for (std::size_t i = 0; i < count; ++i) {
        const unsigned char* p = &pixels[i * channels];
        const std::uint32_t r = p[0], g = channels < 3 ? r : p[1], b = channels < 3 ? r : p[2];
        const int x = int(i % std::size_t(texture.width)), y = int(i / std::size_t(texture.width));
        texture.codes[texture.codeIndex(x, y)] = r | (g << 8) | (b << 16);
        if (alphaChannel >= 0)
            texture.alpha[i] = static_cast<float>(pixels[i * channels + alphaChannel]) / 255.0f;
    }
}

void readTexels(OIIO::ImageInput& in, const std::string& name, Texture& texture,
                TextureEncoding encoding) {
    const OIIO::ImageSpec& spec = in.spec();
    const bool data = encoding != TextureEncoding::Colour;
    const int alphaChannel = alphaChannelOf(spec);
    const int colours = std::min(spec.nchannels, kColourChannels);
    const int channels = std::max(colours, alphaChannel + 1);
    const std::size_t count = static_cast<std::size_t>(texture.width) * texture.height;
    if (alphaChannel >= 0) texture.alpha.resize(count);
    if (spec.format == OIIO::TypeDesc::UINT8 && spec.channelformats.empty()) {
        // The common case (JPEG, PNG): codes and a table instead of floats.
        readCodes(in, name, texture, channels, alphaChannel, data || isLinear(spec));
    } else {
        texture.texels.resize(count);
        const auto pixels = readPixels<float>(in, name, count, channels, OIIO::TypeDesc::FLOAT);
        const bool linear = data || isLinear(spec);
        for (std::size_t i = 0; i < count; ++i) {
            texture.texels[i] = rgbAt(pixels, i, channels, [&](float c) {
                if (!std::isfinite(c) && texture.firstNonFinite < 0) {
                    texture.firstNonFinite = static_cast<long long>(i);
                    texture.nonFiniteValue = c;
                }
                c = std::isfinite(c) ? std::max(c, 0.0f) : 0.0f;
                return linear ? c : srgbToLinear(c);
            });
            if (alphaChannel >= 0) {
                const float a = pixels[i * channels + alphaChannel];
                texture.alpha[i] = std::isfinite(a) ? std::clamp(a, 0.0f, 1.0f) : 0.0f;
            }
        }
    }
    // A coverage map without an alpha channel (MTL map_d in grey): its grey is the coverage.
    if (alphaChannel < 0 && encoding == TextureEncoding::Coverage) {
        texture.alpha.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::vec3 t = texture.texel(i);
            texture.alpha[i] = std::clamp((t.x + t.y + t.z) / 3.0f, 0.0f, 1.0f);
        }
    }
    finishAlpha(texture);
}

void checkImageSize(const std::string& name, const OIIO::ImageSpec& spec,
                    const TextureLimits& limits) {
    if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSide ||
        spec.height > kMaxTextureSide || spec.nchannels <= 0 || spec.depth > 1) {
        throw SceneError::inFile(
            name, "unsupported image size " + std::to_string(spec.width) + " x " +
                      std::to_string(spec.height) +
                      (spec.depth > 1 ? " x " + std::to_string(spec.depth) : "") + " pixels, " +
                      std::to_string(spec.nchannels) + " channels");
    }
    const std::uint64_t pixels = static_cast<std::uint64_t>(spec.width) * spec.height;
    const std::string size = std::to_string(spec.width) + " x " + std::to_string(spec.height);
    if (pixels > limits.maxPixels) {
        throw SceneError::inFile(name, "image is " + size + " pixels, over the limit of " +
                                           std::to_string(limits.maxPixels) +
                                           " pixels per texture");
    }
    if (limits.scenePixels) {
        if (!limits.scenePixels->fits(pixels))
            throw SceneError::inFile(
                name, "image is " + size + " pixels: " + limits.scenePixels->exceeded(pixels));
        limits.scenePixels->add(pixels);
    }
}

glm::vec3 meanOf(const Texture& texture) {
    const std::size_t n = texture.texelCount();
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < n; ++i) sum += glm::dvec3(texture.texel(i));
    return n == 0 ? glm::vec3(0.0f) : glm::vec3(sum / static_cast<double>(n));
}

glm::vec3 minimumOf(const Texture& texture) {
    const std::size_t n = texture.texelCount();
    glm::vec3 m = n == 0 ? glm::vec3(0.0f) : texture.texel(0);
    for (std::size_t i = 1; i < n; ++i) m = glm::min(m, texture.texel(i));
    return m;
}

}  // namespace

Texture decodeTexture(const std::string& name, const std::string& bytes,
                      const TextureLimits& limits, TextureEncoding encoding) {
    OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
    std::unique_ptr<TempImageFile> temp;
    auto in = openImage(name, bytes, proxy, temp);
    // Only the header has been read: judge the size before allocating for pixels.
    checkImageSize(name, in->spec(), limits);
    const OIIO::ImageSpec& spec = in->spec();
    Texture texture;
    texture.path = name;
    texture.width = spec.width;
    texture.height = spec.height;
    readTexels(*in, name, texture, encoding);
    in->close();
    texture.average = meanOf(texture);
    texture.minimum = minimumOf(texture);
    return texture;
}

std::optional<std::string> locateFile(FileSource& files, const std::string& path) {
    if (files.exists(path)) return path;
    const fs::path p(path);
    const std::string folder = p.parent_path().generic_string();
    const std::string wanted = lower(p.filename().string());
    for (const std::string& name : files.list(folder)) {
        if (lower(name) != wanted) continue;
        std::string found = folder.empty() ? name : folder + "/" + name;
        spdlog::warn("'{}' does not exist; using '{}', whose name differs only in case", path,
                     found);
        return found;
    }
    return std::nullopt;
}

}  // namespace igi
