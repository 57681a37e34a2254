// SPDX-License-Identifier: MIT
// The daemon's side of the CIGI interface without a socket or a GPU: the host's ownship and view as the
// eye and frustum, its cloud layers and regions as a weather snapshot, the answers to Environmental
// Conditions Requests, and one datagram applied to the service's next frame.
#include "cigi_host_datagram.h"

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/service/cigi_apply.h"
#include "skyservice/service/cigi_conditions.h"
#include "skyservice/service/cigi_view.h"
#include "skyservice/service/cigi_weather.h"
#include "skyservice/render/view_validation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sky
{
namespace
{

using namespace sky::cigi;
using namespace sky::cigi::test;
using cigi::CloudType; // the same numbering as sky::CloudType

const GeoidGrid& egm96()
{
    static GeoidGrid grid = []
    {
        GeoidGrid g;
        std::string error;
        EXPECT_TRUE(g.load(defaultEgm96GridPath(), error)) << error;
        return g;
    }();
    return grid;
}

OwnshipPose ownship(double lat, double lon, double altMsl, double yaw = 0, double pitch = 0, double roll = 0)
{
    OwnshipPose o;
    o.valid = true;
    o.latDeg = lat;
    o.lonDeg = lon;
    o.altitudeMslM = altMsl;
    o.yawDeg = yaw;
    o.pitchDeg = pitch;
    o.rollDeg = roll;
    return o;
}

// South of India the geoid is ~100 m below the ellipsoid: 1000 m above mean sea level is ~900 m above it.
TEST(CigiEye, AltitudeAboveSeaLevelBecomesEllipsoidHeight)
{
    EyePose pose;
    std::string error;
    ASSERT_TRUE(cigiEyePose(ownship(5.0, 78.0, 1000.0, 30.0, 5.0, -10.0), nullptr, egm96(), pose, error)) << error;
    const double n = egm96().undulationM(5.0, 78.0);
    EXPECT_LT(n, -90.0);
    EXPECT_NEAR(pose.altitudeM, 1000.0 + n, 1e-6);
    EXPECT_NEAR(pose.headingDeg, 30.0, 1e-9);
    EXPECT_NEAR(pose.pitchDeg, 5.0, 1e-9);
    EXPECT_NEAR(pose.rollDeg, -10.0, 1e-9);
}

// A view yawed 90 degrees right on an ownship heading 30 looks 120; a view pitched down 20 on a level
// ownship looks 20 down; an offset forward on an ownship heading east moves the eye east, one up (-Z) raises it.
TEST(CigiEye, ViewControlOffsetsAndAnglesRideOnTheOwnship)
{
    ViewState view;
    view.yawDeg = 90;
    EyePose pose;
    std::string error;
    ASSERT_TRUE(cigiEyePose(ownship(45, 7, 2000, 30), &view, egm96(), pose, error)) << error;
    EXPECT_NEAR(pose.headingDeg, 120.0, 1e-9);
    view = ViewState{};
    view.pitchDeg = -20;
    ASSERT_TRUE(cigiEyePose(ownship(45, 7, 2000, 200), &view, egm96(), pose, error)) << error;
    EXPECT_NEAR(pose.pitchDeg, -20.0, 1e-9);
    EXPECT_NEAR(pose.headingDeg, 200.0, 1e-9);

    EyePose base;
    ASSERT_TRUE(cigiEyePose(ownship(45, 7, 2000, 90), nullptr, egm96(), base, error)) << error;
    view = ViewState{};
    view.xOffsetM = 1000;
    view.zOffsetM = -50;
    ASSERT_TRUE(cigiEyePose(ownship(45, 7, 2000, 90), &view, egm96(), pose, error)) << error;
    const double eastM = (pose.lonDeg - base.lonDeg) * M_PI / 180.0 * 6378137.0 * std::cos(45.0 * M_PI / 180.0);
    EXPECT_NEAR(eastM, 1000.0, 5.0);
    EXPECT_NEAR(pose.latDeg, base.latDeg, 1e-4);
    EXPECT_NEAR(pose.altitudeM - base.altitudeM, 50.0, 0.5); // + the earth's curvature over 1 km: 0.08 m
}

TEST(CigiEye, NoOwnshipOrAnOutOfRangeAltitudeIsRefused)
{
    EyePose pose;
    std::string error;
    EXPECT_FALSE(cigiEyePose(OwnshipPose{}, nullptr, egm96(), pose, error));
    EXPECT_NE(error.find("Entity Control"), std::string::npos) << error;
    EXPECT_FALSE(cigiEyePose(ownship(45, 7, 200000), nullptr, egm96(), pose, error));
    EXPECT_NE(error.find("altitude"), std::string::npos) << error;
}

// CIGI's signed half-angles become the angles from the axis to each edge; the left half of a wall.
TEST(CigiEye, ViewDefinitionBecomesTheAsymmetricFrustum)
{
    ViewState v;
    v.viewId = 3;
    v.leftDeg = -40;
    v.rightDeg = 0;
    v.topDeg = 15;
    v.bottomDeg = -10;
    Frustum f;
    double fovY = 0;
    std::string error;
    ASSERT_TRUE(cigiFrustum(v, f, fovY, error)) << error;
    EXPECT_TRUE(f.asymmetric);
    EXPECT_DOUBLE_EQ(f.leftDeg, 40.0);
    EXPECT_DOUBLE_EQ(f.rightDeg, 0.0);
    EXPECT_DOUBLE_EQ(f.upDeg, 15.0);
    EXPECT_DOUBLE_EQ(f.downDeg, 10.0);
    EXPECT_DOUBLE_EQ(fovY, 25.0);
    v.leftDeg = -89;
    EXPECT_FALSE(cigiFrustum(v, f, fovY, error));
    EXPECT_NE(error.find("View Definition 3"), std::string::npos) << error;
    v.leftDeg = 10; // both edges right of the axis, 10 degrees apart the wrong way
    v.rightDeg = 5;
    EXPECT_FALSE(cigiFrustum(v, f, fovY, error));
}

// A View Definition is taken exactly when the renderer draws the frustum it becomes (one rule,
// skyservice/render/view_limits.h): an extreme one is refused where it enters, never by a frame. The
// symmetric view's range is closed at both ends and the same for every entry.
TEST(CigiEye, ExtremeViewDefinitionsAreRefusedWhereTheyEnter)
{
    ViewState v;
    v.viewId = 2;
    v.leftDeg = -84.99f;
    v.rightDeg = 84.99f;
    v.topDeg = 84.99f;
    v.bottomDeg = -84.99f;
    Frustum f;
    double fovY = 0;
    std::string error;
    ASSERT_TRUE(cigiFrustum(v, f, fovY, error)) << error;
    ViewRequest view;
    view.width = 64;
    view.height = 36;
    view.frustum = f;
    EXPECT_TRUE(validateView(view, error)) << error;
    EXPECT_LE(fovY, kMaxFovYDeg);
    for (float extreme : {85.0f, 89.0f, 180.0f})
    {
        v.topDeg = extreme;
        EXPECT_FALSE(cigiFrustum(v, f, fovY, error)) << extreme;
        EXPECT_NE(error.find("(-85, 85)"), std::string::npos) << error;
        view.frustum.upDeg = double(extreme);
        EXPECT_FALSE(validateView(view, error)) << extreme;
    }

    ViewRequest symmetric;
    symmetric.width = 64;
    symmetric.height = 36;
    for (double fov : {kMinFovYDeg, 60.0, kMaxFovYDeg})
    {
        symmetric.fovYDeg = fov;
        EXPECT_TRUE(validateView(symmetric, error)) << fov << ": " << error;
    }
    for (double fov : {kMinFovYDeg - 1e-3, kMaxFovYDeg + 1e-3, std::nan("")})
    {
        symmetric.fovYDeg = fov;
        EXPECT_FALSE(validateView(symmetric, error)) << fov;
        EXPECT_NE(error.find("[1, 170]"), std::string::npos) << error;
    }
}

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

// One global Stratus layer: everywhere the same layer; the snapshot holds it on a global grid with the
// geoid's undulation added to its altitudes; a cirrus layer goes to the high (2D) layer.
TEST(CigiWeather, GlobalLayersBecomeAGlobalSnapshot)
{
    CigiState s =
        stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100), cloudLayer(2, CloudType::Cirrus, 9000, 300, 40)});
    ASSERT_TRUE(cigiHasCloudWeather(s));
    CigiCloudsAt at = cigiCloudsAt(s, -33.0, 151.0);
    EXPECT_FLOAT_EQ(at[0].coverage, 1.0f);
    EXPECT_FLOAT_EQ(at[0].baseMslM, 1000.0f);
    EXPECT_FLOAT_EQ(at[0].topMslM, 1600.0f);
    EXPECT_EQ(at[0].cloudType, uint8_t(CloudType::Stratus));
    EXPECT_FALSE(at[2].set);

    CigiWeatherGrid grid = cigiWeatherGrid(s, 45.0, 7.0);
    EXPECT_FALSE(grid.regional);
    EXPECT_EQ(grid.grid.cellCount(), 181u * 360u);
    WeatherSnapshot w = cigiWeatherSnapshot(s, grid, egm96(), 1782043200);
    ASSERT_EQ(w.layers.size(), 1u);
    const size_t cell = w.grid.index(90 + 10, 180 + 80); // 10 N, 80 E: the geoid's low
    const float n = float(egm96().undulationM(10.0, 80.0));
    EXPECT_FLOAT_EQ(w.layers[0].coverage[cell], 1.0f);
    EXPECT_NEAR(w.layers[0].baseAltitudeM[cell], 1000.0f + n, 0.01f);
    EXPECT_NEAR(w.layers[0].topAltitudeM[cell], 1600.0f + n, 0.01f);
    EXPECT_EQ(w.layers[0].type[cell], uint8_t(CloudType::Stratus));
    ASSERT_EQ(w.high.coverage.size(), w.grid.cellCount());
    EXPECT_FLOAT_EQ(w.high.coverage[cell], 0.4f);
    EXPECT_EQ(w.high.type[cell], uint8_t(CloudType::Cirrus));
    EXPECT_NEAR(w.high.altitudeM[cell], 9150.0f + n, 0.01f);
}

