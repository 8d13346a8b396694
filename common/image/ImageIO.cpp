#include "image/ImageIO.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "image/ToneMap.h"

namespace igi {
namespace {

// Writes `data` (of type `dataType`) into a file of the layout and format `spec` describes;
// OpenImageIO converts between the two.
void writeWith(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
               OIIO::TypeDesc dataType, const void* data) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(path.string() + ": cannot write: " + OIIO::geterror());
    if (!out->open(path.string(), spec) || !out->write_image(dataType, data) || !out->close())
        throw std::runtime_error(path.string() + ": cannot write: " + out->geterror());
}

}  // namespace

void writeImage(const std::filesystem::path& path, const Image& image, float exposure) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    const std::string ext = path.extension().string();
    if (ext == ".png") {
        const std::vector<std::uint8_t> bytes = toneMap8(image, exposure);
        writeWith(path, OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8),
                  OIIO::TypeDesc::UINT8, bytes.data());
    } else if (ext == ".exr") {
        // Full float: half floats overflow to infinity above 65504, and bright scenes exceed that.
        OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        writeWith(path, spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
    } else {
        throw std::runtime_error(path.string() + ": unsupported output format (use .png or .exr)");
    }
}

Image readImage(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw std::runtime_error(path.string() + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> data(std::size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
        throw std::runtime_error(path.string() + ": cannot read image: " + in->geterror());
    const bool srgb = spec.format == OIIO::TypeDesc::UINT8;
    Image image(spec.width, spec.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
            image.pixels[i][c] = srgb ? srgbToLinear(v) : v;
        }
    }
    return image;
}

}  // namespace igi
