// igi-codec-bench: how many pixels per second one core quantizes + compresses (a client's
// writeTileChannels) and decompresses + dequantizes (the master's readTileChannels) on a
// synthetic typical IGI tile. Single-threaded, so the figures are per core.
//
// The tile: 32 x 32 pixels of one interleaving cell, the five planes of a diffuse scene (no
// glossy plane: the Cornell box's materials have no Phong lobe), modelled on the tiles of
// the default Cornell scene at 640 x 480 (4.3 bytes/pixel on the wire, of which irradiance 2.9
// and depth 0.9; about 270 zstd sequences per tile): two surfaces, so reflectance and normals
// are piecewise constant or smooth and depth smooth, and a corner of misses; irradiance smooth
// with a VPL's shadow edges and noise in the penumbrae; the unfiltered plane zero except in one
// corner (6 %: a mirror). It comes out at 4.1 bytes/pixel with about 560 zstd sequences, a
// little harder on zstd than the Cornell tiles.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>

#include "ByteReader.h"
#include "ByteWriter.h"
#include "ChannelCodec.h"
#include "Compression.h"

namespace {

using Clock = std::chrono::steady_clock;
using igi::TileChannels;

/// The planes a tile of a scene without glossy materials sends.
constexpr std::uint32_t kDiffusePlanes = igi::kAllChannels & ~igi::kGlossy;

TileChannels typicalTile(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    constexpr int kSide = 32;
    TileChannels c;
    c.resize(kSide * kSide, kDiffusePlanes);
    const float phase = u(rng) * 6.0f;
    for (int i = 0; i < c.count; ++i) {
        const float x = float(i % kSide) / kSide, y = float(i / kSide) / kSide;
        // Two surfaces meet on a diagonal: a flat wall and a curved object in front of it.
        const bool wall = x + 0.5f * y < 0.6f + 0.1f * phase;
        const float smooth = 0.6f + 0.3f * std::sin(3.0f * x + 2.0f * y + phase);
        // A VPL's shadow, and noise where the area light is partly hidden (the penumbrae).
        const float edge = std::sin(9.0f * x + phase);
        const float shadow = edge > 0.6f ? 0.5f : 1.0f;
        const float grain = std::abs(edge - 0.6f) < 0.5f ? noise(rng) : 0.0f;
        c.irradiance[i] = glm::max(glm::vec3(2.0f, 1.8f, 1.5f) * smooth * shadow * (1.0f + grain),
                                   glm::vec3(0.0f));
        c.reflectance[i] = wall ? glm::vec3(0.57f, 0.06f, 0.05f) : glm::vec3(0.7f, 0.68f, 0.6f);
        c.normal[i] = wall ? glm::vec3(1.0f, 0.0f, 0.0f)
                           : glm::normalize(glm::vec3(x - 0.5f, 1.0f, y - 0.4f));
        c.depth[i] = (wall ? 4.0f : 2.5f) + 0.8f * x + 0.3f * y + 0.1f * phase;
        if (x + y > 1.7f) {  // a miss: the background shows in one corner
            c.irradiance[i] = c.reflectance[i] = c.normal[i] = glm::vec3(0.0f);
            c.depth[i] = INFINITY;
        }
        // A mirror in one corner: what it reflects is not filtered.
        if (x >= 0.75f && y < 0.25f)
            c.unfiltered[i] = glm::vec3(1.5f, 1.2f, 1.0f) * smooth * (1.0f + noise(rng));
    }
    return c;
}

std::vector<std::uint8_t> encode(const TileChannels& c) {
    std::vector<std::uint8_t> bytes;
    igi::proto::ByteWriter out(bytes);
    igi::proto::writeTileChannels(out, c);
    return bytes;
}

/// The tile with only the planes of `mask` (the others dropped).
TileChannels onlyPlanes(const TileChannels& c, std::uint32_t mask) {
    TileChannels one;
    one.resize(c.count, mask);
    if (mask & igi::kIrradiance) one.irradiance = c.irradiance;
    if (mask & igi::kReflectance) one.reflectance = c.reflectance;
    if (mask & igi::kNormal) one.normal = c.normal;
    if (mask & igi::kDepth) one.depth = c.depth;
    if (mask & igi::kUnfiltered) one.unfiltered = c.unfiltered;
    return one;
}

/// Bytes per pixel of each plane compressed alone (zstd sees only that plane): how the wire
/// bytes divide among the planes. Compressed together they come out a little smaller.
void printPlaneSizes(const std::vector<TileChannels>& tiles, std::size_t headerBytes) {
    const std::pair<const char*, std::uint32_t> planes[] = {{"irradiance", igi::kIrradiance},
                                                            {"reflectance", igi::kReflectance},
                                                            {"normal", igi::kNormal},
                                                            {"depth", igi::kDepth},
                                                            {"unfiltered", igi::kUnfiltered}};
    std::printf("per plane, compressed alone (bytes/pixel):");
    for (const auto& [name, mask] : planes) {
        std::size_t bytes = 0, pixels = 0;
        for (const auto& t : tiles) {
            bytes += encode(onlyPlanes(t, mask)).size() - headerBytes;
            pixels += std::size_t(t.count);
        }
        std::printf(" %s %.2f (of %u)", name, double(bytes) / double(pixels),
                    igi::proto::bytesPerPixel(mask));
    }
    std::printf("\n");
}

/// Runs `once(i)` for i = 0, 1, ... until `seconds` have passed (checking the clock every
/// `batch` calls) and returns the calls per second.
template <typename F>
double rate(double seconds, int batch, F&& once) {
    const auto start = Clock::now();
    long calls = 0;
    double elapsed = 0.0;
    do {
        for (int k = 0; k < batch; ++k) once(calls + k);
        calls += batch;
        elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < seconds);
    return calls / elapsed;
}

/// The best of `rounds` measurements: the one least disturbed by the rest of the machine.
template <typename F>
double bestRate(int rounds, double seconds, int batch, F&& once) {
    double best = 0.0;
    for (int r = 0; r < rounds; ++r) best = std::max(best, rate(seconds, batch, once));
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"igi-codec-bench: tile channel encode/decode throughput on one core"};
    int tiles = 16, rounds = 5;
    double seconds = 0.4;
    app.add_option("--tiles", tiles, "distinct tiles cycled through")->capture_default_str();
    app.add_option("--rounds", rounds, "measurements per figure (the best is printed)")
        ->capture_default_str();
    app.add_option("--seconds", seconds, "duration of one measurement")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    tiles = std::max(tiles, 1);

