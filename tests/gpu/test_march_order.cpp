// SPDX-License-Identifier: MIT
// The launch order of the march's workgroup rows (shaders/shared/march_order.h) on the available Vulkan
// device (lavapipe in CI), validation on.
#include "skyservice/render/march_order.h"
#include "skyservice/render/renderer.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class MarchOrderGpu : public GpuFixture
{
};

// Whether any pixel of image rows [y0, y1) has a cloud alpha above 0.5.
bool rowsHoldCloud(const RenderResult& r, uint32_t y0, uint32_t y1)
{
    for (uint32_t y = y0; y < std::min(y1, r.height); ++y)
        for (uint32_t x = 0; x < r.width; ++x)
            if (glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]) > 0.5f)
                return true;
    return false;
}

}  // namespace

// Full-resolution frames of the built-in Cb, once in the interleaved order and once costliest first by
// what the first frame counted: the same bytes, the same counts, and the costly rows are the cloudy ones.
TEST_F(MarchOrderGpu, CostliestFirstChangesNoPixelAndFollowsTheLastCount)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    RenderTuning interleaved;
    interleaved.costOrderedMarch = false;
    QualitySettings costly = testQuality();
    const uint32_t rows = (180 + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D;

    RenderResult a = renderTuned(v, costly, interleaved);
    ASSERT_EQ(a.marchRowOrder, interleavedRowOrder(rows));
    ASSERT_EQ(a.marchRowLookups.size(), size_t(rows));
    RenderResult b = renderOk(v, costly);
    EXPECT_EQ(b.marchRowOrder, costliestFirstRowOrder(a.marchRowLookups.data(), rows, renderer->march.dispatchRanges));
    EXPECT_NE(b.marchRowOrder, a.marchRowOrder);
    EXPECT_EQ(a.displayRgba8, b.displayRgba8);
    EXPECT_EQ(a.cloudRgbaHalf, b.cloudRgbaHalf);
    EXPECT_EQ(a.cloudDepthM, b.cloudDepthM);
    // Each workgroup marches the same rays in either order, so it counts the same.
    EXPECT_EQ(a.marchRowLookups, b.marchRowLookups);

    // Rows with cloud cost more than rows of clear sky (whose rays still cross the shell, searching).
    double cloudy = 0, clear = 0;
    int cloudyRows = 0, clearRows = 0;
    for (uint32_t row = 0; row < rows; ++row)
    {
        const bool cloud = rowsHoldCloud(a, row * WORKGROUP_SIZE_2D, (row + 1) * WORKGROUP_SIZE_2D);
        (cloud ? cloudy : clear) += a.marchRowLookups[row];
        ++(cloud ? cloudyRows : clearRows);
    }
    ASSERT_GT(cloudyRows, 2);
    ASSERT_GT(clearRows, 0);
    std::printf("lookups per row: cloudy %.0f (%d rows), clear %.0f (%d rows)\n", cloudy / cloudyRows, cloudyRows,
                clear / clearRows, clearRows);
    EXPECT_GT(cloudy / cloudyRows, 2.0 * clear / clearRows);
    EXPECT_GT(clear, 0.0);
}

// A reprojected frame orders its block rows; a frame of another shape (here: full resolution after it)
// starts again from the interleaved order, and a reprojected frame after that follows its own count.
TEST_F(MarchOrderGpu, ReprojectedFramesOrderTheirOwnRows)
{
    const ViewRequest v = builtinCumulonimbus320(*renderer);
    QualitySettings full = testQuality();
    QualitySettings reprojected = reprojectedQuality();
    RenderResult first = renderOk(v, reprojected);
    ASSERT_GT(first.marchBlockPx, 1u);
    const uint32_t blockRows = (180 + first.marchBlockPx - 1) / first.marchBlockPx;
    const uint32_t rows = (blockRows + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D;
    ASSERT_EQ(first.marchRowLookups.size(), size_t(rows));
    RenderResult fullFrame = renderOk(v, full);
    EXPECT_EQ(fullFrame.marchRowOrder, interleavedRowOrder((180 + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D));
    RenderResult second = renderOk(v, reprojected);
    ASSERT_EQ(second.marchBlockPx, first.marchBlockPx);
    EXPECT_EQ(second.marchRowOrder, interleavedRowOrder(rows));  // the last count was the full frame's
    RenderResult third = renderOk(v, reprojected);
    EXPECT_EQ(third.marchRowOrder, costliestFirstRowOrder(second.marchRowLookups.data(), rows,
                                                          renderer->march.dispatchRanges));
    EXPECT_GT(std::accumulate(third.marchRowLookups.begin(), third.marchRowLookups.end(), 0ull), 0ull);
}
