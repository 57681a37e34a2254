// SPDX-License-Identifier: MIT
// client_demo's compositing by depth with the service's layers, on synthetic layers: a cloud deck (alpha 1,
// depth 5 km) in front of a valley floor 8 km away and behind two peaks 3 km away; the terrain's ray march;
// the tone mapping.
#include "client_demo/compositor.h"
#include "client_demo/layer_compositor.h"
#include "client_demo/terrain.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace
{

using namespace demo;

constexpr uint32_t kWidth = 128;
constexpr uint32_t kHeight = 64;
const glm::dvec3 kSky(0.20, 0.35, 0.80);
const glm::dvec3 kCloud(0.90, 0.90, 0.90);  // premultiplied by alpha 1

SkyShmView levelView()
{
    SkyShmView v{};
    v.lat_deg = 44.3;
    v.lon_deg = 7.5;
    v.alt_m = 1500.0;
    v.fov_deg = 60.0;
    v.width = kWidth;
    v.height = kHeight;
    return v;
}

// Two peaks of 3000 m (sigma 700 m) 3 km north of the eye, 2 km west and east of its track: between them a
// valley whose floor (~100 m) the eye sees ~8 km away.
DemoTerrain twoPeaks(const SkyShmView& view)
{
    const GroundCamera cam = makeGroundCamera(view);
    DemoTerrain t;
    for (double east : {-2000.0, 2000.0})
    {
        GroundHit at;
        at.eastM = east;
        at.northM = 3000.0;
        const std::array<double, 2> latLon = groundLatLonDeg(cam, at);
        t.peaks.push_back({latLon[0], latLon[1], 3000.0, 700.0});
    }
    return t;
}

// A frame whose layers are a uniform sky and a uniform deck of cloud at cloudDepthM (alpha, colour alpha *
// kCloud), its front at cloudFrontM (< 0: the same); the shadow map is absent (the terrain is lit by the
// default mid-morning sun).
LatestFrame deckFrame(double alpha, double cloudDepthM, double cloudFrontM = -1.0)
{
    LatestFrame f;
    f.frameId = 1;
    f.view = levelView();
    f.width = kWidth;
    f.height = kHeight;
    const size_t n = size_t(kWidth) * kHeight;
    f.rgba.assign(4 * n, 255);
    f.skyRgba.resize(4 * n);
    f.cloudsRgba.resize(4 * n);
    f.depthM.resize(2 * n);
    for (size_t i = 0; i < n; ++i)
    {
        f.depthM[2 * i] = alpha > 0.0 ? float(cloudFrontM < 0.0 ? cloudDepthM : cloudFrontM) : 0.0f;
        f.depthM[2 * i + 1] = alpha > 0.0 ? float(cloudDepthM) : 0.0f;
    }
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
        {
            f.skyRgba[4 * i + k] = float(kSky[k]);
            f.cloudsRgba[4 * i + k] = float(kCloud[k] * alpha);
        }
    for (size_t i = 0; i < n; ++i)
    {
        f.skyRgba[4 * i + 3] = 1.0f;
        f.cloudsRgba[4 * i + 3] = float(alpha);
    }
    return f;
}

// The pixel (column, row) whose centre ray is nearest to the ENU direction d (level view heading north).
std::array<uint32_t, 2> pixelToward(const glm::dvec3& d)
{
    const GroundCamera cam = makeGroundCamera(levelView());
    const double ndcX = d.x / d.y / cam.tanRight;
    const double ndcY = -d.z / d.y / cam.tanUp;  // symmetric: tanUp = tanDown
    return {uint32_t((ndcX + 1.0) * 0.5 * kWidth), uint32_t((ndcY + 1.0) * 0.5 * kHeight)};
}

double terrainDistanceAt(const std::array<uint32_t, 2>& px)
{
    const SkyShmView view = levelView();
    const GroundCamera cam = makeGroundCamera(view);
    TerrainHit hit;
    if (!intersectTerrain(cam, localTerrain(twoPeaks(view), cam), viewRay(cam, px[0] + 0.5, px[1] + 0.5), hit))
        return -1.0;
    return hit.distanceM;
}

std::array<int, 3> rgbOf(const sky::ImageRgba8& image, const std::array<uint32_t, 2>& px)
{
    const uint8_t* p = image.pixel(px[0], px[1]);
    return {p[0], p[1], p[2]};
}

std::array<int, 3> displayOf(const glm::dvec3& linear)
{
    uint8_t rgb[3];
    toDisplayRgb8(linear, rgb);
    return {rgb[0], rgb[1], rgb[2]};
}

sky::ImageRgba8 compositeWith(const LatestFrame& frame, CompositeStats* stats = nullptr)
{
    CompositeOptions options;
    options.terrain = twoPeaks(frame.view);
    sky::ImageRgba8 out;
    compositeFrame(frame, options, out, stats);
    return out;
}

// The peak's flank straight toward the west peak at eye level, and the valley floor between the peaks.
const std::array<uint32_t, 2> kPeakPixel = pixelToward(glm::dvec3(-2000.0, 3000.0, 0.0));
const std::array<uint32_t, 2> kValleyPixel = pixelToward(glm::dvec3(0.0, 7500.0, -1400.0));
const std::array<uint32_t, 2> kSkyPixel = {kWidth / 2, 4};

TEST(ClientDemoLayers, PixelRulesOfDepthCompositing)
{
    const glm::dvec4 deck(0.9, 0.9, 0.9, 1.0);
    SceneSample peak{true, 3000.0, glm::dvec3(0.05, 0.08, 0.03)};
    SceneSample valley{true, 8000.0, glm::dvec3(0.04, 0.06, 0.02)};
    const SceneSample none;
    EXPECT_EQ(compositeOverScene(kSky, deck, 5000.0, peak), peak.radiance);     // in front of the deck
    EXPECT_EQ(compositeOverScene(kSky, deck, 5000.0, valley), glm::dvec3(0.9));  // under it: hidden
    EXPECT_EQ(compositeOverScene(kSky, glm::dvec4(0.0), 0.0, valley), valley.radiance);  // no cloud
    // A cloud whose depth is unknown (0) stays over the scene instead of vanishing behind it.
    const glm::dvec4 halfCloud(0.2, 0.2, 0.2, 0.5);
    EXPECT_EQ(compositeOverScene(kSky, halfCloud, 0.0, valley), valley.radiance * 0.5 + glm::dvec3(0.2));
    const glm::dvec4 thin(0.36, 0.36, 0.36, 0.4);                                     // premultiplied, alpha 0.4
    const glm::dvec3 blended = compositeOverScene(kSky, thin, 5000.0, valley);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(blended[k], valley.radiance[k] * 0.6 + 0.36, 1e-12);
    const glm::dvec3 skyOnly = compositeOverScene(kSky, thin, 5000.0, none);
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(skyOnly[k], kSky[k] * 0.6 + 0.36, 1e-12);
}

TEST(ClientDemoLayers, PeakInFrontOfTheDeckValleyBehindIt)
{
    ASSERT_NEAR(terrainDistanceAt(kPeakPixel), 3000.0, 500.0);
    ASSERT_NEAR(terrainDistanceAt(kValleyPixel), 8000.0, 1000.0);
    ASSERT_LT(terrainDistanceAt(kSkyPixel), 0.0);

    CompositeStats stats;
    const sky::ImageRgba8 out = compositeWith(deckFrame(1.0, 5000.0), &stats);
    EXPECT_EQ(stats.mode, CompositeMode::Layers);
    ASSERT_EQ(out.width, kWidth);
    const std::array<int, 3> cloud = displayOf(kCloud);
    // The valley floor lies under the deck: exactly the cloud's colour, as is the sky above.
    EXPECT_EQ(rgbOf(out, kValleyPixel), cloud);
    EXPECT_EQ(rgbOf(out, kSkyPixel), cloud);
    // The peak pierces it: terrain (much darker than the white deck, no more blue than green).
    const std::array<int, 3> peak = rgbOf(out, kPeakPixel);
    EXPECT_LT(peak[1] + 60, cloud[1]) << peak[0] << " " << peak[1] << " " << peak[2];
    EXPECT_LE(peak[2], peak[1] + 10);
    EXPECT_GT(stats.terrainInFrontPixels, 50u);
    EXPECT_GT(stats.terrainBehindCloudPixels, 500u);
    EXPECT_EQ(stats.terrainPixels, stats.terrainInFrontPixels + stats.terrainBehindCloudPixels);
    // Every pixel follows the rule: terrain nearer than 5 km is not the cloud, the rest is.
    const SkyShmView view = levelView();
    const GroundCamera cam = makeGroundCamera(view);
    const LocalTerrain terrain = localTerrain(twoPeaks(view), cam);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x)
        {
            TerrainHit hit;
            const bool front = intersectTerrain(cam, terrain, viewRay(cam, x + 0.5, y + 0.5), hit) &&
                               hit.distanceM < 5000.0;
            ASSERT_EQ(rgbOf(out, {x, y}) != cloud, front) << "pixel " << x << "," << y;
        }
}

