// SPDX-License-Identifier: MIT
// The host's weather changes fade in (skyservice/service/cigi_weather_fade.h): a changed or new layer ramps
// from what was drawn to what was set over kCigiFadeS, a change during a fade starts from what is drawn
// (no jump), a new region ramps in and a destroyed one out; the applier publishes the fade's steps only as
// the frames draw them.
#include "cigi_host_datagram.h"

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/service/cigi_apply.h"
#include "skyservice/service/cigi_weather.h"
#include "skyservice/service/cigi_weather_fade.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sky
{
namespace
{

using namespace sky::cigi;
using namespace sky::cigi::test;
using cigi::CloudType;

CigiState stateWith(std::initializer_list<WeatherControl> layers)
{
    CigiState s;
    Decoder decoder;
    HostDatagram d(ByteOrder::Big, 1);
    for (const WeatherControl& w : layers)
        d.add(w);
    applyDatagram(s, decoder.decode(d.bytes().data(), d.bytes().size()), 0);
    return s;
}

float smooth(double t)
{
    return float(t * t * (3 - 2 * t));
}

// The first weather is drawn at once; a coverage change fades over kCigiFadeS (smoothstep in time) and
// a base change moves the layer gradually; then nothing fades.
TEST(CigiFade, ChangedLayerRampsFromWhatWasDrawn)
{
    CigiState s = stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100)});
    CigiWeatherFade fade;
    ASSERT_TRUE(fade.setTarget(s, 0.0));
    EXPECT_FALSE(fade.fading(0.0)) << "the host's first weather fades in";
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, 0.0)[0].coverage, 1.0f);
    EXPECT_FALSE(fade.setTarget(s, 1.0)) << "the same weather resent is a change";

    s.globalLayers[1].coveragePct = 40;
    s.globalLayers[1].baseElevationMslM = 2000;
    ASSERT_TRUE(fade.setTarget(s, 10.0));
    EXPECT_TRUE(fade.fading(10.0));
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, 10.0)[0].coverage, 1.0f) << "the change popped";
    const double quarter = 10.0 + 0.25 * kCigiFadeS;
    const CigiCloudAt mid = fade.cloudsAt(45, 7, quarter)[0];
    EXPECT_NEAR(mid.coverage, 1.0f - 0.6f * smooth(0.25), 1e-5);
    EXPECT_NEAR(mid.baseMslM, 1000.0f + 1000.0f * smooth(0.25), 0.01);
    EXPECT_EQ(mid.cloudType, uint8_t(CloudType::Stratus));
    const CigiCloudAt end = fade.cloudsAt(45, 7, 10.0 + kCigiFadeS)[0];
    EXPECT_FLOAT_EQ(end.coverage, 0.4f);
    EXPECT_FLOAT_EQ(end.baseMslM, 2000.0f);
    EXPECT_FALSE(fade.fading(10.0 + kCigiFadeS));
}

// A second change half way through the first starts from what is drawn at that moment: continuous, and
// it ends on the second target.
TEST(CigiFade, ChangeDuringAFadeDoesNotJump)
{
    CigiState s = stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100)});
    CigiWeatherFade fade;
    fade.setTarget(s, 0.0);
    s.globalLayers[1].coveragePct = 20;
    fade.setTarget(s, 10.0);
    const double t = 10.0 + 0.5 * kCigiFadeS;
    const float before = fade.cloudsAt(45, 7, t)[0].coverage;
    EXPECT_NEAR(before, 0.6f, 1e-5);
    s.globalLayers[1].coveragePct = 90;
    s.globalLayers[1].baseElevationMslM = 1500;
    ASSERT_TRUE(fade.setTarget(s, t));
    const CigiCloudAt after = fade.cloudsAt(45, 7, t)[0];
    EXPECT_NEAR(after.coverage, before, 1e-5);
    EXPECT_NEAR(after.baseMslM, 1000.0f, 0.01);
    EXPECT_NEAR(fade.cloudsAt(45, 7, t + 0.5 * kCigiFadeS)[0].coverage, 0.6f + 0.3f * smooth(0.5), 1e-4);
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, t + kCigiFadeS)[0].coverage, 0.9f);
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, t + kCigiFadeS)[0].baseMslM, 1500.0f);
}

// A layer the host adds later fades in where it will be (its own altitudes from the start); a layer disabled
// fades out where it was.
TEST(CigiFade, NewLayerFadesInAndDisabledLayerFadesOut)
{
    CigiState s = stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100)});
    CigiWeatherFade fade;
    fade.setTarget(s, 0.0);
    s.globalLayers[2] = stateWith({cloudLayer(2, CloudType::Cumulus, 3000, 1500, 50)}).globalLayers[2];
    s.globalLayers[1].enabled = false;
    ASSERT_TRUE(fade.setTarget(s, 10.0));
    EXPECT_FALSE(fade.cloudsAt(45, 7, 10.0)[1].coverage > 0);
    const CigiCloudsAt mid = fade.cloudsAt(45, 7, 10.0 + 0.5 * kCigiFadeS);
    EXPECT_NEAR(mid[1].coverage, 0.25f, 1e-5);
    EXPECT_FLOAT_EQ(mid[1].baseMslM, 3000.0f);
    EXPECT_EQ(mid[1].cloudType, uint8_t(CloudType::Cumulus));
    EXPECT_NEAR(mid[0].coverage, 0.5f, 1e-5);
    EXPECT_FLOAT_EQ(mid[0].baseMslM, 1000.0f);
    const CigiCloudsAt end = fade.cloudsAt(45, 7, 10.0 + kCigiFadeS);
    EXPECT_FLOAT_EQ(end[1].coverage, 0.5f);
    EXPECT_FLOAT_EQ(end[0].coverage, 0.0f);
}

