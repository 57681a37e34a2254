// SPDX-License-Identifier: MIT
// Temporal reprojection (reprojection.*): the Bayer phase order and the history limits on the
// CPU (and the march block near clouds), and on the GPU (lavapipe, validation on, 128x72, test quality):
// a still view converges to the full-resolution image, a teleport, an explicit drop, a weather swap or a
// time jump leaves no pixel of the old view, and a slow pan stays close to full-resolution renders.
//
// PSNR (tests/gpu/image_compare.h) is computed on the cloud image over all pixels, with the peak = the
// largest channel value of the full-resolution reference. The tone-mapped display PSNR is printed too.
#include "skyservice/render/renderer.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/image_compare.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class Reprojection : public GpuFixture
{
protected:
    void SetUp() override
    {
        setWeather(*renderer, reprojectionWeather());
    }
    RenderResult render(const ViewRequest& view, const QualitySettings& q) { return renderOk(view, q); }
};

}  // namespace

TEST(ReprojectionCpu, SixteenConsecutiveFramesMarchEveryBlockPosition)
{
    for (uint32_t start : {0u, 5u, 1000003u})
    {
        std::set<uint32_t> seen;
        for (uint32_t k = 0; k < 16; ++k)
        {
            glm::uvec2 p = reprojectionPhase(start + k);
            ASSERT_LT(p.x, 4u);
            ASSERT_LT(p.y, 4u);
            seen.insert(p.y * 4 + p.x);
        }
        EXPECT_EQ(seen.size(), 16u) << "start " << start;
    }
    // Consecutive frames are not neighbours in the block (Bayer order spreads them).
    glm::ivec2 a(reprojectionPhase(0)), b(reprojectionPhase(1));
    EXPECT_GE(std::abs(a.x - b.x) + std::abs(a.y - b.y), 2);
}

TEST(ReprojectionCpu, HistoryIsDroppedBeyondTheLimits)
{
    ViewRequest v = reprojectionView();
    ReprojectionHistory h;
    h.valid = true;
    h.lastView = v;
    h.lastCamera = computeCameraFrame(v.pose);
    std::string why;
    EXPECT_TRUE(historyUsable(h, v, h.lastCamera, why)) << why;

    auto usable = [&](ViewRequest w) { return historyUsable(h, w, computeCameraFrame(w.pose), why); };
    ViewRequest w = v;
    w.pose.latDeg += 1000.0 / 111000.0;  // ~1 km north: kept
    EXPECT_TRUE(usable(w)) << why;
    w.pose.latDeg = v.pose.latDeg + 6000.0 / 111000.0;  // ~6 km: dropped
    EXPECT_FALSE(usable(w));
    EXPECT_NE(why.find("moved"), std::string::npos) << why;
    w = v;
    w.pose.headingDeg += 20.0;
    EXPECT_TRUE(usable(w)) << why;
    w.pose.headingDeg = v.pose.headingDeg + 40.0;
    EXPECT_FALSE(usable(w));
    EXPECT_NE(why.find("turned"), std::string::npos) << why;
    w = v;
    w.unixTimeS += 3600;
    EXPECT_FALSE(usable(w));
    EXPECT_NE(why.find("time"), std::string::npos) << why;
    w = v;
    w.width = 160;
    EXPECT_FALSE(usable(w));
    h.valid = false;
    EXPECT_FALSE(usable(v));
}

TEST_F(Reprojection, StillViewConvergesToTheFullResolutionImage)
{
    ViewRequest v = reprojectionView();
    RenderResult full = render(v, testQuality());
    ASSERT_GT(cloudStats(full).cloudPixels, 200u) << "the scene must show cloud edges";
    dropHistory(*renderer);
    RenderResult first = render(v, reprojectedQuality());
    EXPECT_FALSE(lastHistoryDropReason(*renderer).empty());
    RenderResult frame;
    for (int k = 1; k < 16; ++k)
        frame = render(v, reprojectedQuality());
    EXPECT_TRUE(lastHistoryDropReason(*renderer).empty()) << lastHistoryDropReason(*renderer);
    double psnrFirst = psnrCloud(first, full), psnr16 = psnrCloud(frame, full);
    std::printf("still view: cloud PSNR frame 1 %.1f dB, frame 16 %.1f dB (display %.1f dB)\n", psnrFirst, psnr16,
                psnrDisplay(frame, full));
    EXPECT_GE(psnr16, 40.0);
    EXPECT_GT(psnr16, psnrFirst + 5.0) << "history must add the pixels the first frame did not march";
    EXPECT_TRUE(cloudStats(frame).allFinite);
}