TEST(CigiWeather, DisabledOrTypelessLayersDrawNothing)
{
    WeatherControl off = cloudLayer(1, CloudType::Stratus, 1000, 600, 100);
    off.weatherEnable = false;
    CigiState s = stateWith(
        {off, cloudLayer(2, CloudType::None, 2000, 500, 100), cloudLayer(3, CloudType::Cumulus, 2000, 0, 100)});
    WeatherSnapshot w = cigiWeatherSnapshot(s, cigiWeatherGrid(s, 0, 0), egm96(), 0);
    EXPECT_TRUE(w.layers.empty());
    EXPECT_TRUE(w.high.coverage.empty());
}

// A region 20 km (X) x 10 km (Y) rotated 90 degrees (X points east), corners rounded by 2 km, fading over
// 4 km: inside its layer replaces the global one, across the band it fades back, beyond it is gone.
TEST(CigiWeather, RegionIsARotatedRoundedRectangleWithATransitionBand)
{
    CigiState s = stateWith(
        {cloudLayer(1, CloudType::Stratus, 1000, 600, 100), cloudLayer(1, CloudType::Cumulus, 1500, 2000, 50, 4)});
    EnvironmentalRegion& r = s.regions[4];
    r.defined = true;
    r.state = RegionState::Active;
    r.latDeg = 45.0;
    r.lonDeg = 7.0;
    r.sizeXM = 20000;
    r.sizeYM = 10000;
    r.cornerRadiusM = 2000;
    r.rotationDeg = 90;
    r.transitionPerimeterM = 4000;
    const double mLat = 111195.0, mLon = 111195.0 * std::cos(45.0 * M_PI / 180.0);
    auto at = [&](double northM) { return 45.0 + northM / mLat; };
    auto lonAt = [&](double eastM) { return 7.0 + eastM / mLon; };
    EXPECT_DOUBLE_EQ(cigiRegionWeight(r, 45.0, 7.0), 1.0);
    EXPECT_DOUBLE_EQ(cigiRegionWeight(r, 45.0, lonAt(9000)), 1.0); // 9 km east: inside (X half 10 km)
    const double t = 1500.0 / 4000.0; // 6.5 km north: 1.5 km beyond the 5 km edge, into the 4 km band
    EXPECT_NEAR(cigiRegionWeight(r, at(6500), 7.0), 1.0 - t * t * (3.0 - 2.0 * t), 0.01);
    EXPECT_DOUBLE_EQ(cigiRegionWeight(r, at(9500), 7.0), 0.0);  // beyond the band
    EXPECT_LT(cigiRegionWeight(r, at(4900), lonAt(9900)), 1.0); // the rounded corner is outside
    EXPECT_DOUBLE_EQ(cigiRegionWeight(r, at(4900), 7.0), 1.0);  // the straight edge is inside

    CigiCloudsAt inside = cigiCloudsAt(s, 45.0, 7.0);
    EXPECT_EQ(inside[0].cloudType, uint8_t(CloudType::Cumulus));
    EXPECT_FLOAT_EQ(inside[0].coverage, 0.5f);
    EXPECT_FLOAT_EQ(inside[0].baseMslM, 1500.0f);
    CigiCloudsAt outside = cigiCloudsAt(s, at(20000), 7.0);
    EXPECT_EQ(outside[0].cloudType, uint8_t(CloudType::Stratus));
    EXPECT_FLOAT_EQ(outside[0].coverage, 1.0f);

    // The snapshot's grid is regional around the ownship and fine enough for the 4 km band.
    CigiWeatherGrid grid = cigiWeatherGrid(s, 45.05, 7.0);
    EXPECT_TRUE(grid.regional);
    EXPECT_LE(grid.grid.dLatDeg * mLat, 1400.0);
    WeatherSnapshot w = cigiWeatherSnapshot(s, grid, egm96(), 0);
    ASSERT_EQ(w.layers.size(), 1u);
    float minCover = 2, maxCover = -1;
    for (float c : w.layers[0].coverage)
        minCover = std::min(minCover, c), maxCover = std::max(maxCover, c);
    EXPECT_FLOAT_EQ(minCover, 0.5f);
    EXPECT_FLOAT_EQ(maxCover, 1.0f);

    r.state = RegionState::Inactive; // an inactive region draws nothing of its own
    EXPECT_EQ(cigiCloudsAt(s, 45.0, 7.0)[0].cloudType, uint8_t(CloudType::Stratus));
    EXPECT_FALSE(cigiWeatherGrid(s, 45.0, 7.0).regional);
}

