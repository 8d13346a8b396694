#include "CodedFrame.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <mutex>
#include <string>

#include "ChannelCodec.h"
#include "ProtocolError.h"
#include "Quantize.h"

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace igi::proto {
namespace {

using namespace lanes;
using R = FrameRow;

/// Where each plane's bytes start among the frame's byte planes (wire order), how many it
/// has and the byte of its empty code (zero; depth: kDepthInfinite).
struct PlaneBytes {
    Channel channel;
    int first;
    int count;
    std::uint8_t empty;
};
constexpr PlaneBytes kPlanes[] = {
    {kIrradiance, 0, int(kIrradianceBytes), 0},  {kReflectance, 4, int(kReflectanceBytes), 0},
    {kNormal, 7, int(kNormalBytes), 0},          {kDepth, 9, int(kDepthBytes), 0xFF},
    {kUnfiltered, 11, int(kUnfilteredBytes), 0}, {kGlossy, 15, int(kGlossyBytes), 0},
};
constexpr int kBytePlanes = 19;
static_assert(kBytePlanes == CodedFrame::kBytesPerPixel);
// Bytes after each plane that eight-lane loads past a run's end may read.
constexpr std::size_t kPadding = 64;

std::mutex& lifeMutex() {
    static std::mutex m;
    return m;
}

/// A shared-exponent plane's run of `count` pixels to floats. When the tile's scale keeps every
/// step scale * 2^(e - 39) a normal float, the float product of mantissa and step rounds the
/// same exact product once, as the decoder's double arithmetic does (Quantize.cpp); eight
/// lanes at a time, writing up to seven entries past the run. Otherwise the per-value decoder.
IGI_LANES void sharedExponentRun(const std::uint8_t* b, std::size_t stride, int count, float scale,
                                 float* r, float* g, float* bl) {
    if (scale >= 0x1p-87f && scale <= FLT_MAX) {
        const F8 s = splat(scale);
        const U8 mantissa = U8{} + 511u;
        for (int j = 0; j < count; j += kWidth) {
            const U8 w = loadBytes(b + j) | loadBytes(b + stride + j) << 8 |
                         loadBytes(b + 2 * stride + j) << 16 | loadBytes(b + 3 * stride + j) << 24;
            // 2^(e - 39), e = w >> 27, as the bits of a float: biased exponent e - 39 + 127.
            const F8 step = s * (F8)(((w >> 27) + (127u - kSharedExponentStepShift)) << 23);
            store(r + j, __builtin_convertvector((I8)(w & mantissa), F8) * step);
            store(g + j, __builtin_convertvector((I8)((w >> 9) & mantissa), F8) * step);
            store(bl + j, __builtin_convertvector((I8)((w >> 18) & mantissa), F8) * step);
        }
        return;
    }
    for (int j = 0; j < count; ++j) {
        const std::uint32_t w = b[j] | std::uint32_t{b[stride + j]} << 8 |
                                std::uint32_t{b[2 * stride + j]} << 16 |
                                std::uint32_t{b[3 * stride + j]} << 24;
        const glm::vec3 v = decodeSharedExponent(w, scale);
        r[j] = v.x, g[j] = v.y, bl[j] = v.z;
    }
}

IGI_LANES void srgbRun(const std::uint8_t* b, std::size_t stride, int count, const float* table,
                       float* r, float* g, float* bl) {
    for (int j = 0; j < count; ++j) {
        r[j] = table[b[j]];
        g[j] = table[b[stride + j]];
        bl[j] = table[b[2 * stride + j]];
    }
}

IGI_LANES void normalRun(const std::uint8_t* b, std::size_t stride, int count,
                         const glm::vec3* table, float* x, float* y, float* z) {
    for (int j = 0; j < count; ++j) {
        const glm::vec3 n = table[b[j] | b[stride + j] << 8];
        x[j] = n.x, y[j] = n.y, z[j] = n.z;
    }
}

IGI_LANES void depthRun(const std::uint8_t* b, std::size_t stride, int count, float d0,
                        const double* factors, float* depth) {
    const double reference = d0;
    for (int j = 0; j < count; ++j) {
        const std::uint32_t code = b[j] | std::uint32_t{b[stride + j]} << 8;
        const float d = static_cast<float>(reference * factors[code]);
        depth[j] = code == kDepthInfinite ? INFINITY : d;
    }
}

void fill(FrameRow& row, int plane, int planes, int width, float value) {
    for (int k = 0; k < planes; ++k) std::fill_n(row[plane + k], width, value);
}

}  // namespace

CodedFrame& CodedFrame::operator=(CodedFrame&& o) noexcept {
    width_ = o.width_, height_ = o.height_, n_ = o.n_, m_ = o.m_, tileSize_ = o.tileSize_;
    regionsX_ = o.regionsX_, regionsY_ = o.regionsY_;
    order_ = std::move(o.order_);
    planeStride_ = o.planeStride_;
    bytes_ = std::move(o.bytes_);
    scales_ = std::move(o.scales_);
    live_ = o.live_.load();
    o.width_ = o.height_ = 0;
    o.planeStride_ = 0;
    o.live_ = 0;
    return *this;
}

void CodedFrame::reuse(int width, int height, int n, int m, int tileSize) {
    if (bytes_ && width == width_ && height == height_ && n == n_ && m == m_ &&
        tileSize == tileSize_)
        return;
    width_ = width, height_ = height, n_ = n, m_ = m, tileSize_ = tileSize;
    regionsX_ = (width + n * tileSize - 1) / (n * tileSize);
    regionsY_ = (height + m * tileSize - 1) / (m * tileSize);
    order_ = CellOrder(width, n);
    // Each plane starts three cache lines further off a 4 KB boundary than the one before, so
    // that the same pixel of the 19 planes does not fall into one cache set.
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    planeStride_ = (pixels + kPadding + 4095) / 4096 * 4096 + 192;
    // Not cleared: a plane is filled with its empty code when it comes to life, and pages of
    // planes that never do are never touched.
    bytes_.reset(new std::uint8_t[planeStride_ * kBytePlanes]);
    for (int b = 0; b < kBytePlanes; ++b) std::memset(bytePlane(b) + pixels, 0, kPadding);
    scales_.assign(std::size_t(n) * m * regionsX_ * regionsY_, Scales{});
    live_ = 0;
}

std::size_t CodedFrame::slot(int kx, int ky, int regionX, int regionY) const {
    return ((std::size_t(ky) * n_ + kx) * regionsY_ + regionY) * regionsX_ + regionX;
}

void CodedFrame::bringToLife(Channel c) {
    if (live(c)) return;
    std::lock_guard lock(lifeMutex());
    if (live(c)) return;
    const std::size_t pixels = std::size_t(width_) * std::size_t(height_);
    for (const PlaneBytes& p : kPlanes)
        if (p.channel == c)
            for (int b = 0; b < p.count; ++b) std::memset(bytePlane(p.first + b), p.empty, pixels);
    // Released after the fill: a thread that sees the bit writes its empties after it.
    live_.fetch_or(c, std::memory_order_release);
}

void CodedFrame::scatter(const Tile& tile, const TileCodes& codes) {
    const int columns = tile.columns(n_), rows = tile.rows(m_);
    if (codes.count != std::uint32_t(tile.pixelCount(n_, m_)))
        throw ProtocolError("a result with " + std::to_string(codes.count) +
                            " pixels for a tile of " + std::to_string(tile.pixelCount(n_, m_)));
    if (columns == 0 || rows == 0) return;
    const std::size_t run = std::size_t(order_.start(tile.kx) + tile.x0 / n_);
    const std::size_t count = codes.count;
    for (const PlaneBytes& p : kPlanes) {
        const std::uint8_t* source = codes.bytes(p.channel);
        if (source) {
            bringToLife(p.channel);
        } else if (!live(p.channel)) {
            continue;  // empty in the whole frame already
        }
        for (int b = 0; b < p.count; ++b) {
            std::uint8_t* plane = bytePlane(p.first + b);
            for (int r = 0; r < rows; ++r) {
                const int y = tile.y0 + tile.ky + r * m_;
                std::uint8_t* out = plane + std::size_t(y) * std::size_t(width_) + run;
                if (source)
                    std::memcpy(out, source + b * count + std::size_t(r) * columns, columns);
                else
                    std::memset(out, p.empty, std::size_t(columns));
            }
        }
    }
    Scales& s =
        scales_[slot(tile.kx, tile.ky, tile.x0 / (n_ * tileSize_), tile.y0 / (m_ * tileSize_))];
    s.irradiance = codes.sent & kIrradiance ? codes.irradianceScale : 1.0f;
    s.depth = codes.sent & kDepth ? codes.depthMin : 1.0f;
    s.unfiltered = codes.sent & kUnfiltered ? codes.unfilteredScale : 1.0f;
    s.glossy = codes.sent & kGlossy ? codes.glossyScale : 1.0f;
}

void CodedFrame::decodeRowBody(int y, FrameRow& row) const {
    const int ky = y % m_, regionY = y / (m_ * tileSize_);
    const std::size_t stride = planeStride_, base = std::size_t(y) * std::size_t(width_);
    const bool irradiance = live(kIrradiance), reflectance = live(kReflectance),
               normal = live(kNormal), depth = live(kDepth), unfiltered = live(kUnfiltered),
               glossy = live(kGlossy);
    if (!irradiance) fill(row, R::kEr, 3, width_, 0.0f);
    if (!reflectance) fill(row, R::kRr, 3, width_, 0.0f);
    if (!normal) fill(row, R::kNx, 3, width_, 0.0f);
    if (!depth) fill(row, R::kDepth, 1, width_, INFINITY);
    if (!unfiltered) fill(row, R::kUr, 3, width_, 0.0f);
    const float* srgb = srgbDecodeValues();
    const glm::vec3* normals = octNormalValues();
    const double* factors = logDepthFactors();
    // Run by run (one tile's row each), in increasing position: a run may write past its end,
    // which the next run then overwrites.
    for (int kx = 0; kx < n_; ++kx) {
        for (int regionX = 0; regionX < regionsX_; ++regionX) {
            const int first = order_.start(kx) + regionX * tileSize_;
            const int count = std::min(tileSize_, order_.count(kx) - regionX * tileSize_);
            if (count <= 0) break;
            const Scales& s = scales_[slot(kx, ky, regionX, regionY)];
            const std::uint8_t* at = bytes_.get() + base + std::size_t(first);
            auto plane = [&](int p) { return row[p] + first; };
            if (irradiance)
                sharedExponentRun(at, stride, count, s.irradiance, plane(R::kEr), plane(R::kEg),
                                  plane(R::kEb));
            if (reflectance)
                srgbRun(at + 4 * stride, stride, count, srgb, plane(R::kRr), plane(R::kRg),
                        plane(R::kRb));
            if (normal)
                normalRun(at + 7 * stride, stride, count, normals, plane(R::kNx), plane(R::kNy),
                          plane(R::kNz));
            if (depth) depthRun(at + 9 * stride, stride, count, s.depth, factors, plane(R::kDepth));
            if (unfiltered)
                sharedExponentRun(at + 11 * stride, stride, count, s.unfiltered, plane(R::kUr),
                                  plane(R::kUg), plane(R::kUb));
            if (glossy)
                sharedExponentRun(at + 15 * stride, stride, count, s.glossy, plane(R::kGr),
                                  plane(R::kGg), plane(R::kGb));
        }
    }
}

void CodedFrame::decodeRowBaseline(int y, FrameRow& row) const {
    decodeRowBody(y, row);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void CodedFrame::decodeRowAvx2(int y, FrameRow& row) const {
    decodeRowBody(y, row);
}
#endif

void CodedFrame::decodeRow(int y, FrameRow& row, Isa isa) const {
    row.resize(width_);
    row.y = y;
#if IGI_HAS_AVX2_TARGET
    if (isa == Isa::kAvx2) return decodeRowAvx2(y, row);
#endif
    decodeRowBaseline(y, row);
}

}  // namespace igi::proto