// The depth layer's front decides: a deck whose front is at 2 km and whose weighted distance is at 5 km
// hides the peak (3 km away), which the weighted distance alone would put in front of it.
TEST(ClientDemoLayers, TerrainBehindTheCloudsFrontIsHiddenWhateverTheWeightedDistance)
{
    CompositeStats stats;
    const sky::ImageRgba8 out = compositeWith(deckFrame(1.0, 5000.0, 2000.0), &stats);
    const std::array<int, 3> cloud = displayOf(kCloud);
    EXPECT_EQ(rgbOf(out, kPeakPixel), cloud);
    EXPECT_EQ(rgbOf(out, kValleyPixel), cloud);
    EXPECT_EQ(stats.terrainInFrontPixels, 0u) << "no terrain lies nearer than 2 km";
    // The same deck with its front at the weighted distance lets the peak through.
    EXPECT_NE(rgbOf(compositeWith(deckFrame(1.0, 5000.0)), kPeakPixel), cloud);
}

TEST(ClientDemoLayers, PartialAlphaBlendsTheValleyAndTheSky)
{
    const sky::ImageRgba8 clear = compositeWith(deckFrame(0.0, 0.0));
    const sky::ImageRgba8 half = compositeWith(deckFrame(0.5, 5000.0));
    const sky::ImageRgba8 opaque = compositeWith(deckFrame(1.0, 5000.0));
    // No cloud: the valley is terrain, the sky the sky layer.
    EXPECT_EQ(rgbOf(clear, kSkyPixel), displayOf(kSky));
    EXPECT_NE(rgbOf(clear, kValleyPixel), rgbOf(opaque, kValleyPixel));
    // Half a cloud: sky * 0.5 + clouds; the valley between terrain and cloud; the peak in front untouched.
    EXPECT_EQ(rgbOf(half, kSkyPixel), displayOf(kSky * 0.5 + kCloud * 0.5));
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_GT(rgbOf(half, kValleyPixel)[k], rgbOf(clear, kValleyPixel)[k]);
        EXPECT_LT(rgbOf(half, kValleyPixel)[k], rgbOf(opaque, kValleyPixel)[k]);
    }
    EXPECT_EQ(rgbOf(half, kPeakPixel), rgbOf(clear, kPeakPixel));
}