// Inside the 100 % Stratus deck the 5 % contrast distance of extinction 0.045 /m: 67 m; above it the
// clear air: far more than 10 km. The standard atmosphere's temperature and pressure.
TEST(CigiConditions, VisibilityTemperaturePressure)
{
    CigiState s = stateWith({cloudLayer(1, CloudType::Stratus, 1000, 600, 100)});
    WeatherConditionsResponse in = cigiWeatherConditions(s, conditionsRequest(9, 45, 7, 1300), 0.045);
    EXPECT_EQ(in.requestId, 9);
    EXPECT_NEAR(in.visibilityM, 3.0 / 0.045, 0.01);
    EXPECT_EQ(in.humidityPct, 100);
    WeatherConditionsResponse above = cigiWeatherConditions(s, conditionsRequest(10, 45, 7, 3000), 0.045);
    EXPECT_GT(above.visibilityM, 100000.0f);
    EXPECT_NEAR(above.airTemperatureC, 15.0 - 6.5 * 3.0, 1e-3);
    EXPECT_NEAR(above.pressureHpa, 701.1, 0.2);
    double t = 0, p = 0;
    standardAtmosphere(11000, 15, 1013.25, t, p);
    EXPECT_NEAR(t, -56.5, 1e-6);
    EXPECT_NEAR(p, 226.32, 0.05);
    standardAtmosphere(20000, 15, 1013.25, t, p);
    EXPECT_NEAR(p, 54.75, 0.05);

    // The host's Atmosphere Control visibility and wind outside clouds.
    s.atmosphere.set = true;
    s.atmosphere.visibilityM = 8000;
    s.atmosphere.horizontalWindMps = 12;
    s.atmosphere.windDirectionDeg = 270;
    s.atmosphere.airTemperatureC = 15;
    s.atmosphere.pressureHpa = 1013.25f;
    // The visibility is the sea-level one; the drawn haze thins above (Mie scale height 1.2 km, Rayleigh 8 km).
    EXPECT_NEAR(cigiWeatherConditions(s, conditionsRequest(11, 45, 7, 0), 0.045).visibilityM, 8000.0f, 0.5f);
    WeatherConditionsResponse hazy = cigiWeatherConditions(s, conditionsRequest(11, 45, 7, 3000), 0.045);
    const double rayleigh = 13.558e-6;
    EXPECT_NEAR(hazy.visibilityM,
                3.0 / (rayleigh * std::exp(-3.0 / 8.0) + (3.0 / 8000.0 - rayleigh) * std::exp(-3.0 / 1.2)), 20.0);
    EXPECT_FLOAT_EQ(hazy.horizontalWindMps, 12.0f);
    EXPECT_FLOAT_EQ(hazy.windDirectionDeg, 270.0f);

    // Inside the global ground fog its extinction adds to the haze's; above it, none.
    WeatherLayer& fog = s.globalLayers[0];
    fog.layerId = 0;
    fog.enabled = true;
    fog.baseElevationMslM = 0;
    fog.thicknessM = 200;
    fog.visibilityM = 300;
    EXPECT_NEAR(cigiWeatherConditions(s, conditionsRequest(11, 45, 7, 100), 0.045).visibilityM,
                3.0 / (3.0 / 300.0 + 3.0 / 8000.0 * std::exp(-100.0 / 1200.0)), 1.0);
    EXPECT_GT(cigiWeatherConditions(s, conditionsRequest(11, 45, 7, 250), 0.045).visibilityM, 8000.0f);
    s.globalLayers.erase(0);

    std::vector<AerosolConcentrationResponse> lwc =
        cigiAerosolConcentrations(s, conditionsRequest(12, 45, 7, 1300, kRequestAerosol), 0.045);
    ASSERT_EQ(lwc.size(), 1u);
    EXPECT_EQ(lwc[0].layerId, 1);
    EXPECT_NEAR(lwc[0].aerosolGPerM3, 0.3, 1e-4); // 2/3 x 1e6 g/m3 x 10 um x 0.045 /m
    EXPECT_FLOAT_EQ(cigiAerosolConcentrations(s, conditionsRequest(13, 45, 7, 3000), 0.045)[0].aerosolGPerM3, 0.0f);
}

