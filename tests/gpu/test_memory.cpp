// SPDX-License-Identifier: MIT
// Device memory (the budget: device memory at 1920x1080 <= 64 MB, all textures and buffers included, in
// full-resolution and reprojected frames), counted by the renderer's MemoryTracker on lavapipe with
// validation on: the linear frame exists only while frames ask for it, the reprojection's fresh images
// follow the march block back down when the eye leaves a cloud (keeping the history), and a 1080p frame
// of either mode without the linear frame stays within the budget.
#include "skyservice/render/renderer.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace sky;
using namespace sky::testscenes;

namespace
{

constexpr uint64_t kBudgetBytes = 64000000;  // the device-memory budget at 1080p: 64 MB

class Memory : public GpuFixture
{
protected:
    static uint64_t totalBytes()
    {
        std::lock_guard<std::mutex> lock(renderer->memory.mutex);
        return renderer->memory.totalBytes;
    }
    static uint64_t liveBytes(const std::string& name)
    {
        std::lock_guard<std::mutex> lock(renderer->memory.mutex);
        auto it = renderer->memory.liveBytes.find(name);
        return it == renderer->memory.liveBytes.end() ? 0 : it->second;
    }
};

}  // namespace

TEST_F(Memory, LinearFrameOnlyWhileFramesAskForIt)
{
    setWeather(*renderer, uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 3000.0f));
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 30.0, "2026-06-21T12:00:00Z");
    v.width = 96;
    v.height = 54;
    for (bool reprojected : {false, true})
    {
        QualitySettings q = reprojected ? reprojectedQuality() : testQuality();
        const uint32_t index = renderer->reconstruct.reprojection.frameIndex;  // the same march phase for both
        dropHistory(*renderer);
        RenderResult with = renderOk(v, q);
        const uint64_t linearBytes = liveBytes("linear frame"), totalWith = totalBytes();
        EXPECT_GE(linearBytes, uint64_t(v.width) * v.height * 8) << "RGBA16F";
        EXPECT_EQ(with.linearRgbaHalf.size(), size_t(v.width) * v.height * 4);

        v.linearOutput = false;
        dropHistory(*renderer);
        renderer->reconstruct.reprojection.frameIndex = index;
        RenderResult without = renderOk(v, q);
        EXPECT_EQ(liveBytes("linear frame"), 0u);
        EXPECT_EQ(totalBytes(), totalWith - linearBytes) << (reprojected ? "reprojected" : "full");
        EXPECT_TRUE(without.linearRgbaHalf.empty());
        // Skipping the linear write changes nothing else.
        EXPECT_EQ(without.displayRgba8, with.displayRgba8);
        EXPECT_EQ(without.cloudRgbaHalf, with.cloudRgbaHalf);
        EXPECT_EQ(without.cloudDepthM, with.cloudDepthM);

        v.linearOutput = true;  // asked for again: made again
        RenderResult again = renderOk(v, q);
        EXPECT_EQ(liveBytes("linear frame"), linearBytes);
        EXPECT_EQ(again.linearRgbaHalf.size(), with.linearRgbaHalf.size());
    }
}

