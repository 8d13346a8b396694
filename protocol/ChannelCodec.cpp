#include "ChannelCodec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "Compression.h"
#include "ProtocolError.h"
#include "Quantize.h"
#include "TileCodes.h"

namespace igi::proto {
namespace {

/// Per-thread buffers of the codec, reused from tile to tile (a tile's allocations cost about
/// as much as its pixels). Whatever grew past `kKeepBytes` (a huge tile) is given back.
struct Scratch {
    static constexpr std::size_t kKeepBytes = std::size_t{1} << 20;
    std::vector<std::uint8_t> raw;     // the planes, byte-shuffled, as zstd sees them
    std::vector<std::uint32_t> words;  // one plane's codes

    std::span<std::uint32_t> wordsFor(std::size_t count) {
        if (words.size() < count) words.resize(count);
        return {words.data(), count};
    }
    void trim() {
        if (raw.capacity() > kKeepBytes) std::vector<std::uint8_t>().swap(raw);
        if (words.capacity() * sizeof(std::uint32_t) > kKeepBytes)
            std::vector<std::uint32_t>().swap(words);
    }
};

/// The calling thread's scratch, trimmed when the codec returns or throws (a hostile huge tile
/// that fails half-way must not leave its buffers behind either).
class ThreadScratch {
  public:
    ThreadScratch() : scratch_(instance()) {}
    ~ThreadScratch() { scratch_.trim(); }
    ThreadScratch(const ThreadScratch&) = delete;
    ThreadScratch& operator=(const ThreadScratch&) = delete;
    Scratch& operator*() { return scratch_; }

  private:
    static Scratch& instance() {
        thread_local Scratch scratch;
        return scratch;
    }
    Scratch& scratch_;
};

/// Writes the low `Bytes` bytes of every word to `raw`: byte 0 of every pixel first, then
/// byte 1, ...
template <std::uint32_t Bytes>
void putShuffled(std::span<const std::uint32_t> words, std::uint8_t* raw) {
    const std::size_t n = words.size();
    for (std::uint32_t b = 0; b < Bytes; ++b) {
        std::uint8_t* plane = raw + b * n;
        for (std::size_t i = 0; i < n; ++i)
            plane[i] = static_cast<std::uint8_t>(words[i] >> (8 * b));
    }
}

/// The inverse of putShuffled.
template <std::uint32_t Bytes>
void getShuffled(const std::uint8_t* raw, std::span<std::uint32_t> words) {
    const std::size_t n = words.size();
    const std::uint8_t* b0 = raw;
    const std::uint8_t* b1 = raw + n;
    const std::uint8_t* b2 = raw + 2 * n;
    const std::uint8_t* b3 = raw + 3 * n;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t w = b0[i] | std::uint32_t{b1[i]} << 8;
        if constexpr (Bytes >= 3) w |= std::uint32_t{b2[i]} << 16;
        if constexpr (Bytes >= 4) w |= std::uint32_t{b3[i]} << 24;
        words[i] = w;
    }
}

bool allEqual(std::span<const std::uint32_t> words, std::uint32_t value) {
    std::uint32_t differ = 0;  // no early exit: a branch-free loop the compiler vectorizes
    for (std::uint32_t w : words) differ |= w ^ value;
    return differ == 0;
}

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "planes are read as arrays of floats");

float largestComponent(const std::vector<glm::vec3>& plane) {
    // Running maxima over the plane as a flat array of floats, without branches (NaN compares
    // false and is skipped), in lanes the compiler can vectorize; +inf is clamped at the end.
    constexpr std::size_t kLanes = 12;  // four pixels
    const float* f = &plane.data()->x;
    const std::size_t n = plane.size() * 3;
    float m[kLanes] = {};
    std::size_t i = 0;
    for (; i + kLanes <= n; i += kLanes)
        for (std::size_t k = 0; k < kLanes; ++k) m[k] = f[i + k] > m[k] ? f[i + k] : m[k];
    for (; i < n; ++i) m[0] = f[i] > m[0] ? f[i] : m[0];
    return std::min(*std::max_element(m, m + kLanes), FLT_MAX);
}