// One host datagram lands in the service's next frame: the eye, the frustum, the time (rate 1 with the
// ephemeris), the weather (swapped in as source "cigi"), and a frame asked for at render rate 0. The same
// weather resent is not rebuilt, a changed one starts a fade; a host resending the same minute does not pull
// the running clock back.
TEST(CigiApply, DatagramDrivesTheNextFrame)
{
    ServiceState service;
    service.renderRateHz = 0;
    service.view.pose.latDeg = 1;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(2, egm96());
    auto send = [&](const HostDatagram& d)
    {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 5);
        applier.apply(state, r, service);
    };
    HostDatagram first(ByteOrder::Little, 100);
    first.add(ownshipAt(5, 45.0, 7.0, 3000.0, 10.0))
        .add(celestialAt(6212026, 12, 0, true))
        .add(cloudLayer(1, CloudType::Stratus, 1000, 600, 100))
        .add(viewDefinition(2, -40, 0, 12, -12))
        .add(viewDefinition(1, -10, 10, 5, -5)); // another daemon's view
    send(first);
    EXPECT_NEAR(service.view.pose.altitudeM, 3000.0 + egm96().undulationM(45.0, 7.0), 1e-6);
    EXPECT_NEAR(service.view.pose.headingDeg, 10.0, 1e-9);
    EXPECT_TRUE(service.view.frustum.asymmetric);
    EXPECT_DOUBLE_EQ(service.view.frustum.leftDeg, 40.0);
    EXPECT_DOUBLE_EQ(service.view.frustum.rightDeg, 0.0);
    EXPECT_DOUBLE_EQ(service.view.frustum.upDeg, 12.0);
    EXPECT_DOUBLE_EQ(service.view.frustum.downDeg, 12.0);
    EXPECT_DOUBLE_EQ(service.clock.baseUnixS, 1782043200.0); // 2026-06-21T12:00:00Z
    EXPECT_DOUBLE_EQ(service.clock.rate, 1.0);
    EXPECT_EQ(service.weather.source, "cigi");
    ASSERT_TRUE(service.weather.timeline);
    EXPECT_EQ(service.weather.timeline->snapshot(0).layers.size(), 1u);
    const uint64_t version = service.weather.version;
    const uint64_t jumps = service.clock.jumps;
    EXPECT_EQ(jumps, 1u); // from the config's time to the host's
    EXPECT_EQ(service.renderWantedUpTo, 1u);

    service.clock.baseUnixS += 30; // the clock ran on half a minute
    service.framesStarted = 1;
    HostDatagram again(ByteOrder::Big, 101);
    again.add(celestialAt(6212026, 12, 0, true)).add(cloudLayer(1, CloudType::Stratus, 1000, 600, 100));
    send(again);
    EXPECT_EQ(service.weather.version, version) << "the same weather resent was rebuilt";
    EXPECT_DOUBLE_EQ(service.clock.baseUnixS, 1782043230.0) << "the same minute resent moved the clock";
    EXPECT_EQ(service.renderWantedUpTo, 2u);

    HostDatagram change(ByteOrder::Big, 102);
    change.add(cloudLayer(1, CloudType::Stratus, 1000, 600, 60)).add(celestialAt(6212026, 18, 30, false));
    send(change);
    // The weather change fades in (tests/cigi/cigi_fade_test.cpp): its first step is published a step later.
    EXPECT_EQ(service.weather.version, version);
    EXPECT_TRUE(applier.fading());
    EXPECT_DOUBLE_EQ(service.clock.baseUnixS, 1782043200.0 + 6.5 * 3600);
    EXPECT_DOUBLE_EQ(service.clock.rate, 0.0);
    EXPECT_EQ(service.clock.jumps, jumps + 1);
}

