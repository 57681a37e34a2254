// SPDX-License-Identifier: MIT
// The weather window's column-bounds pyramid (skyservice/weather/column_bounds.h): conservative for the
// bilinear weather lookups (a covered texel bounds its whole 3x3 neighbourhood), min/max up the levels,
// the anvil slab counted, unknown altitudes unbounded, empty columns empty; within a layer, only the heights
// where its genus may hold cloud at the neighbourhood's coverage (cloud_extent.glsl: the cumulus domes).
#include "skyservice/weather/cloud_extent.h"
#include "skyservice/weather/column_bounds.h"

#include "shaders/shared/column_bounds.h"
#include "shaders/shared/prelude.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
namespace glsl
{
using namespace glm;
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/cloud_extent.glsl"
}  // namespace glsl
#pragma GCC diagnostic pop

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

void setLayer(WeatherWindow& w, uint32_t slice, uint32_t i, uint32_t j, float coverage, float baseM, float topM,
              int type = CLOUD_TYPE_CUMULUS)
{
    w.texels[w.index(slice, i, j)] = glm::vec4(coverage, baseM, topM, float(type));
}

// The highest height fraction (of 4096 steps) where a cumulus layer of this coverage may hold cloud.
float highestCumulusFraction(float coverage)
{
    float highest = -1.0f;
    for (int i = 0; i <= 4096; ++i)
        if (glsl::layerMayHoldCloud(CLOUD_TYPE_CUMULUS, float(i) / 4096.0f, coverage, 0.0f))
            highest = float(i) / 4096.0f;
    return highest;
}

// The shaders' density before detail (cloud_density.glsl) of a non-anvil layer for a base noise value in [0, 1].
float layerDensity(int type, float h, float coverage, float anvilAmount, float noise)
{
    float shape = glsl::equalizeBaseShape(noise) * glsl::cloudHeightProfile(type, h);
    float c = coverage * glsl::coverageHeightFactor(type, h);
    if (type == CLOUD_TYPE_CUMULONIMBUS)
        shape = glsl::anvilShape(shape, h, anvilAmount);
    return glsl::applyCoverage(shape, c);
}

}  // namespace

