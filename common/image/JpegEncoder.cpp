#include "image/JpegEncoder.h"

#include <stdexcept>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "image/ToneMap.h"

namespace igi {

std::string encodeJpeg(const Image& image, float exposureStops, int quality) {
    const std::vector<std::uint8_t> bytes = toneMap8(image, exposureStops);
    std::vector<unsigned char> file;
    OIIO::Filesystem::IOVecOutput memory(file);
    // The name only tells OpenImageIO which format; nothing is written to disk.
    auto out = OIIO::ImageOutput::create("view.jpg");
    if (!out) throw std::runtime_error("JPEG encoder: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Compression", "jpeg:" + std::to_string(quality));
    void* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open("view.jpg", spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) ||
        !out->close())
        throw std::runtime_error("JPEG encoder: " + out->geterror());
    return std::string(file.begin(), file.end());
}

}  // namespace igi