// A region that appears ramps its weight in over the global layer; destroyed (and pruned from the host's
// state), it ramps out and is then forgotten.
TEST(CigiFade, RegionFadesInAndADestroyedOneFadesOut)
{
    CigiState s = stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100)});
    CigiWeatherFade fade;
    fade.setTarget(s, 0.0);
    CigiState withRegion = stateWith(
        {cloudLayer(1, CloudType::Stratus, 1000, 600, 100), cloudLayer(1, CloudType::Cumulus, 1500, 2000, 50, 3)});
    EnvironmentalRegion& r = withRegion.regions[3];
    r.defined = true;
    r.state = RegionState::Active;
    r.latDeg = 45.0;
    r.lonDeg = 7.0;
    r.sizeXM = r.sizeYM = 20000;
    ASSERT_TRUE(fade.setTarget(withRegion, 10.0));
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, 10.0)[0].coverage, 1.0f);
    EXPECT_NEAR(fade.cloudsAt(45, 7, 10.0 + 0.5 * kCigiFadeS)[0].coverage, 0.75f, 1e-5);
    const CigiCloudAt in = fade.cloudsAt(45, 7, 10.0 + kCigiFadeS)[0];
    EXPECT_FLOAT_EQ(in.coverage, 0.5f);
    EXPECT_EQ(in.cloudType, uint8_t(CloudType::Cumulus));
    EXPECT_TRUE(cigiWeatherGrid(fade, 45.0, 7.0).regional);

    withRegion.regions[3].state = RegionState::Destroyed;
    pruneDestroyedRegions(withRegion, 1); // as the link does: the host's state forgets it at once
    ASSERT_TRUE(withRegion.regions.empty());
    ASSERT_TRUE(fade.setTarget(withRegion, 20.0));
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, 20.0)[0].coverage, 0.5f) << "the destroyed region vanished at once";
    EXPECT_NEAR(fade.cloudsAt(45, 7, 20.0 + 0.5 * kCigiFadeS)[0].coverage, 0.75f, 1e-5);
    EXPECT_TRUE(cigiWeatherGrid(fade, 45.0, 7.0).regional) << "the grid lost a region still fading out";
    fade.setTarget(withRegion, 20.0 + kCigiFadeS);
    EXPECT_TRUE(fade.regions().empty());
    EXPECT_FLOAT_EQ(fade.cloudsAt(45, 7, 20.0 + kCigiFadeS)[0].coverage, 1.0f);
    EXPECT_FALSE(cigiWeatherGrid(fade, 45.0, 7.0).regional);
}

// The applier: the first weather at once; a change publishes nothing at once (it would draw what was), then
// a step every kCigiFadeStepS, each only once the frames draw the last one; the last step is the target.
TEST(CigiFade, ApplierPublishesStepsAsTheFramesDrawThem)
{
    ServiceState service;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, GeoidGrid{});
    auto send = [&](const HostDatagram& d, double nowS)
    {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, service, nowS);
    };
    auto drawn = [&] { service.frameWeather = FrameWeather{service.weather.version, "cigi", 0, true}; };
    auto coverage = [&] { return service.weather.timeline->snapshot(0).layers.at(0).coverage.at(0); };
    HostDatagram first(ByteOrder::Big, 1);
    first.add(cloudLayer(1, CloudType::Stratus, 1000, 600, 100));
    send(first, 0.0);
    const uint64_t v0 = service.weather.version;
    EXPECT_FLOAT_EQ(coverage(), 1.0f);
    EXPECT_FALSE(applier.fading());
    drawn();

    HostDatagram change(ByteOrder::Big, 2);
    change.add(cloudLayer(1, CloudType::Stratus, 1000, 600, 40));
    send(change, 10.0);
    EXPECT_EQ(service.weather.version, v0) << "a step that draws what was drawn was published";
    EXPECT_TRUE(applier.fading());
    applier.tick(state, service, 10.0 + 0.5 * kCigiFadeStepS);
    EXPECT_EQ(service.weather.version, v0) << "a step came early";
    applier.tick(state, service, 10.0 + kCigiFadeStepS);
    ASSERT_EQ(service.weather.version, v0 + 1);
    EXPECT_NEAR(coverage(), 1.0f - 0.6f * smooth(kCigiFadeStepS / kCigiFadeS), 1e-5);
    applier.tick(state, service, 10.0 + 2 * kCigiFadeStepS);
    EXPECT_EQ(service.weather.version, v0 + 1) << "a step was published before the frames drew the last";
    drawn();
    send(change, 10.0 + 2 * kCigiFadeStepS); // the host resends: the due step goes out with it
    EXPECT_EQ(service.weather.version, v0 + 2);
    drawn();
    applier.tick(state, service, 10.0 + kCigiFadeS + 1.0);
    EXPECT_EQ(service.weather.version, v0 + 3);
    EXPECT_FLOAT_EQ(coverage(), 0.4f);
    EXPECT_FALSE(applier.fading());
    drawn();
    applier.tick(state, service, 20.0 + kCigiFadeS);
    EXPECT_EQ(service.weather.version, v0 + 3) << "a step after the fade ended";
    EXPECT_EQ(applier.statusJson()["fade_steps"], 3u);
}

} // namespace
} // namespace sky
