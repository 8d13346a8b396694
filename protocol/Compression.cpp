#include "Compression.h"

#include <algorithm>
#include <memory>
#include <string>

#include <zstd.h>
#include <zstd_errors.h>

#include "ProtocolError.h"

namespace igi::proto {
namespace {

// Output is allocated in steps starting here and doubling, so memory follows real content.
constexpr std::size_t kFirstChunk = std::size_t{1} << 20;
// Up to this size, compression and decompression use one context per thread. Creating a
// context costs more than a tile (about 17 us against 8 us to decompress 15 KB): it is a
// 100+ KB allocation, page-faulted anew every time. Larger jobs (scenes) get a fresh context
// so that a thread does not keep the large buffers they make it allocate.
constexpr std::size_t kReuseContextUpTo = kFirstChunk;

[[noreturn]] void fail(std::string_view what, const std::string& message) {
    throw ProtocolError(std::string(what) + ": " + message);
}

struct DctxDeleter {
    void operator()(ZSTD_DCtx* d) const { ZSTD_freeDCtx(d); }
};
struct CctxDeleter {
    void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};
using DctxPtr = std::unique_ptr<ZSTD_DCtx, DctxDeleter>;
using CctxPtr = std::unique_ptr<ZSTD_CCtx, CctxDeleter>;

ZSTD_DCtx& threadDctx() {
    thread_local DctxPtr dctx(ZSTD_createDCtx());
    if (!dctx) throw std::bad_alloc();
    // A previous frame may have failed half-way: start clean.
    ZSTD_DCtx_reset(dctx.get(), ZSTD_reset_session_only);
    return *dctx;
}

ZSTD_CCtx& threadCctx() {
    thread_local CctxPtr cctx(ZSTD_createCCtx());
    if (!cctx) throw std::bad_alloc();
    return *cctx;
}

/// The frame's header must declare exactly `expectedSize` bytes and the frame fill `frame`.
void checkFrame(std::span<const std::uint8_t> frame, std::size_t expectedSize,
                std::string_view what) {
    const std::size_t frameSize = ZSTD_findFrameCompressedSize(frame.data(), frame.size());
    if (ZSTD_isError(frameSize))
        fail(what, std::string("corrupt zstd frame (") + ZSTD_getErrorName(frameSize) + ")");
    if (frameSize != frame.size())
        fail(what,
             std::to_string(frame.size() - frameSize) + " trailing bytes after the zstd frame");
    const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
    if (declared == ZSTD_CONTENTSIZE_UNKNOWN) fail(what, "zstd frame does not declare its size");
    if (declared == ZSTD_CONTENTSIZE_ERROR) fail(what, "corrupt zstd frame header");
    if (declared != expectedSize)
        fail(what, "zstd frame declares " + std::to_string(declared) + " bytes, the message says " +
                       std::to_string(expectedSize));
}

/// Small content, or memory set aside for it: filled in one call.
void decompressAtOnce(std::span<const std::uint8_t> frame, std::span<std::uint8_t> out,
                      std::string_view what) {
    const std::size_t expectedSize = out.size();
    const std::size_t n =
        ZSTD_decompressDCtx(&threadDctx(), out.data(), out.size(), frame.data(), frame.size());
    if (ZSTD_isError(n)) {
        if (ZSTD_getErrorCode(n) == ZSTD_error_dstSize_tooSmall)
            fail(what, "zstd data decompresses to more than the declared size");
        fail(what, std::string("corrupt zstd data (") + ZSTD_getErrorName(n) + ")");
    }
    if (n != expectedSize)
        fail(what, "zstd data decompresses to " + std::to_string(n) + " bytes, expected " +
                       std::to_string(expectedSize));
}

/// Large content: `out` grows only as content is actually produced.
void decompressInSteps(std::span<const std::uint8_t> frame, std::size_t expectedSize,
                       std::string_view what, std::vector<std::uint8_t>& out) {
    DctxPtr dctx(ZSTD_createDCtx());
    if (!dctx) throw std::bad_alloc();
    out.clear();
    std::size_t produced = 0;
    ZSTD_inBuffer in{frame.data(), frame.size(), 0};
    for (;;) {
        std::uint8_t overflow = 0;
        ZSTD_outBuffer o{};
        if (produced == out.size() && out.size() == expectedSize) {
            // Full: the frame must end without producing anything more.
            o = {&overflow, 1, 0};
        } else {
            if (produced == out.size())
                out.resize(std::min(expectedSize, std::max(out.size() * 2, kFirstChunk)));
            o = {out.data(), out.size(), produced};
        }
        const std::size_t ret = ZSTD_decompressStream(dctx.get(), &o, &in);
        if (ZSTD_isError(ret))
            fail(what, std::string("corrupt zstd data (") + ZSTD_getErrorName(ret) + ")");
        if (o.dst == &overflow) {
            if (o.pos != 0) fail(what, "zstd data decompresses to more than the declared size");
        } else {
            produced = o.pos;
        }
        if (ret == 0) break;  // frame complete
        if (in.pos == in.size && o.pos < o.size) fail(what, "incomplete zstd frame");
    }
    if (produced != expectedSize)
        fail(what, "zstd data decompresses to " + std::to_string(produced) + " bytes, expected " +
                       std::to_string(expectedSize));
}

}  // namespace

std::vector<std::uint8_t> zstdCompress(std::span<const std::uint8_t> data, int level) {
    std::vector<std::uint8_t> out;
    zstdCompressAppend(data, level, out);
    return out;
}

void zstdCompressAppend(std::span<const std::uint8_t> data, int level,
                        std::vector<std::uint8_t>& out) {
    const std::size_t start = out.size();
    out.resize(start + ZSTD_compressBound(data.size()));
    std::size_t n = 0;
    if (data.size() <= kReuseContextUpTo) {
        // ZSTD_compressCCtx sets the context to `level` afresh: the same bytes as ZSTD_compress.
        n = ZSTD_compressCCtx(&threadCctx(), out.data() + start, out.size() - start, data.data(),
                              data.size(), level);
    } else {
        n = ZSTD_compress(out.data() + start, out.size() - start, data.data(), data.size(), level);
    }
    if (ZSTD_isError(n)) {
        out.resize(start);
        throw ProtocolError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
    }
    out.resize(start + n);
}

std::vector<std::uint8_t> zstdDecompressExact(std::span<const std::uint8_t> frame,
                                              std::size_t expectedSize, std::string_view what) {
    std::vector<std::uint8_t> out;
    zstdDecompressExactInto(frame, expectedSize, what, out);
    return out;
}

void zstdDecompressExactInto(std::span<const std::uint8_t> frame, std::size_t expectedSize,
                             std::string_view what, std::vector<std::uint8_t>& out) {
    checkFrame(frame, expectedSize, what);
    if (expectedSize <= kReuseContextUpTo) {
        out.resize(expectedSize);
        decompressAtOnce(frame, out, what);
    } else {
        decompressInSteps(frame, expectedSize, what, out);
    }
}

void zstdDecompressExactTo(std::span<const std::uint8_t> frame, std::span<std::uint8_t> out,
                           std::string_view what) {
    checkFrame(frame, out.size(), what);
    decompressAtOnce(frame, out, what);
}

}  // namespace igi::proto