TEST(ClientDemoLayers, WithoutLayersOrGroundTheFrameIsTheServices)
{
    // A frame without layers (the vulkan transport) takes the display path.
    LatestFrame noLayers = deckFrame(1.0, 5000.0);
    noLayers.depthM.clear();
    CompositeStats stats;
    compositeWith(noLayers, &stats);
    EXPECT_EQ(stats.mode, CompositeMode::Display);
    // Ground off: sky * (1 - a) + clouds through the service's curve everywhere, terrain nowhere.
    CompositeOptions off;
    off.ground = false;
    off.terrain = twoPeaks(levelView());
    sky::ImageRgba8 out;
    compositeFrame(deckFrame(0.5, 5000.0), off, out, &stats);
    EXPECT_EQ(stats.terrainPixels, 0u);
    EXPECT_EQ(rgbOf(out, kPeakPixel), displayOf(kSky * 0.5 + kCloud * 0.5));
}

TEST(ClientDemoLayers, ToneMappingIsTheServicesCurve)
{
    // Narkowicz's ACES fit at 1: (2.51 + 0.03) / (2.43 + 0.59 + 0.14); sRGB of 0.5: 1.055 * 0.5^(1/2.4) - 0.055.
    EXPECT_NEAR(tonemapAces(glm::dvec3(1.0)).x, 2.54 / 3.16, 1e-12);
    EXPECT_EQ(tonemapAces(glm::dvec3(100.0)).x, 1.0);
    EXPECT_EQ(tonemapAces(glm::dvec3(0.0)).x, 0.0);
    EXPECT_NEAR(encodeSrgb(0.5), 0.735357, 1e-6);
    EXPECT_NEAR(encodeSrgb(0.002), 0.02584, 1e-12);
}