TEST_F(Reprojection, TeleportLeavesNoPixelOfTheOldView)
{
    ViewRequest a = reprojectionView();
    for (int k = 0; k < 16; ++k)
        render(a, reprojectedQuality());
    // 50 km east and turned: the history limits drop it on their own.
    ViewRequest b = a;
    b.pose.lonDeg += 50000.0 / (111000.0 * std::cos(45.0 * M_PI / 180.0));
    b.pose.headingDeg = 90.0;
    uint32_t index = renderer->reconstruct.reprojection.frameIndex;
    RenderResult teleported = render(b, reprojectedQuality());
    EXPECT_FALSE(lastHistoryDropReason(*renderer).empty());
    // The same frame (same march phase) after an explicit drop: identical bytes, so nothing came from A.
    dropHistory(*renderer);
    renderer->reconstruct.reprojection.frameIndex = index;
    RenderResult reset = render(b, reprojectedQuality());
    EXPECT_EQ(teleported.cloudRgbaHalf, reset.cloudRgbaHalf);
    EXPECT_EQ(teleported.cloudDepthM, reset.cloudDepthM);

    // An explicit drop (weather swap, time jump by the caller) on a pose that history would accept,
    // 16 frames later: the same march phase as the reset frame above.
    for (int k = 0; k < 15; ++k)
        render(b, reprojectedQuality());
    ASSERT_EQ(renderer->reconstruct.reprojection.frameIndex, index + 16);
    RenderResult kept = render(b, reprojectedQuality());
    EXPECT_TRUE(lastHistoryDropReason(*renderer).empty());
    dropHistory(*renderer);
    renderer->reconstruct.reprojection.frameIndex = index + 16;
    RenderResult dropped = render(b, reprojectedQuality());
    EXPECT_FALSE(lastHistoryDropReason(*renderer).empty());
    EXPECT_EQ(dropped.cloudRgbaHalf, reset.cloudRgbaHalf) << "a dropped history must not leak into the frame";
    EXPECT_NE(kept.cloudRgbaHalf, dropped.cloudRgbaHalf) << "with history the frame must differ";
}

// A pan of 2 degrees of heading per frame (at 128x72 and 60 degrees, ~2.8 pixels per frame) after 16
// still frames. Measured on the tone-mapped display (whole frame, peak 255) against the same pose rendered
// without history, and on the cloud image (on the reference's radiance scale, psnrCloudScaled).
// The cloud-image bound is low because the full-resolution reference itself is not stable under
// sub-pixel motion at this size (screen-space march jitter and cloud detail finer than a pixel).
// Both bounds are independent of the picture's brightness (a brighter light costs a fixed display peak and
// a fixed cloud peak several dB with nothing reprojected worse): the pan must beat no history by 1.6 dB on
// the display, and the cloud image stay above 17.5 dB, the margins the earlier bounds had under the
// earlier light (octave contribution 0.5, no diffuse remainder). With history dropped before every frame
// of the pan both fail (the measured figures: BENCHMARKS.md, "Test figures").
TEST_F(Reprojection, SlowPanStaysCloseToFullResolution)
{
    ViewRequest v = reprojectionView();
    dropHistory(*renderer);
    for (int k = 0; k < 16; ++k)
        render(v, reprojectedQuality());
    double worstDisplay = 1e9, worstCloud = 1e9;
    RenderResult frame, full;
    for (int k = 1; k <= 8; ++k)
    {
        v.pose.headingDeg += 2.0;
        frame = render(v, reprojectedQuality());
        EXPECT_TRUE(lastHistoryDropReason(*renderer).empty()) << lastHistoryDropReason(*renderer);
        full = render(v, testQuality());
        double pc = psnrCloudScaled(frame, full), pd = psnrDisplay(frame, full);
        std::printf("pan frame %d: cloud PSNR %.1f dB on the radiance scale (%.1f dB against the largest channel), "
                    "display PSNR %.1f dB\n", k, pc, psnrCloud(frame, full), pd);
        worstDisplay = std::min(worstDisplay, pd);
        worstCloud = std::min(worstCloud, pc);
    }
    EXPECT_GE(worstCloud, 17.5);
    // The same last frame without history (same march phase): reprojection must be what makes it good.
    // Without history the fresh pixels are interpolated, not copied as 4x4 blocks, which narrows the
    // margin reprojection has over it (the measured figures: BENCHMARKS.md, "Test figures").
    uint32_t last = renderer->reconstruct.reprojection.frameIndex - 1;
    dropHistory(*renderer);
    renderer->reconstruct.reprojection.frameIndex = last;
    RenderResult fresh = render(v, reprojectedQuality());
    double freshDisplay = psnrDisplay(fresh, full);
    std::printf("last pose without history: cloud PSNR %.1f dB on the radiance scale, display PSNR %.1f dB; "
                "worst of the pan %.1f / %.1f dB\n",
                psnrCloudScaled(fresh, full), freshDisplay, worstCloud, worstDisplay);
    EXPECT_GE(worstDisplay, freshDisplay + 1.6) << "the worst frame of the pan";
    EXPECT_GT(psnrDisplay(frame, full), freshDisplay + 1.5);
}