// A pose the renderer cannot draw (200 km up) or a frustum it cannot (88 degrees to one side) leaves the last
// good one in the frame and is reported in status until a good one comes.
TEST(CigiApply, UndrawablePoseOrViewKeepsTheLastGoodOne)
{
    ServiceState service;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, egm96());
    auto send = [&](const HostDatagram& d) {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, service);
    };
    HostDatagram good(ByteOrder::Big, 1);
    good.add(ownshipAt(0, 45, 7, 3000)).add(viewDefinition(0, -30, 30, 20, -20));
    send(good);
    const ViewRequest before = service.view;
    EXPECT_TRUE(applier.statusJson()["pose_error"].is_null());
    HostDatagram bad(ByteOrder::Big, 2);
    bad.add(ownshipAt(0, 46, 7, 200000)).add(viewDefinition(0, -88, 30, 20, -20));
    send(bad);
    EXPECT_DOUBLE_EQ(service.view.pose.latDeg, before.pose.latDeg);
    EXPECT_DOUBLE_EQ(service.view.frustum.leftDeg, 30.0);
    nlohmann::json status = applier.statusJson();
    EXPECT_NE(status["pose_error"].get<std::string>().find("altitude"), std::string::npos) << status.dump();
    EXPECT_NE(status["view_error"].get<std::string>().find("-85, 85"), std::string::npos) << status.dump();
    send(good);
    status = applier.statusJson();
    EXPECT_TRUE(status["pose_error"].is_null());
    EXPECT_TRUE(status["view_error"].is_null());
}

