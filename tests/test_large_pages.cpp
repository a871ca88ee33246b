// The storage of tables read at random (scenes/large_pages.h): aligned as promised, whole, and
// usable as any std::vector.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

#include "scenes/large_pages.h"

using namespace voxgi;

TEST(LargePages, SmallAllocationsKeepTheirTypesAlignmentAndLargeOnesStartOnAHugePage) {
    struct alignas(64) Line {
        float values[16];
    };
    LargeVector<Line> lines(3);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(lines.data()) % 64, 0u);
    LargeVector<std::uint8_t> big(std::size_t(5) << 20);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % (std::size_t(2) << 20), 0u);
    // Every byte is there: written and read back at both ends and in between.
    std::iota(big.begin(), big.end(), std::uint8_t(0));
    EXPECT_EQ(big.front(), 0u);
    EXPECT_EQ(big[1000], std::uint8_t(1000 % 256));
    EXPECT_EQ(big.back(), std::uint8_t((big.size() - 1) % 256));
    // Growing copies into a new table and frees the old one (the sanitized build checks).
    big.resize(big.size() + 7, 9);
    EXPECT_EQ(big.back(), 9u);
    EXPECT_EQ(big[1000], std::uint8_t(1000 % 256));
    LargeVector<std::uint8_t> empty;
    empty.shrink_to_fit();
    EXPECT_TRUE(empty.empty());
}

TEST(LargePages, AnImpossibleSizeThrowsBadAlloc) {
    LargePageAllocator<double> allocator;
    EXPECT_THROW(allocator.allocate(std::size_t(-1) / 4), std::bad_alloc);
}
