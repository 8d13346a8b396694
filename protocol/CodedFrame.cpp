#include "CodedFrame.h"

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "ChannelCodec.h"
#include "ProtocolError.h"
#include "Quantize.h"

#if IGI_HAS_AVX2_TARGET
#include <immintrin.h>
#endif

#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#if defined(__GNUC__) && !defined(__clang__)
// GCC 12's own _mm256_i32gather_pd starts from _mm256_undefined_pd(), which it then warns of.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace igi::proto {
namespace {

using namespace lanes;
using R = FrameRow;

// Bytes after each byte plane that eight-lane loads past a run's end may read.
constexpr std::size_t kPadding = 64;

/// The first of each channel's byte planes (wire order), in Channel bit order.
constexpr int kFirstBytePlane[6] = {0, 4, 7, 9, 11, 15};
constexpr int kBytePlanes = 19;
static_assert(kBytePlanes == CodedFrame::kBytesPerPixel);

int bitIndex(Channel c) {
    return std::countr_zero(static_cast<std::uint32_t>(c));
}

/// The bytes of a channel per pixel (ChannelCodec.h).
constexpr std::uint32_t kChannelBytes[6] = {kIrradianceBytes, kReflectanceBytes, kNormalBytes,
                                            kDepthBytes,      kUnfilteredBytes,  kGlossyBytes};

/// A tile decompresses into this thread's buffer before its runs are copied out.
std::vector<std::uint8_t>& threadPlanes() {
    thread_local std::vector<std::uint8_t> planes;
    return planes;
}

/// memcpy for the short runs of a tile's row (a tile is 32 pixels wide by default): whole
/// 16-byte chunks, the last one overlapping, inlined instead of a library call per run.
void copyRun(std::uint8_t* out, const std::uint8_t* in, std::size_t n) {
    if (n < 16) {
        std::memcpy(out, in, n);
        return;
    }
    for (std::size_t i = 0; i + 16 < n; i += 16) std::memcpy(out + i, in + i, 16);
    std::memcpy(out + n - 16, in + n - 16, 16);
}

/// Whether every step scale * 2^(e - 39) of a tile's shared exponents is a normal float: then
/// the float product of mantissa and step rounds the same exact product once, as the decoder's
/// double arithmetic does (Quantize.cpp).
bool floatSteps(float scale) {
    return scale >= 0x1p-87f && scale <= FLT_MAX;
}

/// A shared-exponent plane's run of `count` pixels to floats, one at a time by the per-value
/// decoder.
void sharedExponentRunOneByOne(const std::uint8_t* b, std::size_t stride, int count, float scale,
                               float* r, float* g, float* bl) {
    for (int j = 0; j < count; ++j) {
        const std::uint32_t w = b[j] | std::uint32_t{b[stride + j]} << 8 |
                                std::uint32_t{b[2 * stride + j]} << 16 |
                                std::uint32_t{b[3 * stride + j]} << 24;
        const glm::vec3 v = decodeSharedExponent(w, scale);
        r[j] = v.x, g[j] = v.y, bl[j] = v.z;
    }
}

/// The same four lanes at a time (SSE2), writing up to three entries past the run, when the
/// steps are floats.
void sharedExponentRun(const std::uint8_t* b, std::size_t stride, int count, float scale, float* r,
                       float* g, float* bl) {
    if (!floatSteps(scale)) return sharedExponentRunOneByOne(b, stride, count, scale, r, g, bl);
    const F4 s = splat<F4>(scale);
    const U4 mantissa = U4{} + 511u;
    for (int j = 0; j < count; j += 4) {
        const U4 w = loadBytes4(b + j) | loadBytes4(b + stride + j) << 8 |
                     loadBytes4(b + 2 * stride + j) << 16 | loadBytes4(b + 3 * stride + j) << 24;
        // 2^(e - 39), e = w >> 27, as the bits of a float: biased exponent e - 39 + 127.
        const F4 step = s * (F4)(((w >> 27) + (127u - kSharedExponentStepShift)) << 23);
        store(r + j, __builtin_convertvector((I4)(w & mantissa), F4) * step);
        store(g + j, __builtin_convertvector((I4)((w >> 9) & mantissa), F4) * step);
        store(bl + j, __builtin_convertvector((I4)((w >> 18) & mantissa), F4) * step);
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

#if IGI_HAS_AVX2_TARGET
// The table planes with AVX2's gathers, eight lanes at a time (writing up to seven entries
// past the run, as sharedExponentRun): the same table entries and the same double product as
// the loops above.

IGI_AVX2 inline __m256i bytesAt(const std::uint8_t* p) {
    return _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)));
}