float smallestFiniteDepth(const std::vector<float>& depth) {
    float m = INFINITY;
    for (float d : depth) {
        const float candidate = d > 0.0f ? d : INFINITY;  // NaN and <= 0 do not count
        m = candidate < m ? candidate : m;                // without a branch: depth is noisy
    }
    return std::isfinite(m) ? m : FLT_MIN;  // only invalid depths: any positive reference works
}

void checkPlaneSize(std::size_t size, int count, const char* name) {
    if (size != 0 && size != static_cast<std::size_t>(count))
        throw ProtocolError(std::string("tile ") + name + " plane has " + std::to_string(size) +
                            " entries, expected " + std::to_string(count));
}

/// Appends planes to the raw (shuffled) bytes in bit order, leaving out those whose every
/// code is the default, and remembers which were sent and their references.
class PlaneWriter {
  public:
    PlaneWriter(Scratch& scratch, std::size_t count, std::uint32_t planes)
        : scratch_(scratch), count_(count) {
        scratch_.raw.resize(std::size_t{bytesPerPixel(planes)} * count);
    }

    std::span<std::uint32_t> words() { return scratch_.wordsFor(count_); }

    /// Adds the plane `bit` whose codes are in words(), unless they all equal `defaultCode`.
    template <std::uint32_t Bytes>
    void add(std::uint32_t bit, std::uint32_t defaultCode, bool hasReference, float reference) {
        const auto w = words();
        if (allEqual(w, defaultCode)) return;
        putShuffled<Bytes>(w, scratch_.raw.data() + size_);
        size_ += Bytes * count_;
        sent_ |= bit;
        if (hasReference) references_[referenceCount_++] = reference;
    }

    std::uint32_t sent() const { return sent_; }
    std::span<const float> references() const { return {references_, referenceCount_}; }
    std::span<const std::uint8_t> raw() const { return {scratch_.raw.data(), size_}; }

  private:
    Scratch& scratch_;
    std::size_t count_;
    std::size_t size_ = 0;
    std::uint32_t sent_ = 0;
    float references_[4] = {};
    std::size_t referenceCount_ = 0;
};

/// A sent plane's codes as words (getShuffled), in the scratch.
template <std::uint32_t Bytes>
std::span<const std::uint32_t> words(Scratch& scratch, const TileCodes& codes, Channel c) {
    const auto w = scratch.wordsFor(codes.count);
    getShuffled<Bytes>(scratch.raw.data() + codes.planeOffset(c), w);
    return w;
}

}  // namespace

std::uint32_t bytesPerPixel(std::uint32_t mask) {
    std::uint32_t n = 0;
    if (mask & kIrradiance) n += kIrradianceBytes;
    if (mask & kReflectance) n += kReflectanceBytes;
    if (mask & kNormal) n += kNormalBytes;
    if (mask & kDepth) n += kDepthBytes;
    if (mask & kUnfiltered) n += kUnfilteredBytes;
    if (mask & kGlossy) n += kGlossyBytes;
    return n;
}