// Atmosphere Control's visibility becomes the haze the frame draws (ViewRequest::visibilityM: the aerosol
// near the ground, tests/gpu/test_aerial_lut.cpp); 0 returns to the clear atmosphere; datagrams without
// the packet leave it. The global ground fog becomes the frame's fog band.
TEST(CigiApply, AtmosphereVisibilityAndGroundFogSetTheHaze)
{
    ServiceState service;
    CigiState state;
    Decoder decoder;
    CigiApplier applier(0, egm96());
    auto send = [&](const HostDatagram& d) {
        DecodeResult r = decoder.decode(d.bytes().data(), d.bytes().size());
        ASSERT_TRUE(r.accepted);
        applyDatagram(state, r, 0);
        applier.apply(state, r, service);
    };
    AtmosphereControl air;
    air.visibilityM = 2000;
    air.humidityPct = 90;
    HostDatagram hazy(ByteOrder::Little, 1);
    hazy.add(air);
    send(hazy);
    EXPECT_DOUBLE_EQ(service.view.visibilityM, 2000.0);
    HostDatagram other(ByteOrder::Little, 2);
    other.add(ownshipAt(0, 45, 7, 3000));
    send(other);
    EXPECT_DOUBLE_EQ(service.view.visibilityM, 2000.0);
    air.visibilityM = 0;
    HostDatagram clear(ByteOrder::Little, 3);
    clear.add(air);
    send(clear);
    EXPECT_DOUBLE_EQ(service.view.visibilityM, 0.0);
    EXPECT_DOUBLE_EQ(service.view.fogVisibilityM, 0.0);

    // Global ground fog (layer 0): a band at its height above mean sea level under the eye, its visibility.
    WeatherControl fog = cloudLayer(0, CloudType::None, 100, 200, 0);
    fog.visibilityM = 300;
    HostDatagram foggy(ByteOrder::Little, 4);
    foggy.add(fog);
    send(foggy);
    const double n = egm96().undulationM(45, 7);
    EXPECT_NEAR(service.view.fogBaseM, 100.0 + n, 1e-4);
    EXPECT_NEAR(service.view.fogTopM, 300.0 + n, 1e-4);
    EXPECT_DOUBLE_EQ(service.view.fogVisibilityM, 300.0);
    fog.weatherEnable = false;
    HostDatagram fogOff(ByteOrder::Little, 5);
    fogOff.add(fog);
    send(fogOff);
    EXPECT_DOUBLE_EQ(service.view.fogVisibilityM, 0.0);
}

} // namespace
} // namespace sky