IGI_AVX2 void sharedExponentRunAvx2(const std::uint8_t* b, std::size_t stride, int count,
                                    float scale, float* r, float* g, float* bl) {
    if (!floatSteps(scale)) return sharedExponentRunOneByOne(b, stride, count, scale, r, g, bl);
    const __m256 s = _mm256_set1_ps(scale);
    const __m256i mantissa = _mm256_set1_epi32(511);
    const __m256i bias = _mm256_set1_epi32(127 - kSharedExponentStepShift);
    for (int j = 0; j < count; j += 8) {
        const __m256i w = _mm256_or_si256(
            _mm256_or_si256(bytesAt(b + j), _mm256_slli_epi32(bytesAt(b + stride + j), 8)),
            _mm256_or_si256(_mm256_slli_epi32(bytesAt(b + 2 * stride + j), 16),
                            _mm256_slli_epi32(bytesAt(b + 3 * stride + j), 24)));
        const __m256 step =
            _mm256_mul_ps(s, _mm256_castsi256_ps(_mm256_slli_epi32(
                                 _mm256_add_epi32(_mm256_srli_epi32(w, 27), bias), 23)));
        // Mantissas are 9 bits: the int-to-float conversion is exact, one rounding in the product.
        const __m256i m0 = _mm256_and_si256(w, mantissa);
        const __m256i m1 = _mm256_and_si256(_mm256_srli_epi32(w, 9), mantissa);
        const __m256i m2 = _mm256_and_si256(_mm256_srli_epi32(w, 18), mantissa);
        _mm256_storeu_ps(r + j, _mm256_mul_ps(_mm256_cvtepi32_ps(m0), step));
        _mm256_storeu_ps(g + j, _mm256_mul_ps(_mm256_cvtepi32_ps(m1), step));
        _mm256_storeu_ps(bl + j, _mm256_mul_ps(_mm256_cvtepi32_ps(m2), step));
    }
}

/// Whether the eight codes are all the same (a flat surface's albedo or normal): then one
/// table entry serves them, without a gather.
IGI_AVX2 inline bool uniform(__m256i code) {
    const __m256i first = _mm256_broadcastd_epi32(_mm256_castsi256_si128(code));
    return _mm256_movemask_epi8(_mm256_cmpeq_epi32(code, first)) == -1;
}

IGI_AVX2 inline __m256 lookUp(const float* table, __m256i code) {
    if (uniform(code)) return _mm256_set1_ps(table[_mm256_cvtsi256_si32(code)]);
    return _mm256_i32gather_ps(table, code, 4);
}

IGI_AVX2 void srgbRunAvx2(const std::uint8_t* b, std::size_t stride, int count, const float* table,
                          float* r, float* g, float* bl) {
    for (int j = 0; j < count; j += 8) {
        _mm256_storeu_ps(r + j, lookUp(table, bytesAt(b + j)));
        _mm256_storeu_ps(g + j, lookUp(table, bytesAt(b + stride + j)));
        _mm256_storeu_ps(bl + j, lookUp(table, bytesAt(b + 2 * stride + j)));
    }
}

IGI_AVX2 void normalRunAvx2(const std::uint8_t* b, std::size_t stride, int count,
                            const glm::vec3* table, float* x, float* y, float* z) {
    const float* base = &table->x;
    for (int j = 0; j < count; j += 8) {
        const __m256i code =
            _mm256_or_si256(bytesAt(b + j), _mm256_slli_epi32(bytesAt(b + stride + j), 8));
        if (uniform(code)) {
            const glm::vec3 n = table[_mm256_cvtsi256_si32(code)];
            _mm256_storeu_ps(x + j, _mm256_set1_ps(n.x));
            _mm256_storeu_ps(y + j, _mm256_set1_ps(n.y));
            _mm256_storeu_ps(z + j, _mm256_set1_ps(n.z));
            continue;
        }
        const __m256i at = _mm256_add_epi32(code, _mm256_slli_epi32(code, 1));  // 3 floats each
        _mm256_storeu_ps(x + j, _mm256_i32gather_ps(base, at, 4));
        _mm256_storeu_ps(y + j, _mm256_i32gather_ps(base + 1, at, 4));
        _mm256_storeu_ps(z + j, _mm256_i32gather_ps(base + 2, at, 4));
    }
}