void writeTileChannels(ByteWriter& out, const TileChannels& channels) {
    const int count = channels.count;
    if (count < 0 || static_cast<std::uint32_t>(count) > kMaxTilePixels)
        throw ProtocolError("tile of " + std::to_string(count) + " pixels, the limit is " +
                            std::to_string(kMaxTilePixels));
    checkPlaneSize(channels.irradiance.size(), count, "irradiance");
    checkPlaneSize(channels.reflectance.size(), count, "reflectance");
    checkPlaneSize(channels.normal.size(), count, "normal");
    checkPlaneSize(channels.depth.size(), count, "depth");
    checkPlaneSize(channels.unfiltered.size(), count, "unfiltered");
    checkPlaneSize(channels.glossy.size(), count, "glossy");
    const std::uint32_t planes = count == 0 ? 0 : channels.mask();

    ThreadScratch scratch;
    PlaneWriter w(*scratch, static_cast<std::size_t>(count), planes);
    // In bit order, which is also the order on the wire.
    if (planes & kIrradiance) {
        const float scale = largestComponent(channels.irradiance);
        encodeSharedExponents(channels.irradiance, scale, w.words());
        w.add<kIrradianceBytes>(kIrradiance, 0, true, scale);
    }
    if (planes & kReflectance) {
        encodeSrgb8Triples(channels.reflectance, w.words());
        w.add<kReflectanceBytes>(kReflectance, 0, false, 0.0f);  // all black: left out
    }
    if (planes & kNormal) {
        encodeOctNormals(channels.normal, w.words());
        w.add<kNormalBytes>(kNormal, 0, false, 0.0f);  // no normals at all: left out
    }
    if (planes & kDepth) {
        const float d0 = smallestFiniteDepth(channels.depth);
        encodeLogDepths(channels.depth, d0, w.words());
        w.add<kDepthBytes>(kDepth, kDepthInfinite, true, d0);  // all +inf: left out
    }
    if (planes & kUnfiltered) {
        const float scale = largestComponent(channels.unfiltered);
        encodeSharedExponents(channels.unfiltered, scale, w.words());
        w.add<kUnfilteredBytes>(kUnfiltered, 0, true, scale);
    }
    if (planes & kGlossy) {
        const float scale = largestComponent(channels.glossy);
        encodeSharedExponents(channels.glossy, scale, w.words());
        w.add<kGlossyBytes>(kGlossy, 0, true, scale);
    }

    out.u32(static_cast<std::uint32_t>(count));
    out.u32(planes);
    out.u32(w.sent());
    for (float r : w.references()) out.f32(r);
    if (w.sent() != 0) {
        // A blob, compressed straight into the output behind its length.
        const std::size_t at = out.size();
        out.u32(0);
        std::vector<std::uint8_t>& buffer = out.buffer();
        zstdCompressAppend(w.raw(), kTileZstdLevel, buffer);
        const std::size_t length = buffer.size() - at - 4;
        for (int i = 0; i < 4; ++i) buffer[at + i] = static_cast<std::uint8_t>(length >> (8 * i));
    }
}

TileChannels readTileChannels(ByteReader& in) {
    ThreadScratch scratch;
    const TileCodes codes = readTileCodes(in);
    // Bounded by the count, checked before anything is allocated; a frame that declares more
    // than it holds is refused before it grows the buffer far (zstdDecompressExactInto).
    if (codes.sent != 0)
        zstdDecompressExactInto(codes.compressed, codes.rawSize(), in.what(), (*scratch).raw);
    TileChannels channels;
    channels.resize(static_cast<int>(codes.count), codes.planes);
    const std::uint32_t sent = codes.sent;
    Scratch& s = *scratch;
    if (sent & kIrradiance)
        decodeSharedExponents(words<kIrradianceBytes>(s, codes, kIrradiance), codes.irradianceScale,
                              channels.irradiance);
    if (sent & kReflectance)
        decodeSrgb8Triples(words<kReflectanceBytes>(s, codes, kReflectance), channels.reflectance);
    if (sent & kNormal) decodeOctNormals(words<kNormalBytes>(s, codes, kNormal), channels.normal);
    if (sent & kDepth)
        decodeLogDepths(words<kDepthBytes>(s, codes, kDepth), codes.depthMin, channels.depth);
    if (sent & kUnfiltered)
        decodeSharedExponents(words<kUnfilteredBytes>(s, codes, kUnfiltered), codes.unfilteredScale,
                              channels.unfiltered);
    if (sent & kGlossy)
        decodeSharedExponents(words<kGlossyBytes>(s, codes, kGlossy), codes.glossyScale,
                              channels.glossy);
    return channels;
}

}  // namespace igi::proto
