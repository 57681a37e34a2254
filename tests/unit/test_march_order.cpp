// SPDX-License-Identifier: MIT
// The march's row order on the CPU (skyservice/render/march_order.h).
#include "skyservice/render/march_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

using namespace sky;

namespace
{

bool isPermutation(std::vector<uint32_t> order, uint32_t rows)
{
    std::sort(order.begin(), order.end());
    std::vector<uint32_t> expected(rows);
    std::iota(expected.begin(), expected.end(), 0u);
    return order == expected;
}

// The cost of each of `ranges` contiguous ranges of `order` (range i: positions [i n / r, (i+1) n / r)).
std::vector<uint64_t> rangeCosts(const std::vector<uint32_t>& order, const std::vector<uint32_t>& cost,
                                 uint32_t ranges)
{
    const size_t n = order.size();
    std::vector<uint64_t> sums(ranges, 0);
    for (uint32_t i = 0; i < ranges; ++i)
        for (size_t k = i * n / ranges; k < (i + 1) * n / ranges; ++k)
            sums[i] += cost[order[k]];
    return sums;
}

}  // namespace

// Top and bottom rows in turn, as the march's workgroups ran before they were measured.
TEST(MarchOrder, InterleavedAlternatesTopAndBottom)
{
    EXPECT_EQ(interleavedRowOrder(5), (std::vector<uint32_t>{0, 4, 1, 3, 2}));
    EXPECT_EQ(interleavedRowOrder(4), (std::vector<uint32_t>{0, 3, 1, 2}));
    EXPECT_EQ(interleavedRowOrder(1), (std::vector<uint32_t>{0}));
    EXPECT_TRUE(isPermutation(interleavedRowOrder(135), 135));
}

// On a GPU (one range): costliest first, ties in image order.
TEST(MarchOrder, OneRangeIsCostliestFirst)
{
    const std::vector<uint32_t> cost = {4, 40, 7, 40, 0, 90};
    EXPECT_EQ(costliestFirstRowOrder(cost.data(), uint32_t(cost.size()), 1),
              (std::vector<uint32_t>{5, 1, 3, 2, 0, 4}));
}

// On lavapipe, which gives each thread a contiguous range of the dispatch: a horizon band of costly rows
// in the middle of the image lands in one thread's range in the interleaved order, and is shared out
// when dealt. Every range costs within one row's cost of the others, and lists its rows costliest first.
TEST(MarchOrder, RangesAreDealtToEvenCost)
{
    std::vector<uint32_t> cost(34, 5);
    for (uint32_t row = 14; row < 22; ++row)
        cost[row] = 100 + 10 * row;
    for (uint32_t ranges : {2u, 3u, 8u})
    {
        const std::vector<uint32_t> order = costliestFirstRowOrder(cost.data(), 34, ranges);
        ASSERT_TRUE(isPermutation(order, 34)) << ranges;
        const std::vector<uint64_t> dealt = rangeCosts(order, cost, ranges);
        const uint64_t spread = *std::max_element(dealt.begin(), dealt.end()) - *std::min_element(dealt.begin(), dealt.end());
        EXPECT_LE(spread, uint64_t(*std::max_element(cost.begin(), cost.end()))) << ranges;
        for (uint32_t i = 0; i < ranges; ++i)
            for (size_t k = i * 34 / ranges + 1; k < (i + 1) * 34 / ranges; ++k)
                EXPECT_GE(cost[order[k - 1]], cost[order[k]]) << ranges << " range " << i;
    }
    const std::vector<uint64_t> interleaved = rangeCosts(interleavedRowOrder(34), cost, 2);
    const std::vector<uint64_t> dealt = rangeCosts(costliestFirstRowOrder(cost.data(), 34, 2), cost, 2);
    EXPECT_GT(std::max(interleaved[0], interleaved[1]), 1.5 * double(std::min(interleaved[0], interleaved[1])));
    EXPECT_LT(std::max(dealt[0], dealt[1]), 1.1 * double(std::min(dealt[0], dealt[1])));
}

TEST(MarchOrder, MoreRangesThanRowsStillGiveAPermutation)
{
    const std::vector<uint32_t> cost = {3, 1, 2};
    EXPECT_TRUE(isPermutation(costliestFirstRowOrder(cost.data(), 3, 16), 3));
    EXPECT_TRUE(isPermutation(costliestFirstRowOrder(cost.data(), 1, 2), 1));
}