/// The factors of four codes: from the first octave times 2^octave when that is exact
/// (logDepthOctaveFactors), else from the full table.
IGI_AVX2 inline __m256d depthFactors(__m128i code, const double* octave, const double* full) {
    if (!octave) return _mm256_i32gather_pd(full, code, 8);
    const __m128i fraction = _mm_and_si128(code, _mm_set1_epi32(2047));
    const __m256i exponent =
        _mm256_add_epi64(_mm256_cvtepu32_epi64(_mm_srli_epi32(code, 11)), _mm256_set1_epi64x(1023));
    return _mm256_mul_pd(_mm256_i32gather_pd(octave, fraction, 8),
                         _mm256_castsi256_pd(_mm256_slli_epi64(exponent, 52)));
}

IGI_AVX2 void depthRunAvx2(const std::uint8_t* b, std::size_t stride, int count, float d0,
                           const double* octave, const double* full, float* depth) {
    const __m256d reference = _mm256_set1_pd(d0);
    const __m256i infinite = _mm256_set1_epi32(kDepthInfinite);
    for (int j = 0; j < count; j += 8) {
        const __m256i code =
            _mm256_or_si256(bytesAt(b + j), _mm256_slli_epi32(bytesAt(b + stride + j), 8));
        const __m128 low = _mm256_cvtpd_ps(
            _mm256_mul_pd(reference, depthFactors(_mm256_castsi256_si128(code), octave, full)));
        const __m128 high = _mm256_cvtpd_ps(_mm256_mul_pd(
            reference, depthFactors(_mm256_extracti128_si256(code, 1), octave, full)));
        const __m256 d = _mm256_insertf128_ps(_mm256_castps128_ps256(low), high, 1);
        const __m256 miss = _mm256_castsi256_ps(_mm256_cmpeq_epi32(code, infinite));
        _mm256_storeu_ps(depth + j, _mm256_blendv_ps(d, _mm256_set1_ps(INFINITY), miss));
    }
}
#endif

void fill(FrameRow& row, int plane, int planes, int first, int count, float value) {
    for (int k = 0; k < planes; ++k) std::fill_n(row[plane + k] + first, count, value);
}

}  // namespace

CodedFrame& CodedFrame::operator=(CodedFrame&& o) noexcept {
    width_ = o.width_, height_ = o.height_, n_ = o.n_, m_ = o.m_, tileSize_ = o.tileSize_;
    regionsX_ = o.regionsX_, regionsY_ = o.regionsY_;
    order_ = std::move(o.order_);
    planeBytes_ = o.planeBytes_, planeStride_ = o.planeStride_;
    bytes_ = std::move(o.bytes_);
    records_ = std::move(o.records_);
    live_ = o.live_.load();
    o.width_ = o.height_ = 0;
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
    planeBytes_ = (std::size_t(width) + 15) / 16 * 16;
    // Each plane starts three cache lines further off a 4 KB boundary than the one before, so
    // that the same pixel of the 19 planes does not fall into one cache set.
    planeStride_ = (planeBytes_ * height + kPadding + 4095) / 4096 * 4096 + 192;
    // Zeroed once, so that loads past a run's end read defined bytes.
    bytes_.reset(new std::uint8_t[planeStride_ * kBytePlanes]());
    records_.assign(std::size_t(n) * m * regionsX_ * regionsY_, TileRecord{});
    live_ = 0;
}

std::size_t CodedFrame::slot(int kx, int ky, int regionX, int regionY) const {
    return ((std::size_t(ky) * n_ + kx) * regionsY_ + regionY) * regionsX_ + regionX;
}