// Inside a stratus deck with every pixel marched there (block 1, RenderTuning::insideCloudBlockPx 1): the fresh images
// are full size. 1000 m above
// its top (beyond the 300 m near zone, within the 5 km history limit) the block is 4 again: they
// shrink back to one pixel per 4x4 block, and the history survives.
TEST_F(Memory, FreshImagesShrinkWhenTheEyeLeavesTheCloudAndHistoryStays)
{
    setWeather(*renderer, uniformLayer(1.0f, CloudType::Stratus, 1000.0f, 3000.0f));
    ViewRequest v = lookUp(45.0, 7.0, 2000.0, 5.0, "2026-06-21T12:00:00Z");
    v.width = 64;
    v.height = 36;
    QualitySettings q = reprojectedQuality();
    v.linearOutput = false;
    renderer->tuning.insideCloudBlockPx = 1;
    const struct DefaultTuningAfter  // for the suite's next tests, however this one ends
    {
        ~DefaultTuningAfter() { renderer->tuning = RenderTuning{}; }
    } restore;
    RenderResult inside = renderOk(v, q);
    ASSERT_EQ(inside.marchBlockPx, 1u) << inside.marchBlockReason;
    EXPECT_EQ(renderer->march.freshCloudImage.extent.width, v.width);
    EXPECT_EQ(renderer->march.freshCloudImage.extent.height, v.height);
    const uint64_t insideBytes = totalBytes();

    v.pose.altitudeM = 4000.0;
    RenderResult above = renderOk(v, q);
    ASSERT_EQ(above.marchBlockPx, 4u) << above.marchBlockReason;
    EXPECT_TRUE(lastHistoryDropReason(*renderer).empty()) << lastHistoryDropReason(*renderer);
    // One texel per 4x4 block, and beside and below them room for the columns and rows a turn or a pitch
    // change marches in full (reprojection.h NewLines): 4 texels per line.
    const uint32_t freshWidth = v.width / 4 + maxNewColumns(v.width) * 4;
    EXPECT_EQ(renderer->march.freshCloudImage.extent.width, freshWidth);
    EXPECT_EQ(renderer->march.freshCloudImage.extent.height, v.height / 4 + maxNewRows(v.height) * 4);
    EXPECT_EQ(renderer->march.freshDepthImage.extent.width, freshWidth);
    EXPECT_LT(totalBytes(), insideBytes);
    std::printf("64x36 reprojected: %llu bytes inside the deck, %llu above it\n", (unsigned long long)insideBytes,
                (unsigned long long)totalBytes());
}

// The budget at 1920x1080, clear sky (the march block is 4: no cloud near the eye), no linear
// frame (what the service's shm and vulkan transports and sky-bench make), every allocation counted. One
// renderer per mode, as the service runs: a renderer that made both keeps the images of both (full
// frames between reprojected ones must not disturb the history).
TEST(MemoryBudget, At1080pEachModeStaysWithin64MB)
{
    for (bool reprojected : {false, true})
    {
        Renderer r;
        RendererOptions options;
        options.context.validation = true;
        options.context.quiet = true;
        ASSERT_TRUE(createRenderer(r, options).ok());
        setWeather(r, clearSky());
        ViewRequest v = lookUp(45.0, 7.0, 300.0, 10.0, "2026-06-21T12:00:00Z");
        v.width = 1920;
        v.height = 1080;
        QualitySettings q = reprojected ? reprojectedQuality() : testQuality();
        v.linearOutput = false;
        v.copyToHost = false;
        RenderResult result;
        for (int k = 0; k < 2; ++k)
            ASSERT_TRUE(renderView(r, v, q, result).ok());
        const uint64_t total = r.memory.totalBytes;
        // What the service renders for a display subscriber: the display read back into host-cached memory
        // (system RAM, counted apart), no device memory added.
        v.copyToHost = true;
        v.readback = kReadDisplay;
        ASSERT_TRUE(renderView(r, v, q, result).ok());
        ASSERT_TRUE(renderView(r, v, q, result).ok());
        EXPECT_EQ(r.memory.totalBytes, total) << (reprojected ? "reprojected" : "full");
        EXPECT_LE(r.memory.hostReadbackBytes, 2 * (uint64_t(1920) * 1080 * 4 + 65536));
        std::printf("1920x1080 %s, display read back: %.2f MB device, %.2f MB host readback\n",
                    reprojected ? "reprojected" : "full", double(r.memory.totalBytes) * 1e-6,
                    double(r.memory.hostReadbackBytes) * 1e-6);
        v.copyToHost = false;
        v.linearOutput = true;
        ASSERT_TRUE(renderView(r, v, q, result).ok());
        std::printf("1920x1080 %s: %.2f MB (%.2f MiB) without the linear frame, %.2f MB with it\n",
                    reprojected ? "reprojected" : "full", double(total) * 1e-6, double(total) / 1048576.0,
                    double(r.memory.totalBytes) * 1e-6);
        EXPECT_LE(total, kBudgetBytes) << (reprojected ? "reprojected" : "full");
        EXPECT_EQ(r.ctx.validationMessages.load(), 0u);
        destroyRenderer(r);
    }
}
