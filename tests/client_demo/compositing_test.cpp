// SPDX-License-Identifier: MIT
// client_demo's CPU side without Vulkan or a service: the ground under the frame's horizon, the shadow map
// lookup with its geo-reference, the compositing, the flight model and the UTC parser.
#include "client_demo/compositor.h"
#include "client_demo/flight_model.h"
#include "client_demo/ground_shading.h"
#include "client_demo/utc_time.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{

using namespace demo;

SkyShmView levelView(uint32_t width, uint32_t height)
{
    SkyShmView v{};
    v.lat_deg = 44.3;
    v.lon_deg = 7.5;
    v.alt_m = 1500.0;
    v.heading_deg = 0.0;
    v.pitch_deg = 0.0;
    v.fov_deg = 60.0;
    v.width = width;
    v.height = height;
    return v;
}

// A shadow map of 8x8 texels of 1 km centred on the eye, clear but for an opaque block of 2x2 texels whose
// north-west texel is (opaqueColumn, opaqueRow) (2x2 so that bilinear lookups inside it give exactly 0).
LatestFrame frameWithShadow(const SkyShmView& view, uint32_t opaqueColumn, uint32_t opaqueRow)
{
    LatestFrame f;
    f.frameId = 1;
    f.view = view;
    f.width = view.width;
    f.height = view.height;
    f.rgba.assign(size_t(f.width) * f.height * 4, 0);
    for (size_t i = 0; i < f.rgba.size(); i += 4)
    {
        f.rgba[i] = 100;  // a uniform grey-blue frame: no "cloud" brighter than its ground
        f.rgba[i + 1] = 110;
        f.rgba[i + 2] = 130;
        f.rgba[i + 3] = 255;
    }
    f.shadowSize = 8;
    f.shadowTransmittance.assign(64, 1.0f);
    for (uint32_t r = opaqueRow; r < opaqueRow + 2; ++r)
        for (uint32_t c = opaqueColumn; c < opaqueColumn + 2; ++c)
            f.shadowTransmittance[r * 8 + c] = 0.0f;
    f.shadow.centre_lat_deg = view.lat_deg;
    f.shadow.centre_lon_deg = view.lon_deg;
    f.shadow.extent_m = 8000.0;
    f.shadow.size_texels = 8;
    f.shadow.sun_elevation_deg = 60.0;
    return f;
}

TEST(ClientDemoGround, PixelCentreRowsMeetTheHorizonWhereTheServiceDoes)
{
    // Level eye at 1500 m: the horizon dips by acos(R / (R + h)) ~ 1.24 degrees, so with a 60 degree
    // field of view the row just above the centre is sky and a row 2 degrees below is ground.
    const GroundCamera cam = makeGroundCamera(levelView(640, 360));
    GroundHit hit;
    EXPECT_FALSE(intersectGround(cam, viewRay(cam, 320.5, 179.5), hit));
    const double rowsPerDeg = 180.0 / std::tan(30.0 * M_PI / 180.0) * M_PI / 180.0;  // near the centre
    ASSERT_TRUE(intersectGround(cam, viewRay(cam, 320.5, 180.0 + 2.0 * rowsPerDeg), hit));
    EXPECT_GT(hit.distanceM, 30000.0);
    EXPECT_LT(hit.distanceM, 60000.0);
    EXPECT_GT(hit.northM, 0.0);  // heading north: the ground ahead is north
    // Straight down from the bottom edge of a 90 degree pitch-down view: the ground 1500 m below.
    SkyShmView down = levelView(64, 64);
    down.pitch_deg = -89.9;
    const GroundCamera camDown = makeGroundCamera(down);
    ASSERT_TRUE(intersectGround(camDown, viewRay(camDown, 32.0, 32.0), hit));
    EXPECT_NEAR(hit.distanceM, 1500.0, 1.0);
}