void CodedFrame::scatter(const Tile& tile, const TileCodes& codes, std::string_view what) {
    if (codes.count != std::uint32_t(tile.pixelCount(n_, m_)))
        throw ProtocolError(std::string(what) + ": a result with " + std::to_string(codes.count) +
                            " pixels for a tile of " + std::to_string(tile.pixelCount(n_, m_)));
    std::vector<std::uint8_t>& planes = threadPlanes();
    planes.resize(codes.rawSize());
    const int columns = tile.columns(n_), rows = tile.rows(m_);
    const std::size_t run = std::size_t(order_.start(tile.kx) + tile.x0 / n_);
    // The sent byte planes: where each comes from and goes to. Planes the tile did not send
    // are not written: its record says so, and decodeRow makes them empty.
    struct BytePlane {
        const std::uint8_t* in;
        std::uint8_t* out;  // at the tile's first row
    } sent[kBytePlanes];
    int count = 0;
    const int y0 = tile.y0 + tile.ky;
    for (Channel c : {kIrradiance, kReflectance, kNormal, kDepth, kUnfiltered, kGlossy}) {
        if (!(codes.sent & c)) continue;
        const int i = bitIndex(c);
        for (std::uint32_t b = 0; b < kChannelBytes[i]; ++b)
            sent[count++] = {planes.data() + codes.planeOffset(c) + b * codes.count,
                             bytes(y0, kFirstBytePlane[i] + int(b)) + run};
    }
    // The lines the runs will write are rarely in the cache (a frame is written once): asked
    // for now, they arrive while zstd decompresses the tile.
    const std::size_t rowStep = std::size_t(m_) * planeBytes_;
    for (int r = 0; r < rows; ++r)
        for (int k = 0; k < count; ++k) {
            const std::uint8_t* at = sent[k].out + r * rowStep;
            __builtin_prefetch(at, 1, 2);
            if ((reinterpret_cast<std::uintptr_t>(at) & 63) + std::size_t(columns) > 64)
                __builtin_prefetch(at + columns - 1, 1, 2);
        }
    decompressPlanes(codes, planes, what);
    // Row by row of the tile, a run per byte plane.
    for (int r = 0; r < rows; ++r) {
        for (int k = 0; k < count; ++k)
            copyRun(sent[k].out + r * rowStep, sent[k].in + std::size_t(r) * columns,
                    std::size_t(columns));
    }
    if (planes.capacity() > (std::size_t{1} << 20)) std::vector<std::uint8_t>().swap(planes);
    TileRecord& t =
        records_[slot(tile.kx, tile.ky, tile.x0 / (n_ * tileSize_), tile.y0 / (m_ * tileSize_))];
    t.sent = codes.sent;
    t.irradiance = codes.sent & kIrradiance ? codes.irradianceScale : 1.0f;
    t.depth = codes.sent & kDepth ? codes.depthMin : 1.0f;
    t.unfiltered = codes.sent & kUnfiltered ? codes.unfilteredScale : 1.0f;
    t.glossy = codes.sent & kGlossy ? codes.glossyScale : 1.0f;
    live_.fetch_or(codes.sent, std::memory_order_relaxed);
}

void CodedFrame::copyRegion(const CodedFrame& from, const Tile& region) {
    if (from.width_ != width_ || from.height_ != height_ || from.n_ != n_ || from.m_ != m_ ||
        from.tileSize_ != tileSize_)
        throw std::logic_error("CodedFrame::copyRegion from a frame of another shape");
    const int regionX = region.x0 / (n_ * tileSize_), regionY = region.y0 / (m_ * tileSize_);
    for (int y = region.y0; y < std::min(height_, region.y0 + region.height); ++y)
        for (int kx = 0; kx < n_; ++kx) {
            const Tile cell{region.x0, region.y0, region.width, region.height, kx, 0};
            const std::size_t run = std::size_t(order_.start(kx) + region.x0 / n_);
            const std::size_t columns = std::size_t(std::max(0, cell.columns(n_)));
            for (int b = 0; b < kBytePlanes; ++b)
                std::memcpy(bytes(y, b) + run, from.bytes(y, b) + run, columns);
        }
    // The planes the copied tiles sent are live here too, as if they had been scattered here.
    std::uint32_t sent = 0;
    for (int ky = 0; ky < m_; ++ky)
        for (int kx = 0; kx < n_; ++kx) {
            const TileRecord& record = from.records_[slot(kx, ky, regionX, regionY)];
            records_[slot(kx, ky, regionX, regionY)] = record;
            sent |= record.sent;
        }
    live_.fetch_or(sent, std::memory_order_relaxed);
}

