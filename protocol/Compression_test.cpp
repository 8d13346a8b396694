#include "Compression.h"

#include <gtest/gtest.h>

#include <zstd.h>

#include "ByteWriter.h"
#include "ProtocolError.h"

namespace igi::proto {
namespace {

std::vector<std::uint8_t> text(std::size_t n) {
    std::vector<std::uint8_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>("igi wire "[i % 9]);
    return v;
}

std::string errorOf(std::span<const std::uint8_t> frame, std::size_t expected) {
    try {
        zstdDecompressExact(frame, expected, "test");
    } catch (const ProtocolError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Compression, RoundTripsIncludingEmptyAndMultiChunkContent) {
    for (std::size_t n :
         {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{5} << 20}) {
        const auto data = text(n);
        const auto frame = zstdCompress(data, 3);
        EXPECT_EQ(zstdDecompressExact(frame, n, "test"), data) << n;
    }
}

TEST(Compression, AppendKeepsWhatWasThere) {
    std::vector<std::uint8_t> out = {1, 2, 3};
    zstdCompressAppend(text(100), 1, out);
    EXPECT_EQ(out[2], 3);
    EXPECT_EQ(zstdDecompressExact(std::span(out).subspan(3), 100, "test"), text(100));
}

TEST(Compression, DeclaredSizeMustMatch) {
    const auto frame = zstdCompress(text(1000), 3);
    EXPECT_NE(errorOf(frame, 999).find("declares 1000 bytes"), std::string::npos);
    EXPECT_NE(errorOf(frame, 1001).find("declares 1000 bytes"), std::string::npos);
}

TEST(Compression, FrameWithoutDeclaredSizeIsRefused) {
    // A frame without its content size (as streaming produces) could expand to anything.
    const auto data = text(1000);
    std::vector<std::uint8_t> frame(ZSTD_compressBound(data.size()));
    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
    const std::size_t n =
        ZSTD_compress2(cctx, frame.data(), frame.size(), data.data(), data.size());
    ZSTD_freeCCtx(cctx);
    ASSERT_FALSE(ZSTD_isError(n));
    frame.resize(n);
    ASSERT_EQ(ZSTD_getFrameContentSize(frame.data(), frame.size()), ZSTD_CONTENTSIZE_UNKNOWN);
    EXPECT_NE(errorOf(frame, 1000).find("does not declare"), std::string::npos);
}

TEST(Compression, TrailingBytesAndSecondFramesAreRefused) {
    auto frame = zstdCompress(text(100), 3);
    auto twice = frame;
    twice.insert(twice.end(), frame.begin(), frame.end());
    EXPECT_NE(errorOf(twice, 100).find("trailing"), std::string::npos);
    frame.push_back(0);
    EXPECT_NE(errorOf(frame, 100).find("trailing"), std::string::npos);
}

TEST(Compression, TruncatedFramesAreRefused) {
    const auto frame = zstdCompress(text(5000), 3);
    for (std::size_t n = 0; n < frame.size(); ++n) {
        const std::vector<std::uint8_t> cut(frame.begin(), frame.begin() + n);
        EXPECT_THROW(zstdDecompressExact(cut, 5000, "test"), ProtocolError) << n;
    }
}

TEST(Compression, FrameClaimingMoreThanItHoldsIsRefused) {
    // Header says 1 GiB, one raw block holds 10 bytes.
    const std::uint64_t claim = 1ull << 30;
    std::vector<std::uint8_t> frame;
    ByteWriter out(frame);
    out.u32(0xFD2FB528);
    out.u8(0xE0);  // 8-byte content size, single segment
    out.u64(claim);
    out.u8(0x51);  // last block, raw, 10 bytes
    out.u8(0);
    out.u8(0);
    for (int i = 0; i < 10; ++i) out.u8('a');
    EXPECT_THROW(zstdDecompressExact(frame, claim, "test"), ProtocolError);
    // Without single segment (window 1 MiB): the decoder runs out of input long before 1 GiB.
    frame[4] = 0xC0;
    frame.insert(frame.begin() + 5, 0x50);  // window descriptor: 2^(10 + 10) bytes
    EXPECT_NE(errorOf(frame, claim), "(no error)");
}

TEST(Compression, ReusedContextsGiveTheBytesOfFreshOnes) {
    // The per-thread context must not carry anything from one frame to the next, whatever the
    // level or size before: the bytes are those of ZSTD_compress.
    for (int round = 0; round < 2; ++round)
        for (int level : {1, 3, 1, 19, 1})
            for (std::size_t n : {std::size_t{100}, std::size_t{15000}, std::size_t{3} << 20}) {
                const auto data = text(n);
                std::vector<std::uint8_t> fresh(ZSTD_compressBound(n));
                fresh.resize(ZSTD_compress(fresh.data(), fresh.size(), data.data(), n, level));
                EXPECT_EQ(zstdCompress(data, level), fresh) << "level " << level << ", " << n;
            }
}

TEST(Compression, DecompressIntoReusesTheBufferAndRecoversFromBadFrames) {
    std::vector<std::uint8_t> out(50000, 0xAB);  // longer than the content: must be cut
    const auto small = text(1000);
    zstdDecompressExactInto(zstdCompress(small, 1), small.size(), "test", out);
    EXPECT_EQ(out, small);
    // A frame that fails half-way leaves the per-thread context mid-frame; the next one must
    // still decode.
    std::vector<std::uint8_t> corrupt;
    ByteWriter frame(corrupt);
    frame.u32(0xFD2FB528);
    frame.u8(0x60);  // single segment, 2-byte content size (+ 256)
    frame.u16(20000 - 256);
    frame.u8(0x25);  // last block, compressed, 4 bytes
    frame.u8(0);
    frame.u8(0);
    frame.u32(0xFFFFFFFF);  // literals "repeating" a Huffman table there is none of
    EXPECT_THROW(zstdDecompressExactInto(corrupt, 20000, "test", out), ProtocolError);
    const auto big = text(3 << 20);  // beyond 1 MiB: the step-by-step path into the same vector
    zstdDecompressExactInto(zstdCompress(big, 1), big.size(), "test", out);
    EXPECT_EQ(out, big);
    zstdDecompressExactInto(zstdCompress(small, 1), small.size(), "test", out);
    EXPECT_EQ(out, small);
}

TEST(Compression, SmallFramesProducingMoreThanDeclaredAreRefused) {
    // A raw block of 10 bytes in a frame whose header declares 5, within the one-call path.
    std::vector<std::uint8_t> frame;
    ByteWriter out(frame);
    out.u32(0xFD2FB528);
    out.u8(0x20);  // single segment, 1-byte content size
    out.u8(5);
    out.u8(0x51);  // last block, raw, 10 bytes
    out.u8(0);
    out.u8(0);
    for (int i = 0; i < 10; ++i) out.u8('a');
    EXPECT_NE(errorOf(frame, 5).find("more than the declared size"), std::string::npos)
        << errorOf(frame, 5);
    std::vector<std::uint8_t> into;
    EXPECT_THROW(zstdDecompressExactInto(frame, 5, "test", into), ProtocolError);
}

}  // namespace
}  // namespace igi::proto