TEST(ColumnBounds, ACoveredTexelBoundsItsNeighbourhoodAndNothingElse)
{
    WeatherWindow w = emptyWindow();
    // A full stratus layer: cloud may reach its top (a cumulus has domes: CumulusDomesLowerTheTop).
    setLayer(w, 0, 5, 7, 1.0f, 1000.0f, 2000.0f, CLOUD_TYPE_STRATUS);
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
            setLayer(w, 2, i, j, 1.0f, 900.0f + 10.0f * float(i), 1700.0f, CLOUD_TYPE_STRATUS);
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
            setLayer(w, 2, i, j, 1.0f, 5000.0f, 9000.0f, CLOUD_TYPE_STRATUS);
    // An anvil slab over the far corner, higher than anything else (thick enough to reach its top).
    setLayer(w, WEATHER_WINDOW_ANVIL_SLICE, 14, 14, 1.0f, 9000.0f, 12000.0f);
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

// A cumulus field of coverage 0.4 holds no cloud in the top of its layer (the domes): the bound's top lies
// below the layer's, but above every height the genus may fill at that coverage. More coverage, higher.
TEST(ColumnBounds, CumulusDomesLowerTheTop)
{
    for (float coverage : {0.2f, 0.4f, 0.7f})
    {
        WeatherWindow w = emptyWindow();
        for (uint32_t j = 0; j < kSize; ++j)
            for (uint32_t i = 0; i < kSize; ++i)
                setLayer(w, 0, i, j, coverage, 1200.0f, 3200.0f);
        const ColumnBound b = columnBoundAt(buildColumnBounds(w), kSize, 0, 8, 8);
        const float highestM = 1200.0f + highestCumulusFraction(coverage) * 2000.0f;
        std::printf("cumulus coverage %.1f: cloud up to %.0f m, bound %.0f m (layer top 3200 m)\n", double(coverage),
                    double(highestM), double(b.maxTopM));
        EXPECT_GE(b.maxTopM, highestM + COLUMN_BOUNDS_UNIT_M);
        EXPECT_LE(b.maxTopM, highestM + 3.0f * COLUMN_BOUNDS_UNIT_M);
        // The base ramp of the profile leaves the lowest few metres empty too.
        EXPECT_LE(b.minBaseM, 1200.0f + 0.05f * 2000.0f);
        EXPECT_GE(b.minBaseM, 1200.0f - 2.0f * COLUMN_BOUNDS_UNIT_M);
    }
    // 0.4 (the built-in field): cloud ends near 70 % of the layer, 600 m under its top.
    EXPECT_LT(highestCumulusFraction(0.4f), 0.75f);
    EXPECT_GT(highestCumulusFraction(0.4f), 0.6f);
    EXPECT_LT(highestCumulusFraction(0.2f), highestCumulusFraction(0.4f));
    // A column takes the largest coverage of its neighbourhood, and any genus there.
    WeatherWindow w = emptyWindow();
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            setLayer(w, 0, i, j, 0.2f, 1200.0f, 3200.0f);
    setLayer(w, 0, 9, 9, 0.7f, 1200.0f, 3200.0f);
    setLayer(w, 0, 4, 4, 0.2f, 1200.0f, 3200.0f, CLOUD_TYPE_STRATUS);
    const std::vector<uint8_t> atlas = buildColumnBounds(w);
    EXPECT_GE(columnBoundAt(atlas, kSize, 0, 8, 8).maxTopM, 1200.0f + highestCumulusFraction(0.7f) * 2000.0f);
    EXPECT_LT(columnBoundAt(atlas, kSize, 0, 12, 12).maxTopM, 1200.0f + highestCumulusFraction(0.7f) * 2000.0f);
    const HeightFractionRange stratus = layerCloudRange(CLOUD_TYPE_STRATUS, 0.2f);
    EXPECT_GE(columnBoundAt(atlas, kSize, 0, 5, 5).maxTopM, 1200.0f + stratus.hi * 2000.0f);
}

// Where the extent rules cloud out, the density is 0 for every noise value: random genera, heights,
// coverages and noise, the anvil slab too; and the ruled-out part is not nothing (the domes, the anvil's edge).
TEST(ColumnBounds, CloudExtentRulesOutOnlyEmptyPoints)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int ruledOut = 0;
    for (int n = 0; n < 200000; ++n)
    {
        const int type = int(rng() % (CLOUD_TYPE_STRATUS + 1));
        const float h = unit(rng), coverage = unit(rng), anvilAmount = unit(rng);
        const bool anvil = n % 4 == 0;
        const bool may = anvil ? glsl::anvilSlabMayHoldCloud(h, coverage)
                               : glsl::layerMayHoldCloud(type, h, coverage, anvilAmount);
        if (may)
            continue;
        ++ruledOut;
        // The equalized noise is largest for the largest texel value (1): try it and a few below.
        for (float noise : {1.0f, 0.99f, 0.9f, unit(rng)})
        {
            const float slab = glsl::equalizeBaseShape(noise) * glsl::anvilSlabProfile(h, coverage);
            const float d = anvil ? glsl::applyCoverage(slab, glsl::saturate1(coverage * 1.8f))
                                  : layerDensity(type, h, coverage, anvilAmount, noise);
            ASSERT_EQ(d, 0.0f) << "type " << type << " h " << h << " coverage " << coverage << " anvil " << anvil;
        }
    }
    EXPECT_GT(ruledOut, 20000);
    // The tables behind the column bounds hold at least every height the functions allow.
    for (int type = 0; type <= CLOUD_TYPE_STRATUS; ++type)
        for (float coverage : {0.05f, 0.3f, 0.5f, 0.8f, 1.0f})
        {
            const HeightFractionRange r = layerCloudRange(type, coverage);
            for (int i = 0; i <= 2000; ++i)
            {
                const float h = float(i) / 2000.0f;
                if (glsl::layerMayHoldCloud(type, h, coverage, 1.0f))
                {
                    ASSERT_TRUE(h >= r.lo && h <= r.hi) << "type " << type << " coverage " << coverage << " h " << h;
                }
            }
        }
    EXPECT_TRUE(layerCloudRange(CLOUD_TYPE_CUMULUS, std::numeric_limits<float>::quiet_NaN()).lo == 0.0f);
    EXPECT_TRUE(layerCloudRange(CLOUD_TYPE_CUMULUS, std::numeric_limits<float>::quiet_NaN()).hi == 1.0f);
}