template <bool Avx2>
void CodedFrame::decodeRowBody(int y, FrameRow& row) const {
    const int ky = y % m_, regionY = y / (m_ * tileSize_);
    const bool glossy = live(kGlossy);
    const float* srgb = srgbDecodeValues();
    const glm::vec3* normals = octNormalValues();
    const double* factors = logDepthFactors();
    [[maybe_unused]] const double* octave = logDepthOctaveFactors();
    const std::size_t stride = planeStride_;  // between a channel's bytes 0, 1, ...
    // Run by run (one tile's row each), in increasing position: a run may write past its end,
    // which the next run then overwrites.
    for (int kx = 0; kx < n_; ++kx) {
        for (int regionX = 0; regionX < regionsX_; ++regionX) {
            const int first = order_.start(kx) + regionX * tileSize_;
            const int count = std::min(tileSize_, order_.count(kx) - regionX * tileSize_);
            if (count <= 0) break;
            const TileRecord& t = records_[slot(kx, ky, regionX, regionY)];
            auto at = [&](Channel c) { return bytes(y, kFirstBytePlane[bitIndex(c)]) + first; };
            auto plane = [&](int p) { return row[p] + first; };
            // The shared-exponent planes: irradiance, unfiltered and glossy.
            auto sharedExponents = [&](Channel c, float scale, int p) {
                if (!(t.sent & c)) return fill(row, p, 3, first, count, 0.0f);
#if IGI_HAS_AVX2_TARGET
                if constexpr (Avx2)
                    return sharedExponentRunAvx2(at(c), stride, count, scale, plane(p),
                                                 plane(p + 1), plane(p + 2));
#endif
                sharedExponentRun(at(c), stride, count, scale, plane(p), plane(p + 1),
                                  plane(p + 2));
            };
            sharedExponents(kIrradiance, t.irradiance, R::kEr);
            sharedExponents(kUnfiltered, t.unfiltered, R::kUr);
            if (glossy) sharedExponents(kGlossy, t.glossy, R::kGr);
            if (!(t.sent & kReflectance)) fill(row, R::kRr, 3, first, count, 0.0f);
            if (!(t.sent & kNormal)) fill(row, R::kNx, 3, first, count, 0.0f);
            if (!(t.sent & kDepth)) fill(row, R::kDepth, 1, first, count, INFINITY);
            const bool reflectance = t.sent & kReflectance, normal = t.sent & kNormal,
                       depth = t.sent & kDepth;
#if IGI_HAS_AVX2_TARGET
            if constexpr (Avx2) {
                if (reflectance)
                    srgbRunAvx2(at(kReflectance), stride, count, srgb, plane(R::kRr), plane(R::kRg),
                                plane(R::kRb));
                if (normal)
                    normalRunAvx2(at(kNormal), stride, count, normals, plane(R::kNx), plane(R::kNy),
                                  plane(R::kNz));
                if (depth)
                    depthRunAvx2(at(kDepth), stride, count, t.depth, octave, factors,
                                 plane(R::kDepth));
                continue;
            }
#endif
            if (reflectance)
                srgbRun(at(kReflectance), stride, count, srgb, plane(R::kRr), plane(R::kRg),
                        plane(R::kRb));
            if (normal)
                normalRun(at(kNormal), stride, count, normals, plane(R::kNx), plane(R::kNy),
                          plane(R::kNz));
            if (depth) depthRun(at(kDepth), stride, count, t.depth, factors, plane(R::kDepth));
        }
    }
}

void CodedFrame::decodeRowBaseline(int y, FrameRow& row) const {
    decodeRowBody<false>(y, row);
}

#if IGI_HAS_AVX2_TARGET
IGI_AVX2 void CodedFrame::decodeRowAvx2(int y, FrameRow& row) const {
    decodeRowBody<true>(y, row);
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