// One channel of a 2x1 display wall (left 40, right 0, up 20, down 10 degrees): the ground camera's rays
// span exactly those angles, the right edge is the view axis, and the other channel's left edge meets it.
TEST(ClientDemoGround, AsymmetricChannelsSpanTheirHalfAnglesAndMeetAtTheAxis)
{
    const double kDeg = 3.14159265358979323846 / 180.0;
    SkyShmView left = levelView(200, 100);
    left.asymmetric = 1;
    left.left_deg = 40.0;
    left.right_deg = 0.0;
    left.up_deg = 20.0;
    left.down_deg = 10.0;
    SkyShmView right = left;
    right.left_deg = 0.0;
    right.right_deg = 40.0;
    const GroundCamera l = makeGroundCamera(left);
    const GroundCamera r = makeGroundCamera(right);
    auto angleDeg = [&](const glm::dvec3& a, const glm::dvec3& b) {
        return std::acos(std::min(1.0, glm::dot(a, b))) / kDeg;
    };
    // The view axis's row: tan(20) of tan(20) + tan(10) down from the top edge.
    const double axisRow = 100.0 * std::tan(20.0 * kDeg) / (std::tan(20.0 * kDeg) + std::tan(10.0 * kDeg));
    // Heading 0, level: forward is north, right is east, up is up.
    const glm::dvec3 leftEdge = viewRay(l, 0.0, axisRow);
    EXPECT_NEAR(std::atan2(-leftEdge.x, leftEdge.y) / kDeg, 40.0, 1e-9) << "left edge 40 degrees left of the axis";
    EXPECT_NEAR(angleDeg(viewRay(l, 200.0, axisRow), l.forwardEnu), 0.0, 1e-6) << "right edge on the axis";
    const glm::dvec3 top = viewRay(l, 200.0, 0.0);
    EXPECT_NEAR(std::atan2(top.z, top.y) / kDeg, 20.0, 1e-9) << "top edge 20 degrees up";
    const glm::dvec3 bottom = viewRay(l, 200.0, 100.0);
    EXPECT_NEAR(std::atan2(bottom.z, bottom.y) / kDeg, -10.0, 1e-9) << "bottom edge 10 degrees down";
    for (double y : {0.0, 37.5, 100.0})
        EXPECT_NEAR(angleDeg(viewRay(l, 200.0, y), viewRay(r, 0.0, y)), 0.0, 1e-6) << "the channels meet, row " << y;
    // A symmetric view is the same camera as before: fov 30 = up 15 + down 15, sides from the aspect.
    SkyShmView sym = levelView(200, 100);
    sym.fov_deg = 30.0;
    const GroundCamera s = makeGroundCamera(sym);
    EXPECT_NEAR(s.tanUp, std::tan(15.0 * kDeg), 1e-12);
    EXPECT_NEAR(s.tanLeft, 2.0 * std::tan(15.0 * kDeg), 1e-12);
    // The demo's view of an asymmetric channel carries the four angles and fov = up + down.
    ViewAngles angles;
    angles.asymmetric = true;
    angles.leftDeg = 40.0;
    angles.upDeg = 20.0;
    angles.downDeg = 10.0;
    const SkyShmView sent = viewOf(Aircraft{}, angles, 200, 100);
    EXPECT_EQ(sent.asymmetric, 1u);
    EXPECT_DOUBLE_EQ(sent.left_deg, 40.0);
    EXPECT_DOUBLE_EQ(sent.fov_deg, 30.0);
}

TEST(ClientDemoGround, ShadowLookupFollowsTheGeoReference)
{
    std::vector<float> map(16, 1.0f);
    map[1 * 4 + 2] = 0.0f;  // column 2, row 1: east 0.5 km, north 0.5 km of the centre (texels of 1 km)
    EXPECT_NEAR(shadowTransmittanceAt(map, 4, 4000.0, 500.0, 500.0), 0.0, 1e-9);
    EXPECT_NEAR(shadowTransmittanceAt(map, 4, 4000.0, -500.0, 500.0), 1.0, 1e-9);
    EXPECT_NEAR(shadowTransmittanceAt(map, 4, 4000.0, 500.0, -500.0), 1.0, 1e-9);
    EXPECT_NEAR(shadowTransmittanceAt(map, 4, 4000.0, 1000.0, 500.0), 0.5, 1e-9);  // half way to the next centre
    EXPECT_NEAR(shadowTransmittanceAt(map, 4, 4000.0, 9000.0, 0.0), 1.0, 1e-9);   // outside: clear
    EXPECT_NEAR(shadowTransmittanceAt({}, 0, 4000.0, 0.0, 0.0), 1.0, 1e-9);

    // The eye 1 km east and 2 km north of the map's centre, in the tangent plane.
    SkyShmShadowGeoRef geo{};
    geo.centre_lat_deg = 44.3;
    geo.centre_lon_deg = 7.5;
    const double mPerDegLat = 111132.0;  // ~ at 44 N (meridian arc per degree, standard tables)
    const double mPerDegLon = 79800.0;   // ~ 111320 cos(44.3)
    const std::array<double, 2> en = offsetFromShadowCentreM(44.3 + 2000.0 / mPerDegLat, 7.5 + 1000.0 / mPerDegLon, geo);
    EXPECT_NEAR(en[0], 1000.0, 10.0);
    EXPECT_NEAR(en[1], 2000.0, 10.0);
}

TEST(ClientDemoGround, ShadowDarkensSunlitGroundOnly)
{
    GroundLight sun;
    sun.sunElevationDeg = 60.0;
    const glm::dvec3 lit = shadeGround(44.31, 7.51, sun, 1.0);
    const glm::dvec3 shaded = shadeGround(44.31, 7.51, sun, 0.0);
    EXPECT_LT(shaded.g, 0.6 * lit.g);
    EXPECT_GT(shaded.g, 0.0);  // sky light still reaches it
    GroundLight night;
    night.sunElevationDeg = -30.0;
    EXPECT_LT(shadeGround(44.31, 7.51, night, 1.0).g, 0.2 * lit.g);
}

