// SPDX-License-Identifier: MIT
// A new weather staged off the frame path (skyservice/weather/weather_stage.h), on the GPU (lavapipe,
// validation on, small images, test quality):
//  - frames keep drawing the old weather, byte for byte, until the new one's window is ready; the first
//    frame that draws it is byte for byte a one-shot render with it; no window is made on the frame path;
//  - the swap frame drops the reprojection history (as setWeather does), the frames before keep it; a
//    small step (StageHistory::Keep, a fade step) keeps it, unless it replaced a new weather not drawn yet;
//  - a bad staged weather (empty, wrong field sizes) is refused and the last good one stays;
//  - a flight during which a weather is staged makes no window on the frame path either.
// It prints the CPU time of the frame that first draws a new weather, set synchronously and staged.
#include "skyservice/render/renderer.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class WeatherSwap : public GpuFixture
{
protected:
    static RenderResult render(const ViewRequest& view, const QualitySettings& q = testQuality())
    {
        return renderOk(view, q);
    }
};

ViewRequest overhead()
{
    ViewRequest v = lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z");
    v.width = 64;
    v.height = 36;
    return v;
}

WeatherSnapshot scattered() { return uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2600.0f); }
WeatherSnapshot overcast() { return uniformLayer(1.0f, CloudType::Stratus, 1000.0f, 1800.0f); }

constexpr int kMaxFramesToSwap = 500;

}  // namespace

TEST_F(WeatherSwap, StagedWeatherSwapsInOffTheFramePathAndMatchesAOneShotRender)
{
    const ViewRequest v = overhead();
    const WindowPrefetch& p = renderer->weather.prefetch;
    const WeatherSnapshot weathers[2] = {scattered(), overcast()};
    render(v);  // the suite's first frame also builds the atmosphere tables: not part of the figures
    for (int round = 0; round < 2; ++round)
    {
        const WeatherSnapshot& from = weathers[round];
        const WeatherSnapshot& to = weathers[1 - round];
        setWeather(*renderer, from);
        RenderResult sync = render(v);  // what setWeather costs: the window made on the frame path
        RenderResult old = render(v);   // a frame that reuses its window
        const uint64_t madeBefore = p.madeOnFrame;

        const uint64_t version = stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(to));
        RenderResult swap;
        int framesBefore = 0;
        for (; framesBefore < kMaxFramesToSwap; ++framesBefore)
        {
            RenderResult f = render(v);
            if (f.weatherVersion == version)
            {
                swap = std::move(f);
                break;
            }
            EXPECT_EQ(f.weatherVersion, old.weatherVersion);
            EXPECT_EQ(f.displayRgba8, old.displayRgba8) << "a frame before the swap draws the old weather";
        }
        ASSERT_LT(framesBefore, kMaxFramesToSwap) << "the staged weather never swapped in";
        EXPECT_GE(framesBefore, 1) << "the frame right after staging draws the old weather (it never waits)";
        EXPECT_EQ(p.madeOnFrame, madeBefore) << "a staged weather's window is made on the worker";
        EXPECT_FALSE(weatherStagePending(*renderer));
        EXPECT_NE(swap.displayRgba8, old.displayRgba8);

        // One-shot: the same weather set synchronously and the same pose give the same bytes.
        setWeather(*renderer, to);
        RenderResult oneShot = render(v);
        EXPECT_EQ(swap.displayRgba8, oneShot.displayRgba8);
        EXPECT_EQ(swap.cloudRgbaHalf, oneShot.cloudRgbaHalf);
        EXPECT_EQ(swap.linearRgbaHalf, oneShot.linearRgbaHalf);
        EXPECT_EQ(swap.weatherValidTimeUnixS, to.validTimeUnixS);
        std::printf("new weather, CPU setup of the frame that first draws it: setWeather %.1f ms, staged %.1f ms "
                    "(a frame reusing its window %.1f ms); %d frames drew the old weather meanwhile\n",
                    sync.cpuSetupMs, swap.cpuSetupMs, old.cpuSetupMs, framesBefore);
    }
}

TEST_F(WeatherSwap, TheSwapFrameDropsTheReprojectionHistoryAndTheFramesBeforeKeepIt)
{
    QualitySettings q = testQuality();
    q.reprojected = true;
    const ViewRequest v = overhead();
    setWeather(*renderer, scattered());
    render(v, q);
    render(v, q);
    ASSERT_EQ(lastHistoryDropReason(*renderer), "");
    const uint64_t version = stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(overcast()));
    int frames = 0;
    for (; frames < kMaxFramesToSwap; ++frames)
    {
        RenderResult f = render(v, q);
        if (f.weatherVersion == version)
            break;
        EXPECT_EQ(lastHistoryDropReason(*renderer), "") << "frame " << frames << " before the swap";
    }
    ASSERT_LT(frames, kMaxFramesToSwap);
    EXPECT_EQ(lastHistoryDropReason(*renderer), "no history");
    render(v, q);
    EXPECT_EQ(lastHistoryDropReason(*renderer), "");
}