// A weather swap (setWeather) and a time jump beyond the limit drop history on their own: the frame
// after either is byte-identical to the same frame (same march phase) rendered from no history, and
// the drop reason says why. A time step inside the limit keeps history.
TEST_F(Reprojection, WeatherSwapAndTimeJumpDropHistory)
{
    ViewRequest v = reprojectionView();
    dropHistory(*renderer);
    for (int k = 0; k < 4; ++k)
        render(v, reprojectedQuality());
    auto expectDropped = [&](const ViewRequest& view, const char* what) {
        uint32_t index = renderer->reconstruct.reprojection.frameIndex;
        RenderResult after = render(view, reprojectedQuality());
        std::string why = lastHistoryDropReason(*renderer);
        EXPECT_FALSE(why.empty()) << what;
        dropHistory(*renderer);
        renderer->reconstruct.reprojection.frameIndex = index;
        RenderResult clean = render(view, reprojectedQuality());
        EXPECT_EQ(after.cloudRgbaHalf, clean.cloudRgbaHalf) << what << ": history leaked into the frame";
        return why;
    };
    setWeather(*renderer, uniformLayer(0.6f, CloudType::Stratocumulus, 900.0f, 1500.0f));
    expectDropped(v, "weather swap");
    ViewRequest later = v;
    later.unixTimeS += 1;
    render(later, reprojectedQuality());
    EXPECT_TRUE(lastHistoryDropReason(*renderer).empty()) << "1 s is inside the time limit";
    later.unixTimeS += int64_t(kReprojectionMaxTimeJumpS) + 1;
    std::string why = expectDropped(later, "time jump");
    EXPECT_NE(why.find("time"), std::string::npos) << why;
}

TEST(ReprojectionCpu, MarchBlockIsFinerNearAndInsideACloudLayer)
{
    std::set<uint32_t> seen;
    for (uint32_t k = 7; k < 11; ++k)
        seen.insert(reprojectionPhase(k, 2).y * 2 + reprojectionPhase(k, 2).x);
    EXPECT_EQ(seen.size(), 4u) << "4 consecutive frames march every position of a 2x2 block";
    EXPECT_EQ(reprojectionPhase(5, 1), glm::uvec2(0, 0));

    WeatherWindow window;
    resampleWeatherWindow(uniformLayer(0.7f, CloudType::Stratocumulus, 1500.0f, 2100.0f), 45.0, 7.0, 800000.0,
                          window, WEATHER_WINDOW_SIZE, 150000.0);
    struct Case
    {
        double altitudeM;
        uint32_t blockPx;
    } cases[] = {{1000.0, 4}, {1250.0, 2}, {1500.0, 1}, {1800.0, 1}, {2300.0, 2}, {2500.0, 4}, {9000.0, 4}};
    for (const Case& c : cases)
    {
        MarchBlock b = chooseMarchBlock(window, c.altitudeM);
        EXPECT_EQ(b.blockPx, c.blockPx) << c.altitudeM << " m: " << b.reason;
        EXPECT_EQ(b.reason.empty(), c.blockPx == 4) << b.reason;
    }
    // Inside an overcast layer (coverage >= kOvercastCoverage around the eye) a quarter of the pixels by
    // default (RenderTuning::insideCloudBlockPx 2), every pixel when asked for (1); near it still 2.
    resampleWeatherWindow(uniformLayer(0.9f, CloudType::Stratocumulus, 1500.0f, 2100.0f), 45.0, 7.0, 800000.0,
                          window, WEATHER_WINDOW_SIZE, 150000.0);
    MarchBlock fog = chooseMarchBlock(window, 1800.0);
    EXPECT_EQ(fog.blockPx, 2u) << fog.reason;
    EXPECT_NE(fog.reason.find("inside overcast"), std::string::npos) << fog.reason;
    EXPECT_EQ(chooseMarchBlock(window, 1800.0, glm::dvec2(0.0), 1).blockPx, 1u);
    EXPECT_EQ(chooseMarchBlock(window, 1250.0, glm::dvec2(0.0), 1).blockPx, 2u);
    resampleWeatherWindow(clearSky(), 45.0, 7.0, 800000.0, window, WEATHER_WINDOW_SIZE, 150000.0);
    EXPECT_EQ(chooseMarchBlock(window, 1800.0).blockPx, 4u) << "no cloud around the eye";

    // Windows are centred on a lattice node near the eye, not on it (weather/window_lattice.h): the rule
    // looks around the eye's place on the window. A cell 3.2 km east of the window centre, 1 km wide.
    resampleWeatherWindow(isolatedCell(45.0, 7.04, 1000.0, CloudType::Cumulus, 1500.0f, 2100.0f), 45.0, 7.0,
                          800000.0, window, WEATHER_WINDOW_SIZE, 150000.0);
    EyeOnWindow inCell = placeEyeOnWindow(45.0, 7.0, 45.0, 7.04);
    EXPECT_EQ(chooseMarchBlock(window, 1800.0, inCell.offsetM, 1).blockPx, 1u) << "eye in the cell, every pixel";
    EXPECT_EQ(chooseMarchBlock(window, 1800.0).blockPx, 4u) << "an eye at the window centre is 3.2 km from it";
}