TEST(ClientDemoTerrain, RayMarchMeetsThePeakAndTheFlatGround)
{
    SkyShmView down = levelView();
    down.alt_m = 5000.0;
    down.pitch_deg = -89.99;
    const GroundCamera cam = makeGroundCamera(down);
    // A peak right below the eye: met at 5000 - 3000 m, its normal straight up.
    DemoTerrain below;
    below.peaks.push_back({down.lat_deg, down.lon_deg, 3000.0, 2000.0});
    TerrainHit hit;
    ASSERT_TRUE(intersectTerrain(cam, localTerrain(below, cam), glm::dvec3(0.0, 0.0, -1.0), hit));
    EXPECT_NEAR(hit.distanceM, 2000.0, 0.05);
    EXPECT_NEAR(hit.heightM, 3000.0, 0.05);
    EXPECT_NEAR(hit.normalEnu.z, 1.0, 1e-6);
    // Without peaks the march is the flat ground's intersection.
    GroundHit flat;
    const glm::dvec3 slant = glm::normalize(glm::dvec3(0.3, 1.0, -0.2));
    ASSERT_TRUE(intersectGround(cam, slant, flat));
    ASSERT_TRUE(intersectTerrain(cam, localTerrain(DemoTerrain{}, cam), slant, hit));
    EXPECT_NEAR(hit.distanceM, flat.distanceM, 1e-6);
    // Up into the sky: nothing; an eye inside the rock: nothing drawn.
    EXPECT_FALSE(intersectTerrain(cam, localTerrain(below, cam), glm::dvec3(0.0, 0.6, 0.8), hit));
    SkyShmView inside = down;
    inside.alt_m = 2500.0;
    const GroundCamera camInside = makeGroundCamera(inside);
    EXPECT_FALSE(intersectTerrain(camInside, localTerrain(below, camInside), glm::dvec3(0.0, 0.0, -1.0), hit));
}

TEST(ClientDemoTerrain, MountainAheadAndItsLightAndShadow)
{
    // Heading east: the main peak 12 km east, the shoulder 8 km south of it (to the right).
    const DemoTerrain t = demoMountainAhead(44.3, 7.5, 90.0);
    ASSERT_EQ(t.peaks.size(), 2u);
    SkyShmView v = levelView();
    const GroundCamera cam = makeGroundCamera(v);
    const LocalTerrain local = localTerrain(t, cam);
    EXPECT_NEAR(local.peaks[0].eastM, 12000.0, 5.0);
    EXPECT_NEAR(local.peaks[0].northM, 0.0, 5.0);
    EXPECT_NEAR(local.peaks[1].northM, -8000.0, 5.0);
    EXPECT_NEAR(terrainHeightM(local, 12000.0, 0.0), 3000.0, 5.0);
    const double saddle = terrainHeightM(local, 12000.0, -4000.0);
    EXPECT_LT(saddle, 1200.0);  // a valley between the peaks
    EXPECT_GT(saddle, 800.0);

    // The key light's footprint: a point 1000 m up, the sun in the south at 45 degrees -> 1000 m north.
    TerrainHit hit;
    hit.heightM = 1000.0;
    TerrainLight south;
    south.azimuthDeg = 180.0;
    south.elevationDeg = 45.0;
    const std::array<double, 2> footprint = shadowFootprintM(hit, south);
    EXPECT_NEAR(footprint[0], 0.0, 1e-9);
    EXPECT_NEAR(footprint[1], 1000.0, 1e-9);
    // A slope facing the light is brighter than one facing away; the cloud shadow darkens it.
    hit.normalEnu = glm::normalize(glm::dvec3(0.0, -1.0, 1.0));
    const glm::dvec3 facing = shadeTerrainLinear(hit, 44.3, 7.5, south, 1.0);
    hit.normalEnu = glm::normalize(glm::dvec3(0.0, 1.0, 1.0));
    const glm::dvec3 away = shadeTerrainLinear(hit, 44.3, 7.5, south, 1.0);
    hit.normalEnu = glm::normalize(glm::dvec3(0.0, -1.0, 1.0));
    const glm::dvec3 shadowed = shadeTerrainLinear(hit, 44.3, 7.5, south, 0.0);
    EXPECT_GT(facing.g, 2.0 * away.g);
    EXPECT_LT(shadowed.g, 0.5 * facing.g);
    EXPECT_GT(shadowed.g, 0.0);
}

}  // namespace
