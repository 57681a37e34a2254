// SPDX-License-Identifier: MIT
// The weather window's column-bounds pyramid (skyservice/render/column_bounds.h): conservative for the
// bilinear weather lookups (a covered texel bounds its whole 3x3 neighbourhood), min/max up the levels,
// the anvil slab counted, unknown altitudes unbounded, empty columns empty.
#include "skyservice/render/column_bounds.h"

#include "shaders/shared/column_bounds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sky;

namespace
{

constexpr uint32_t kSize = 16;

WeatherWindow emptyWindow()
{
    WeatherWindow w;
    w.sizeTexels = kSize;
    w.texels.assign(size_t(WEATHER_WINDOW_SLICES) * kSize * kSize, glm::vec4(0.0f));
    return w;
}

void setLayer(WeatherWindow& w, uint32_t slice, uint32_t i, uint32_t j, float coverage, float baseM, float topM)
{
    w.texels[w.index(slice, i, j)] = glm::vec4(coverage, baseM, topM, float(CLOUD_TYPE_CUMULUS));
}

}  // namespace

TEST(ColumnBounds, ACoveredTexelBoundsItsNeighbourhoodAndNothingElse)
{
    WeatherWindow w = emptyWindow();
    setLayer(w, 0, 5, 7, 0.5f, 1000.0f, 2000.0f);
    std::vector<uint8_t> atlas = buildColumnBounds(w);
    ASSERT_EQ(atlas.size(), size_t(columnBoundsWidth(kSize)) * kSize * 2);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
        {
            ColumnBound b = columnBoundAt(atlas, kSize, 0, i, j);
            bool near = std::abs(int(i) - 5) <= 1 && std::abs(int(j) - 7) <= 1;
            if (!near)
            {
                EXPECT_TRUE(b.empty()) << i << "," << j;
                continue;
            }
            // The neighbours' zero bases count: a bilinear lookup mixes them into the base.
            EXPECT_EQ(b.minBaseM, -std::numeric_limits<float>::infinity()) << i << "," << j;
            EXPECT_GE(b.maxTopM, 2000.0f + COLUMN_BOUNDS_UNIT_M) << i << "," << j;  // rounded up, one unit more
            EXPECT_LE(b.maxTopM, 2000.0f + 2.0f * COLUMN_BOUNDS_UNIT_M) << i << "," << j;
        }
}

TEST(ColumnBounds, AFullyCoveredNeighbourhoodKeepsItsBase)
{
    WeatherWindow w = emptyWindow();
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            setLayer(w, 2, i, j, 0.9f, 900.0f + 10.0f * float(i), 1700.0f);
    std::vector<uint8_t> atlas = buildColumnBounds(w);
    ColumnBound b = columnBoundAt(atlas, kSize, 0, 8, 8);  // neighbourhood bases 970..990 m
    EXPECT_LE(b.minBaseM, 970.0f - COLUMN_BOUNDS_UNIT_M);
    EXPECT_GE(b.minBaseM, 970.0f - 2.0f * COLUMN_BOUNDS_UNIT_M);
    EXPECT_GE(b.maxTopM, 1700.0f);
    EXPECT_LE(b.maxTopM, 1700.0f + 2.0f * COLUMN_BOUNDS_UNIT_M);
}

TEST(ColumnBounds, LevelsTakeTheMinOfBasesAndTheMaxOfTops)
{
    WeatherWindow w = emptyWindow();
    setLayer(w, 0, 2, 2, 0.5f, 3000.0f, 4000.0f);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 8; i < kSize; ++i)
            setLayer(w, 2, i, j, 0.9f, 5000.0f, 9000.0f);
    // An anvil slab over the far corner, higher than anything else.
    setLayer(w, WEATHER_WINDOW_ANVIL_SLICE, 14, 14, 0.4f, 9000.0f, 12000.0f);
    std::vector<uint8_t> atlas = buildColumnBounds(w);
    // Level 2 texel (0, 0) covers level-0 texels 0..3: the small cloud's neighbourhood only.
    ColumnBound small = columnBoundAt(atlas, kSize, 2, 0, 0);
    EXPECT_FALSE(small.empty());
    EXPECT_LT(small.maxTopM, 4200.0f);
    // Level 2 texel (1, 0): texels 4..7 are clear except column 7, next to the covered half.
    EXPECT_GE(columnBoundAt(atlas, kSize, 2, 1, 0).maxTopM, 9000.0f);
    EXPECT_TRUE(columnBoundAt(atlas, kSize, 1, 2, 6).empty());  // level-0 texels 4..5 x 12..13
    // The last level (one texel) bounds everything, the anvil included.
    const int last = int(std::log2(double(kSize)));
    ColumnBound all = columnBoundAt(atlas, kSize, last, 0, 0);
    EXPECT_GE(all.maxTopM, 12000.0f);
    EXPECT_EQ(all.minBaseM, -std::numeric_limits<float>::infinity());
    EXPECT_EQ(columnBoundsLevelOrigin(1, int(kSize)).x, int(kSize));
    EXPECT_EQ(columnBoundsLevelOrigin(2, int(kSize)).y, int(kSize / 2));
}

TEST(ColumnBounds, UnknownAltitudesAndCoverageAreUnbounded)
{
    WeatherWindow w = emptyWindow();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    setLayer(w, 0, 3, 3, 0.5f, 1000.0f, nan);
    setLayer(w, 0, 10, 10, nan, 1000.0f, 2000.0f);
    setLayer(w, 0, 12, 3, 0.5f, 1000.0f, 30000.0f);  // beyond the 16.3 km the code holds
    std::vector<uint8_t> atlas = buildColumnBounds(w);
    EXPECT_EQ(columnBoundAt(atlas, kSize, 0, 3, 3).maxTopM, std::numeric_limits<float>::infinity());
    EXPECT_FALSE(columnBoundAt(atlas, kSize, 0, 10, 10).empty());
    EXPECT_EQ(columnBoundAt(atlas, kSize, 0, 12, 3).maxTopM, std::numeric_limits<float>::infinity());
    EXPECT_TRUE(columnBoundAt(atlas, kSize, 0, 7, 7).empty());
}
