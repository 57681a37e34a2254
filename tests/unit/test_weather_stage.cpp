// SPDX-License-Identifier: MIT
// CPU side of a new weather prepared off the frame path (skyservice/weather/weather_stage.h) and of the
// speed-dependent window look-ahead (weather/window_provider.h): no GPU, so these run under ASan/UBSan.
//  - a staged weather is never handed out by the step that starts its job, swaps in with exactly the
//    window a frame would make itself for the eye's node, waits for its release when held, is made
//    again for the node the eye moved to, and a newer stage supersedes an older one;
//  - a small step keeps the reprojection history unless it replaced a new weather not swapped in yet;
//  - a bad staged weather (empty grid, wrong field sizes, a maker that fails) is refused with a reason;
//  - the look-ahead covers 1.5 s of motion, within [1.5 km, 20 km]; the node prefetched is the one the
//    eye reaches next, named from the moment it enters the cell before, even at 3000 m/s.
#include "skyservice/render/render_types.h"
#include "skyservice/weather/weather_stage.h"
#include "skyservice/sky/builtin_weather.h"

#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <future>
#include <limits>
#include <stdexcept>
#include <thread>

using namespace sky;

namespace
{

constexpr int64_t kNoon = 1782043200;  // 2026-06-21T12:00:00Z

/// The stages' weather worker (a renderer has one in RendererWeather).
WeatherWorker& worker()
{
    static WeatherWorker w;
    return w;
}

WindowKey keyAt(double latDeg, double lonDeg)
{
    QualitySettings q;
    return WindowKey{0, 0, windowCentreForEye(latDeg, lonDeg), q.windowHalfExtentM, q.windowWarpRadiusM};
}

std::shared_ptr<const WeatherSnapshot> builtin(int64_t t)
{
    return std::make_shared<const WeatherSnapshot>(makeBuiltinWeather(t));
}

/// Steps the stage as frames would (never waiting) until it hands out a weather or drops its own.
std::optional<StagedResult> stepUntilDone(WeatherStage& s, const WindowKey& eye, int* steps = nullptr)
{
    for (int i = 0; i < 20000; ++i)
    {
        if (steps)
            *steps = i + 1;
        std::optional<StagedResult> out = advanceStage(s, worker(), eye, false);
        if (out || !stagePending(s))
            return out;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ADD_FAILURE() << "the staged weather never finished";
    return std::nullopt;
}

/// Steps until the job in flight finished (its result is then collected by the next step).
void waitForJob(WeatherStage& s)
{
    while (s.job.valid() && s.job.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

}  // namespace

TEST(WeatherStage, SwapsInTheWindowAFrameWouldMakeAndNeverOnTheStepThatStartsIt)
{
    WeatherStage s;
    auto weather = builtin(kNoon);
    std::atomic<int> made{0};
    stage(s, 7, [&] { ++made; return weather; }, StageSwap::WhenReady);
    const WindowKey eye = keyAt(44.3, 7.5);
    EXPECT_FALSE(advanceStage(s, worker(), eye, false)) << "the step that starts the job must not wait for it";
    int steps = 0;
    std::optional<StagedResult> out = stepUntilDone(s, eye, &steps);
    ASSERT_TRUE(out);
    EXPECT_EQ(out->version, 7u);
    EXPECT_EQ(out->weather, weather);
    WindowKey expected = eye;
    expected.weatherVersion = 7;
    expected.weatherValidTimeUnixS = kNoon;
    EXPECT_TRUE(out->window->key == expected);
    // The window depends on its key only: the one a frame would make for itself is the same.
    std::shared_ptr<const PreparedWindow> direct = prepareWindow(*weather, expected);
    EXPECT_EQ(out->window->gpuTexelsHalf, direct->gpuTexelsHalf);
    EXPECT_FALSE(stagePending(s));
    EXPECT_EQ(made.load(), 1);
    EXPECT_EQ(s.swapped, 1u);
    EXPECT_EQ(s.windowsMade, 1u);
    EXPECT_TRUE(s.lastError.empty());
    std::printf("the staged window was ready after %d frame steps of 2 ms\n", steps);
}

TEST(WeatherStage, HeldUntilReleasedAndRemadeForTheNodeTheEyeMovedTo)
{
    WeatherStage s;
    std::atomic<int> made{0};
    auto weather = builtin(kNoon);
    stage(s, 3, [&] { ++made; return weather; }, StageSwap::WhenReleased);
    const WindowKey a = keyAt(44.3, 7.5), b = keyAt(44.33, 7.5);  // 3.3 km apart: other nodes
    ASSERT_FALSE(a.centre == b.centre);
    EXPECT_FALSE(advanceStage(s, worker(), a, false));
    waitForJob(s);
    EXPECT_FALSE(advanceStage(s, worker(), a, false)) << "held: ready, but not released";
    ASSERT_TRUE(s.ready);
    // The eye moved into another cell: the window alone is made again (the snapshot is not).
    EXPECT_FALSE(advanceStage(s, worker(), b, false));
    waitForJob(s);
    EXPECT_FALSE(advanceStage(s, worker(), b, false));
    releaseStage(s);
    std::optional<StagedResult> out = advanceStage(s, worker(), b, false);
    ASSERT_TRUE(out);
    EXPECT_TRUE(out->window->key.centre == b.centre);
    EXPECT_EQ(made.load(), 1);
    EXPECT_EQ(s.windowsMade, 2u);
}

TEST(WeatherStage, ANewerStageSupersedesAnOlderOneWhoseJobStillRuns)
{
    WeatherStage s;
    std::promise<void> gate;
    std::shared_future<void> open = gate.get_future().share();
    auto older = builtin(kNoon), newer = builtin(kNoon + 3600);
    stage(s, 1, [open, older] { open.wait(); return older; }, StageSwap::WhenReady);
    const WindowKey eye = keyAt(44.3, 7.5);
    EXPECT_FALSE(advanceStage(s, worker(), eye, false));  // job 1 starts and blocks on the gate
    stage(s, 2, [newer] { return newer; }, StageSwap::WhenReady);
    EXPECT_FALSE(advanceStage(s, worker(), eye, false));  // job 1 still runs: never abandoned, never waited for
    EXPECT_NE(s.jobTicket, s.ticket);
    gate.set_value();
    std::optional<StagedResult> out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_EQ(out->version, 2u);
    EXPECT_EQ(out->weather, newer);
    EXPECT_EQ(s.swapped, 1u);
}

// One weather (one version) sampled at two times: the service re-stages a running clock's next sample
// under the loaded weather's version. The second stage supersedes the first all the same, and its window
// is keyed by its own valid time.
TEST(WeatherStage, ASecondSampleOfOneVersionSupersedesTheFirst)
{
    WeatherStage s;
    std::promise<void> gate;
    std::shared_future<void> open = gate.get_future().share();
    auto first = builtin(kNoon), second = builtin(kNoon + 60);
    stage(s, 4, [open, first] { open.wait(); return first; }, StageSwap::WhenReady);
    const WindowKey eye = keyAt(44.3, 7.5);
    EXPECT_FALSE(advanceStage(s, worker(), eye, false));  // the first sample's job starts, blocked
    stage(s, 4, [second] { return second; }, StageSwap::WhenReady);
    gate.set_value();
    std::optional<StagedResult> out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_EQ(out->version, 4u);
    EXPECT_EQ(out->weather, second) << "the superseded sample's result was taken";
    EXPECT_EQ(out->window->key.weatherValidTimeUnixS, kNoon + 60);
    EXPECT_EQ(s.swapped, 1u);
}

// A small step (StageHistory::Keep) swaps in keeping the reprojection history; one that replaced a new
// weather before it swapped in does not (the frames still draw the weather before that one), one that
// replaced another small step does.
TEST(WeatherStage, ASmallStepKeepsTheHistoryUnlessItReplacedANewWeather)
{
    const WindowKey eye = keyAt(44.3, 7.5);
    auto weather = builtin(kNoon);
    auto make = [weather] { return weather; };
    WeatherStage s;
    stage(s, 1, make, StageSwap::WhenReady, StageHistory::Keep);
    std::optional<StagedResult> out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_TRUE(out->keepHistory);
    stage(s, 2, make, StageSwap::WhenReady);
    stage(s, 3, make, StageSwap::WhenReady, StageHistory::Keep);
    out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_EQ(out->version, 3u);
    EXPECT_FALSE(out->keepHistory) << "a small step over a new weather never drawn";
    stage(s, 4, make, StageSwap::WhenReady, StageHistory::Keep);
    stage(s, 5, make, StageSwap::WhenReady, StageHistory::Keep);
    out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_TRUE(out->keepHistory);
    stage(s, 6, make, StageSwap::WhenReady);
    out = stepUntilDone(s, eye);
    ASSERT_TRUE(out);
    EXPECT_FALSE(out->keepHistory);
}

TEST(WeatherStage, BadWeatherIsRefusedWithAReason)
{
    WeatherSnapshot wrongSizes = makeBuiltinWeather(kNoon);
    wrongSizes.layers[0].coverage.resize(3);
    struct Case
    {
        const char* what;
        WeatherMaker make;
        const char* expect;
    } cases[] = {
        {"empty", [] { return std::make_shared<const WeatherSnapshot>(); }, "grid"},
        {"wrong sizes", [wrongSizes] { return std::make_shared<const WeatherSnapshot>(wrongSizes); }, "coverage"},
        {"no snapshot", [] { return std::shared_ptr<const WeatherSnapshot>(); }, "no snapshot"},
        {"throws", []() -> std::shared_ptr<const WeatherSnapshot> { throw std::runtime_error("disk on fire"); },
         "disk on fire"},
    };
    WeatherStage s;
    uint64_t version = 0;
    for (const Case& c : cases)
    {
        stage(s, ++version, c.make, StageSwap::WhenReady);
        EXPECT_FALSE(stepUntilDone(s, keyAt(44.3, 7.5))) << c.what;
        EXPECT_FALSE(stagePending(s)) << c.what;
        EXPECT_NE(s.lastError.find(c.expect), std::string::npos) << c.what << ": " << s.lastError;
    }
    EXPECT_EQ(s.refused, 4u);
    EXPECT_EQ(s.swapped, 0u);
    EXPECT_EQ(s.windowsMade, 0u);
}

TEST(WeatherStage, WaitingBlocksUntilReadyAndCancelDropsTheResult)
{
    WeatherStage s;
    stage(s, 5, [] { return builtin(kNoon); }, StageSwap::WhenReleased);
    std::optional<StagedResult> out = advanceStage(s, worker(), keyAt(44.3, 7.5), true);  // nothing on screen yet
    ASSERT_TRUE(out) << "with wait, the staged weather is handed out at once, held or not";
    EXPECT_EQ(out->version, 5u);

    stage(s, 6, [] { return builtin(kNoon); }, StageSwap::WhenReady);
    EXPECT_FALSE(advanceStage(s, worker(), keyAt(44.3, 7.5), false));
    cancelStage(s);
    EXPECT_FALSE(stagePending(s));
    waitForJob(s);
    EXPECT_FALSE(advanceStage(s, worker(), keyAt(44.3, 7.5), false));
    EXPECT_FALSE(s.job.valid()) << "the cancelled job's result was collected and dropped";
    EXPECT_EQ(s.swapped, 1u);
}

TEST(WindowLookAhead, CoversOneAndAHalfSecondsOfMotionWithinLimits)
{
    EXPECT_EQ(windowLookAheadM(0.0), kWindowLookAheadMinM);
    EXPECT_EQ(windowLookAheadM(250.0), kWindowLookAheadMinM);  // airliner: 1.5 km is 6 s
    EXPECT_DOUBLE_EQ(windowLookAheadM(3000.0), 4500.0);
    EXPECT_GE(windowLookAheadM(3000.0), 3000.0);                // at least 1 s
    EXPECT_EQ(windowLookAheadM(1e6), kWindowLookAheadMaxM);     // a jump, not a flight
    EXPECT_EQ(windowLookAheadM(std::numeric_limits<double>::infinity()), kWindowLookAheadMaxM);
    for (double v = 0; v < 20000; v += 37)
        EXPECT_LE(windowLookAheadM(v), windowLookAheadM(v + 37));  // never shrinks with speed

    // The speed estimate: 12 m in 4 ms is 3000 m/s; a frame in which the eye did not move keeps most
    // of it (a service renders between two set_view requests); it fades over seconds.
    double v = updateEyeSpeedMps(0, 12.0, 0.004);
    EXPECT_DOUBLE_EQ(v, 3000.0);
    v = updateEyeSpeedMps(v, 0.0, 0.004);
    EXPECT_GT(v, 2990.0);
    EXPECT_LT(updateEyeSpeedMps(3000.0, 0.0, 10.0), 30.0);
    EXPECT_EQ(updateEyeSpeedMps(42.0, 5.0, 0.0), 42.0);  // no time between frames: no new estimate
}

TEST(WindowLookAhead, NamesTheNodeTheEyeReachesNextEvenAt3000MetresPerSecond)
{
    // 3000 m/s, a frame every 4 ms (12 m), heading 37 degrees (cells are entered through both kinds of
    // edge) for 20 km. The truth: the next different node along the flown geodesic, frame by frame.
    const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
    const double speedMps = 3000.0, frameS = 0.004, headingDeg = 37.0;
    const int frames = int(20000.0 / (speedMps * frameS));
    std::vector<EyePose> poses(static_cast<size_t>(frames));
    std::vector<WindowCentre> nodes(static_cast<size_t>(frames));
    for (int k = 0; k < frames; ++k)
    {
        EyePose& p = poses[size_t(k)];
        g.Direct(44.3, 7.5, headingDeg, speedMps * frameS * k, p.latDeg, p.lonDeg);
        p.altitudeM = 10000.0;
        p.headingDeg = headingDeg;
        nodes[size_t(k)] = windowCentreForEye(p.latDeg, p.lonDeg);
    }
    const double lookAheadM = windowLookAheadM(speedMps);
    int checked = 0, wrong = 0, oldRuleWrong = 0, edges = 0;
    for (int k = 0; k + 1 < frames; ++k)
    {
        int j = k + 1;
        while (j < frames && nodes[size_t(j)] == nodes[size_t(k)])
            ++j;
        edges += nodes[size_t(k + 1)] == nodes[size_t(k)] ? 0 : 1;
        if (j == frames || (j - k) * speedMps * frameS > lookAheadM)
            continue;  // the next node is beyond the look-ahead (or the end of the flight)
        CameraFrame camera = computeCameraFrame(poses[size_t(k)]);
        const glm::dvec3 moveEnu =
            glm::transpose(camera.enuToEcef) * (computeCameraFrame(poses[size_t(k + 1)]).eyeEcefM - camera.eyeEcefM);
        std::optional<WindowCentre> next = nextWindowNode(camera, glm::dvec2(moveEnu), lookAheadM);
        ++checked;
        wrong += !next || !(*next == nodes[size_t(j)]);
        // The rule before: the node under the point 1500 m ahead (when it differs from the eye's).
        double latDeg = 0, lonDeg = 0, hM = 0;
        enuToGeodetic(camera, glm::dvec3(glm::normalize(glm::dvec2(moveEnu)) * 1500.0, 0.0), latDeg, lonDeg, hM);
        oldRuleWrong += !(windowCentreForEye(latDeg, lonDeg) == nodes[size_t(j)]);
    }
    std::printf("%d cell edges in %d frames; next node named right at %d of %d frames (1500 m rule: %d wrong)\n",
                edges, frames, checked - wrong, checked, oldRuleWrong);
    EXPECT_GE(edges, 8);
    // Every frame within the look-ahead of the next edge, i.e. at 3000 m/s every frame (cells are
    // < 4.5 km across), names the next node: it is prefetched from the frame the eye enters the cell
    // before, never skipped for the one after it.
    EXPECT_GT(checked, frames * 9 / 10);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(oldRuleWrong, 0);
}