TEST_F(WeatherSwap, ASmallStagedStepKeepsTheReprojectionHistory)
{
    QualitySettings q = testQuality();
    q.reprojected = true;
    const ViewRequest v = overhead();
    setWeather(*renderer, scattered());
    render(v, q);
    render(v, q);
    ASSERT_EQ(lastHistoryDropReason(*renderer), "");
    const uint64_t& drops = renderer->reconstruct.reprojection.drops;
    // Stages `w` and renders until it swaps in; true when the swap frame kept the history.
    auto swapIn = [&](const WeatherSnapshot& w, StageHistory history, bool dropFirst = false)
    {
        if (dropFirst) // a new weather staged just before, replaced by the small step before it swapped in
            stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(overcast()));
        const uint64_t version =
            stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(w), StageSwap::WhenReady, history);
        for (int frames = 0; frames < kMaxFramesToSwap; ++frames)
            if (render(v, q).weatherVersion == version)
                return lastHistoryDropReason(*renderer).empty();
        ADD_FAILURE() << "the staged weather never swapped in";
        return false;
    };
    const uint64_t before = drops;
    EXPECT_TRUE(swapIn(uniformLayer(0.53f, CloudType::Cumulus, 1200.0f, 2600.0f), StageHistory::Keep))
        << "a fade step dropped the history: " << lastHistoryDropReason(*renderer);
    EXPECT_EQ(drops, before);
    EXPECT_FALSE(swapIn(overcast(), StageHistory::Drop)) << "a new weather kept the history";
    EXPECT_EQ(drops, before + 1);
    render(v, q);
    EXPECT_FALSE(swapIn(uniformLayer(0.97f, CloudType::Stratus, 1000.0f, 1800.0f), StageHistory::Keep, true))
        << "a small step over a new weather never drawn kept the history";
    EXPECT_EQ(drops, before + 2);
}

TEST_F(WeatherSwap, ABadStagedWeatherKeepsTheLastGoodOne)
{
    const ViewRequest v = overhead();
    setWeather(*renderer, scattered());
    RenderResult good = render(v);
    WeatherSnapshot wrongSizes = overcast();
    wrongSizes.layers[0].topAltitudeM.resize(5);
    const std::pair<const char*, WeatherSnapshot> bad[] = {{"grid", WeatherSnapshot{}}, {"topAltitudeM", wrongSizes}};
    for (const auto& [expect, snapshot] : bad)
    {
        stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(snapshot));
        for (int i = 0; i < kMaxFramesToSwap && weatherStagePending(*renderer); ++i)
        {
            RenderResult f = render(v);
            EXPECT_EQ(f.weatherVersion, good.weatherVersion);
            EXPECT_EQ(f.displayRgba8, good.displayRgba8);
        }
        EXPECT_FALSE(weatherStagePending(*renderer));
        EXPECT_NE(renderer->weather.stage.lastError.find(expect), std::string::npos) << renderer->weather.stage.lastError;
        RenderResult after = render(v);
        EXPECT_EQ(after.weatherVersion, good.weatherVersion);
        EXPECT_EQ(after.displayRgba8, good.displayRgba8);
    }
}

TEST_F(WeatherSwap, AFlightWithAStagedWeatherMakesNoWindowOnTheFramePath)
{
    // North at 300 m per frame over 4 lattice cells (as window.WindowMotion's flight), a new weather
    // staged at the 5th frame: its window is made for the node the eye is in when the job runs, made
    // again if the eye left that cell meanwhile; the old weather's next-cell windows keep coming.
    setWeather(*renderer, isolatedCell(45.06, 7.07, 1500.0, CloudType::Cumulus, 1500.0f, 2600.0f));
    const WeatherSnapshot next = isolatedCell(45.06, 7.07, 3000.0, CloudType::Stratocumulus, 1200.0f, 2000.0f);
    const WindowPrefetch& p = renderer->weather.prefetch;
    ViewRequest v = lookUp(44.99, 7.0, 2000.0, 0.0, "2026-06-21T12:00:00Z");
    v.pose.headingDeg = 45.0;
    v.fovYDeg = 40.0;
    v.width = 48;
    v.height = 27;
    const double stepDeg = 300.0 / 111132.0;  // metres per degree of latitude at 45 N (Torge)
    uint64_t madeAfterFirst = 0, version = 0;
    RenderResult swap;
    ViewRequest swapView;
    for (int k = 0; k < 30; ++k)
    {
        ViewRequest f = v;
        f.pose.latDeg = v.pose.latDeg + k * stepDeg;
        if (k == 5)
            version = stageWeather(*renderer, std::make_shared<const WeatherSnapshot>(next));
        RenderResult r = render(f);
        if (k == 0)
            madeAfterFirst = p.madeOnFrame;
        if (version != 0 && r.weatherVersion == version && swap.displayRgba8.empty())
        {
            swap = std::move(r);
            swapView = f;
        }
    }
    ASSERT_FALSE(swap.displayRgba8.empty()) << "the staged weather never swapped in during the flight";
    EXPECT_EQ(p.madeOnFrame, madeAfterFirst) << "only the first frame made its window itself";
    // The swap frame is a one-shot render of its pose with the new weather.
    render(lookUp(10.0, 7.0, 2000.0, 0.0, "2026-06-21T12:00:00Z"));
    setWeather(*renderer, next);
    RenderResult oneShot = render(swapView);
    EXPECT_EQ(swap.displayRgba8, oneShot.displayRgba8);
    EXPECT_EQ(swap.cloudRgbaHalf, oneShot.cloudRgbaHalf);
}
