#include "util/HeapMemory.h"

#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

namespace igi {
namespace {

// 48 MiB in blocks small enough to come from the arena (not mmap'd one by one), freed but for
// the last: the free memory then lies below the arena's top, where free() leaves it resident.
TEST(HeapMemory, FreedMemoryBelowTheTopIsReleased) {
    constexpr std::size_t kBlock = 4096, kBlocks = 48 * 256;
    std::vector<char*> blocks;
    blocks.reserve(kBlocks);
    for (std::size_t i = 0; i < kBlocks; ++i) {
        blocks.push_back(static_cast<char*>(std::malloc(kBlock)));
        std::memset(blocks.back(), 1, kBlock);  // resident
    }
    const HeapFigures full = heapFigures();
    for (std::size_t i = 0; i + 1 < kBlocks; ++i) std::free(blocks[i]);
    const HeapFigures freed = heapFigures();
    EXPECT_GE(full.inUse - freed.inUse, 40u << 20);
    EXPECT_GE(freed.held - freed.inUse, 40u << 20);  // kept by the allocator

    EXPECT_GE(releaseFreeHeap(), 32u << 20);
    std::free(blocks.back());
}

TEST(HeapMemory, ResidentMemoryIsReadAndCountsWhatIsTouched) {
    const std::size_t before = residentBytes();
    ASSERT_GT(before, 0u);
    constexpr std::size_t kSize = 64u << 20;
    std::unique_ptr<char[]> big(new char[kSize]);
    std::memset(big.get(), 1, kSize);
    EXPECT_GE(residentBytes(), before + (kSize * 3) / 4);
}

}  // namespace
}  // namespace igi
