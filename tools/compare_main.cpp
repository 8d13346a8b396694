// igi-compare: how far an image is from a reference (relative MSE, RMSE, bias, SSIM, speckle),
// as JSON.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "image/ImageCompare.h"
#include "image/ImageIO.h"

namespace {

// Where an image is brighter or darker than the reference: one number per block.
void printRatioMap(const igi::Image& a, const igi::Image& r, int size) {
    for (int y0 = 0; y0 < a.height; y0 += size) {
        for (int x0 = 0; x0 < a.width; x0 += size) {
            double sa = 0, sr = 0;
            for (int y = y0; y < std::min(a.height, y0 + size); ++y)
                for (int x = x0; x < std::min(a.width, x0 + size); ++x) {
                    sa += a.at(x, y).x + a.at(x, y).y + a.at(x, y).z;
                    sr += r.at(x, y).x + r.at(x, y).y + r.at(x, y).z;
                }
            if (sr > 1e-4 * size * size)
                std::fprintf(stderr, " %5.2f", sa / sr);
            else
                std::fprintf(stderr, "   -  ");
        }
        std::fprintf(stderr, "\n");
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-compare: compares an image with a reference and prints the errors as JSON"};
    std::string image, reference;
    int block = 8;
    float exposure = 0;
    app.add_option("image", image, "the image to judge (.exr for linear values)")->required();
    app.add_option("reference", reference, "the reference image")->required();
    app.add_option("--block", block, "block size for the block relative error")
        ->capture_default_str();
    app.add_option("--exposure", exposure, "stops applied before tone mapping for SSIM")
        ->capture_default_str();
    int ratioBlocks = 0;
    app.add_option(
        "--ratio-blocks", ratioBlocks,
        "also print to stderr the map of mean(image) / mean(reference) over blocks of this size");
    CLI11_PARSE(app, argc, argv);
    try {
        const igi::Image a = igi::readImage(image), r = igi::readImage(reference);
        const igi::ImageDifference d = igi::compareImages(a, r, block, exposure);
        if (ratioBlocks > 0) printRatioMap(a, r, ratioBlocks);
        nlohmann::json out{{"image", image},
                           {"reference", reference},
                           {"relative_mse", d.relativeMse},
                           {"rmse", d.rmse},
                           {"mean_relative_bias", d.meanRelativeBias},
                           {"block_relative_error", d.blockRelativeError},
                           {"ssim", d.ssim},
                           {"speckle", d.speckle}};
        std::cout << out.dump(2) << '\n';
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "igi-compare: " << e.what() << '\n';
        return 1;
    }
}
