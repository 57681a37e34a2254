// SPDX-License-Identifier: MIT
// The host's weather fading in keeps the renderer's reprojection history (GPU: lavapipe, validation on, a
// 64 x 36 image, test quality, reprojected): a CIGI host changes its layer, the applier publishes the fade's
// steps (skyservice/service/cigi_apply.h), the weather schedule stages each (weather_schedule.h), and the frame
// that swaps a step in still reprojects the last frame (no history dropped); a new snapshot file loaded under
// the host's weather, and the host's first weather, drop it.
#include "cigi_host_datagram.h"

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/service/cigi_apply.h"
#include "skyservice/service/weather_schedule.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>

namespace sky
{
namespace
{

using namespace sky::cigi;
using namespace sky::cigi::test;
using namespace sky::testscenes;
using sky::CloudType;

class CigiHistory : public GpuFixture
{
};

constexpr int kMaxFrames = 500;

TEST_F(CigiHistory, AFadeStepKeepsTheReprojectionHistoryANewSnapshotDropsIt)
{
    ServiceState s;
    s.view = lookUp(45.0, 7.0, 200.0, 40.0, "2026-06-21T12:00:00Z");
    s.view.width = 64;
    s.view.height = 36;
    s.clock.baseUnixS = double(s.view.unixTimeS);
    QualitySettings q = testQuality();
    q.reprojected = true;
    WeatherSchedule schedule;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, GeoidGrid{});
    double igTimeS = 0;
    // One frame as the render loop makes it: the service's weather handed to the schedule, then published.
    auto frame = [&]
    {
        schedule.beforeFrame(*renderer, s.weather, s.clock, s.clock.baseUnixS);
        renderOk(s.view, q);
        schedule.afterFrame(*renderer);
        s.frameWeather = FrameWeather{schedule.drawn().version, schedule.drawn().source, 0, true};
        // The IG clock moves on only once the schedule has drawn what it was handed: on a loaded machine the
        // weather worker may take several frames per step, and the fade would otherwise end in fewer steps.
        if (!schedule.pending())
            igTimeS += 0.1;
        applier.tick(state, s, igTimeS);
    };
    auto host = [&](float coveragePct)
    {
        HostDatagram d(ByteOrder::Big, 1);
        d.add(cloudLayer(1, cigi::CloudType::Cumulus, 1200, 1400, coveragePct));
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, s, igTimeS);
    };
    // Frames until the schedule draws the service's weather; the drops of history meanwhile.
    auto drawNewest = [&]
    {
        const uint64_t before = renderer->reconstruct.reprojection.drops;
        for (int i = 0; i < kMaxFrames && !(s.frameWeather.version == s.weather.version && !schedule.pending()); ++i)
            frame();
        EXPECT_EQ(s.frameWeather.version, s.weather.version) << "the service's weather was never drawn";
        return renderer->reconstruct.reprojection.drops - before;
    };
    setWeather(*renderer, uniformLayer(0.5f, CloudType::Cumulus, 1200.0f, 2600.0f));
    frame();
    host(50);
    EXPECT_EQ(drawNewest(), 1u) << "the host's first weather (a new weather) kept the history";

    host(90); // fades in over kCigiFadeS of IG time, a step every kCigiFadeStepS
    const uint64_t dropsBefore = renderer->reconstruct.reprojection.drops;
    const uint64_t stepsBefore = applier.statusJson()["fade_steps"].get<uint64_t>();
    for (int i = 0; i < kMaxFrames && applier.fading(); ++i)
        frame();
    drawNewest();
    EXPECT_FALSE(applier.fading());
    EXPECT_GE(applier.statusJson()["fade_steps"].get<uint64_t>(), stepsBefore + 5) << "too few fade steps drawn";
    EXPECT_EQ(renderer->reconstruct.reprojection.drops, dropsBefore) << "a fade step dropped the history";
    EXPECT_EQ(lastHistoryDropReason(*renderer), "");

    // A snapshot file loaded: the host's weather is laid over it, and the history is dropped.
    auto file = std::make_shared<WeatherTimeline>();
    std::string error;
    ASSERT_TRUE(file->setSnapshots({uniformLayer(0.3f, CloudType::Stratus, 600.0f, 900.0f)}, error)) << error;
    s.weather.timeline = file;
    s.weather.source = "file";
    ++s.weather.version;
    EXPECT_GE(drawNewest(), 1u) << "a new snapshot kept the history";
    host(90); // the host's next datagram lays its weather over the file
    EXPECT_TRUE(s.weather.overlay);
    EXPECT_GE(drawNewest(), 1u);
    EXPECT_EQ(schedule.drawn().source, "file + cigi");
}

} // namespace
} // namespace sky