    std::vector<TileChannels> inputs;
    std::vector<std::vector<std::uint8_t>> wire;
    std::size_t wireBytes = 0, pixels = 0, zstdBytes = 0;
    for (int t = 0; t < tiles; ++t) {
        inputs.push_back(typicalTile(static_cast<std::uint32_t>(t + 1)));
        wire.push_back(encode(inputs.back()));
        wireBytes += wire.back().size();
        pixels += static_cast<std::size_t>(inputs.back().count);
    }
    // Where the zstd frame starts: count, planes, sent, three references, blob length.
    const std::size_t blobAt = 3 * 4 + 3 * 4;
    const std::uint32_t sent = wire[0][8] | wire[0][9] << 8;
    if (sent != kDiffusePlanes) {
        std::fprintf(stderr, "the synthetic tile should send every plane but glossy (sent 0x%x)\n",
                     sent);
        return 1;
    }
    for (const auto& w : wire) zstdBytes += w.size() - blobAt - 4;
    const double pixelsPerTile = double(pixels) / tiles;
    const std::size_t rawSize = igi::proto::bytesPerPixel(sent) * inputs[0].count;

    volatile float sink = 0.0f;  // keeps the optimizer from dropping the decoded tiles
    const double decodeTiles = bestRate(rounds, seconds, 64, [&](long i) {
        const auto& w = wire[static_cast<std::size_t>(i % tiles)];
        igi::proto::ByteReader in(w, "TileResult");
        const TileChannels c = igi::proto::readTileChannels(in);
        sink = sink + c.depth[7];
    });
    const double encodeTiles = bestRate(rounds, seconds, 16, [&](long i) {
        const auto w = encode(inputs[static_cast<std::size_t>(i % tiles)]);
        sink = sink + w[20];
    });
    // zstd alone, for the share of the decode time that is decompression.
    const double zstdTiles = bestRate(rounds, seconds, 64, [&](long i) {
        const auto& w = wire[static_cast<std::size_t>(i % tiles)];
        const auto raw = igi::proto::zstdDecompressExact(std::span(w).subspan(blobAt + 4), rawSize,
                                                         "TileResult");
        sink = sink + raw[100];
    });

    const double decodePx = decodeTiles * pixelsPerTile, encodePx = encodeTiles * pixelsPerTile;
    std::printf("tile: %.0f pixels, every plane but glossy, %d distinct tiles\n", pixelsPerTile,
                tiles);
    std::printf(
        "size: %.2f bytes/pixel on the wire (zstd frame %.2f, quantized before zstd %u, "
        "as floats 52)\n",
        double(wireBytes) / pixels, double(zstdBytes) / pixels, igi::proto::bytesPerPixel(sent));
    std::printf("decode: %.1f M pixels/s per core (%.1f ns/pixel; zstd alone %.1f ns/pixel)\n",
                decodePx * 1e-6, 1e9 / decodePx, 1e9 / (zstdTiles * pixelsPerTile));
    std::printf("encode: %.1f M pixels/s per core (%.1f ns/pixel)\n", encodePx * 1e-6,
                1e9 / encodePx);
    printPlaneSizes(inputs, blobAt + 4);
    return 0;
}