TEST(ClientDemoCompositing, GroundUnderAnOpaqueShadowTexelIsDarkened)
{
    // Pitched down 60 degrees, the image centre looks at the ground ~870 m north of the eye, inside the
    // block of columns 3-4 (east -1..1 km) and rows 2-3 (north 0..2 km) of an 8 km map of 1 km texels.
    SkyShmView view = levelView(64, 64);
    view.pitch_deg = -60.0;
    const GroundCamera cam = makeGroundCamera(view);
    GroundHit hit;
    ASSERT_TRUE(intersectGround(cam, viewRay(cam, 32.5, 32.5), hit));
    ASSERT_NEAR(hit.northM, 866.0, 60.0);
    ASSERT_NEAR(hit.eastM, 0.0, 60.0);
    EXPECT_NEAR(shadowTransmittanceAt(frameWithShadow(view, 3, 2).shadowTransmittance, 8, 8000.0, hit.eastM,
                                      hit.northM), 0.0, 1e-9);

    CompositeOptions options;
    sky::ImageRgba8 shadowed;
    sky::ImageRgba8 clear;
    const LatestFrame underOpaque = frameWithShadow(view, 3, 2);
    compositeFrame(underOpaque, options, shadowed);
    const LatestFrame underClear = frameWithShadow(view, 0, 0);  // the opaque block far in the north-west
    compositeFrame(underClear, options, clear);
    ASSERT_EQ(shadowed.width, 64u);
    const uint8_t* s = shadowed.pixel(32, 32);
    const uint8_t* c = clear.pixel(32, 32);
    EXPECT_LT(int(s[1]) + 20, int(c[1])) << "green: shadowed " << int(s[1]) << ", clear " << int(c[1]);
    // A ground point outside both blocks (top-right pixel: ~2.5 km north, ~1.4 km east) is the same in both.
    const uint8_t* s2 = shadowed.pixel(62, 1);
    const uint8_t* c2 = clear.pixel(62, 1);
    EXPECT_EQ(int(s2[1]), int(c2[1]));
    // The frame shows through: the ground is blended, not pasted (the frame is grey-blue, the ground not).
    EXPECT_NE(int(c[2]), 130);
}

TEST(ClientDemoCompositing, SkyIsTheFrameUntouched)
{
    const SkyShmView view = levelView(32, 32);
    LatestFrame f = frameWithShadow(view, 0, 0);
    sky::ImageRgba8 out;
    compositeFrame(f, CompositeOptions{}, out);
    for (uint32_t x = 0; x < 32; ++x)
        EXPECT_EQ(out.pixel(x, 3)[2], 130u);  // well above the horizon
    EXPECT_NE(out.pixel(16, 31)[1], 110u);   // below it: ground
    CompositeOptions off;
    off.ground = false;
    compositeFrame(f, off, out);
    EXPECT_EQ(out.pixels, f.rgba);
}

TEST(ClientDemoFlight, FliesAlongItsHeadingAndClimbsWithPitch)
{
    Aircraft a;
    a.latDeg = 44.3;
    a.lonDeg = 7.5;
    a.headingDeg = 90.0;
    a.speedMps = 100.0;
    advanceAircraft(a, FlightInput{}, 10.0);
    EXPECT_NEAR(a.latDeg, 44.3, 1e-6);
    EXPECT_NEAR((a.lonDeg - 7.5) * 79800.0, 1000.0, 5.0);  // 1 km east
    a.pitchDeg = 30.0;
    const double alt = a.altitudeM;
    advanceAircraft(a, FlightInput{}, 10.0);
    EXPECT_NEAR(a.altitudeM - alt, 500.0, 1e-6);  // 1000 m * sin 30
    FlightInput turn;
    turn.turnDegPerS = 30.0;
    advanceAircraft(a, turn, 10.0);
    EXPECT_NEAR(a.headingDeg, 30.0, 1e-9);  // 90 + 300, wrapped
    a.altitudeM = 30.0;
    a.pitchDeg = -80.0;
    advanceAircraft(a, FlightInput{}, 10.0);
    EXPECT_EQ(a.altitudeM, kMinAltitudeM);
}

TEST(ClientDemoTime, ParsesAndFormatsIsoUtc)
{
    double t = 0.0;
    ASSERT_TRUE(parseUtc("2026-06-21T12:00:00Z", t));
    EXPECT_EQ(t, 1782043200.0);
    EXPECT_EQ(formatUtc(t + 3600.5), "2026-06-21T13:00:00Z");
    EXPECT_FALSE(parseUtc("2026-06-21 12:00", t));
    EXPECT_FALSE(parseUtc("2026-13-01T00:00:00Z", t));
}

}  // namespace
