// SPDX-License-Identifier: MIT
// Geo-referencing accuracy: clouds appear where the snapshot's latitude, longitude and
// altitude put them, anywhere on the globe; the real GFS sample renders its decks and its clear sky.
// GPU tests on the available Vulkan device (lavapipe in CI), validation on, small images.
#include "skyservice/output/image_files.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/ephemeris.h"
#include "skyservice/sky/weather_places.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#ifdef SKY_HAVE_INGEST
#include "weather_ingest/ingest.h"
#endif

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

using namespace sky;
using namespace sky::testscenes;

namespace
{

class Georef : public GpuFixture
{
protected:

    RenderResult render(const WeatherSnapshot& weather, const ViewRequest& request)
    {
        setWeather(*renderer, weather);
        RenderResult result;
        SkyStatus s = renderView(*renderer, request, testQuality(), result);
        EXPECT_TRUE(s.ok()) << s.message;
        // For looking at the pictures: SKY_TEST_IMAGE_DIR=DIR writes DIR/<test name>.png.
        if (const char* dir = std::getenv("SKY_TEST_IMAGE_DIR"))
        {
            std::string error;
            const std::string path =
                std::string(dir) + "/" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".png";
            EXPECT_TRUE(writePng(path, {result.width, result.height, result.displayRgba8}, error)) << error;
        }
        return result;
    }

    // One cumulus cell (radius 2.5 km, 2000-3500 m) at a known place, seen from ~50 km away with the
    // cell off the image centre (10 degrees left of it, 3 degrees above), so a wrong heading, pitch or
    // pixel mapping moves it. The alpha-weighted centroid of the cloud pixels, turned into a view
    // direction by the mapping of shaders/clouds/view_ray.glsl, must lie within 1 degree of the
    // direction GeographicLib gives from the eye to the cell's centre at mid-cloud height, and no
    // cloud may appear beyond 5 degrees from it.
    void checkCellDirection(double eyeLatDeg, double eyeLonDeg, double cellLatDeg, double cellLonDeg,
                            const std::string& timeIso)
    {
        const double eyeAltitudeM = 1500.0, radiusM = 2500.0;
        const float baseM = 2000.0f, topM = 3500.0f;
        WeatherSnapshot cell = isolatedCell(cellLatDeg, cellLonDeg, radiusM, CloudType::Cumulus, baseM, topM);

        const CameraFrame level = computeCameraFrame({eyeLatDeg, eyeLonDeg, eyeAltitudeM, 0.0, 0.0, 0.0});
        const glm::dvec3 target = geodeticToEnu(level, cellLatDeg, cellLonDeg, 0.5 * double(baseM + topM));
        double azimuthDeg = 0, elevationDeg = 0;
        enuDirectionToAzimuthElevation(target, azimuthDeg, elevationDeg);
        const double distanceKm = glm::length(target) / 1000.0;

        ViewRequest v;
        v.pose = {eyeLatDeg, eyeLonDeg, eyeAltitudeM, azimuthDeg + 10.0, elevationDeg - 3.0, 0.0};
        v.fovYDeg = 30.0;
        v.width = 320;
        v.height = 180;
        v.unixTimeS = parseTime(timeIso);
        RenderResult r = render(cell, v);

        const CameraFrame cam = computeCameraFrame(v.pose);
        const CloudCentroid c = cloudCentroid(r, 0.01f);
        ASSERT_GT(c.pixels, 100u) << "the cell is not in the picture";
        const glm::dvec3 seen = pixelRayEnu(cam, v, c.xPx, c.yPx);
        double seenAzimuthDeg = 0, seenElevationDeg = 0;
        enuDirectionToAzimuthElevation(seen, seenAzimuthDeg, seenElevationDeg);
        const double errorDeg = std::acos(std::clamp(glm::dot(seen, glm::normalize(target)), -1.0, 1.0)) * 180.0 / M_PI;
        uint32_t stray = 0;
        const double spreadDeg = maxCloudAngleDeg(r, cam, v, target, 0.01f, 5.0, stray);
        std::printf("  eye %s -> cell %s: %.1f km, expected az %.3f el %.3f, seen az %.3f el %.3f "
                    "(centroid %.1f, %.1f px, %u px): error %.3f deg, cloud up to %.2f deg away\n",
                    formatLatLon(eyeLatDeg, eyeLonDeg).c_str(), formatLatLon(cellLatDeg, cellLonDeg).c_str(),
                    distanceKm, azimuthDeg, elevationDeg, seenAzimuthDeg, seenElevationDeg, c.xPx, c.yPx, c.pixels,
                    errorDeg, spreadDeg);
        EXPECT_GT(distanceKm, 45.0);
        EXPECT_LT(distanceKm, 55.0);
        EXPECT_LT(errorDeg, 1.0);
        EXPECT_EQ(stray, 0u) << "cloud pixels more than 5 degrees from the cell (up to " << spreadDeg << " deg)";
    }
};

}  // namespace

TEST_F(Georef, CellAppearsInItsGeodesicDirectionMidLatitude)
{
    checkCellDirection(45.0, 7.0, 45.3, 7.5, "2026-06-21T12:00:00Z");
}

// Svalbard: meridians converge, one degree of longitude is 23 km.
TEST_F(Georef, CellAppearsInItsGeodesicDirectionAt78North)
{
    checkCellDirection(78.0, 15.0, 78.35, 16.3, "2026-06-21T12:00:00Z");
}

// Eye at 179.8 E, cell at 179.7 W: the cell's grid runs from 179.8 E (written -180.2) eastwards.
TEST_F(Georef, CellAppearsInItsGeodesicDirectionAcrossTheAntimeridian)
{
    checkCellDirection(25.0, 179.8, 25.1, -179.7, "2026-06-21T00:00:00Z");
}

// ---------------------------------------------------------------------------------------------------
// The real GFS sample (README.md): converted here with sky_ingest, places chosen from the data.

#ifdef SKY_HAVE_INGEST
namespace
{

const std::string kGfsPath = std::string(SKY_SHARED_DIR) + "/weather/gfs-2p5deg-20110110-12z-f120.grib2";

// Converted once for the whole suite (about a second).
const WeatherSnapshot* gfsSnapshot()
{
    static std::unique_ptr<WeatherSnapshot> snapshot;
    if (!snapshot && std::filesystem::exists(kGfsPath))
    {
        ConvertResult converted = convertFiles({kGfsPath}, MappingOptions{}, {});
        if (converted.snapshots.size() == 1)
            snapshot = std::make_unique<WeatherSnapshot>(std::move(converted.snapshots[0]));
    }
    return snapshot.get();
}

ViewRequest lookUpAt(const WeatherPlace& place, double altitudeM, int64_t unixTimeS)
{
    ViewRequest v = lookUp(place.latDeg, place.lonDeg, altitudeM, 40.0, "2011-01-15T12:00:00Z");
    v.unixTimeS = unixTimeS;
    return v;
}

}  // namespace

TEST_F(Georef, GfsLowDeckWhereLowCoverIsHigh)
{
    if (!std::filesystem::exists(kGfsPath))
        GTEST_SKIP() << kGfsPath << " not found";
    const WeatherSnapshot* gfs = gfsSnapshot();
    ASSERT_NE(gfs, nullptr) << "conversion gave no single snapshot";
    const WeatherPlace place = findWeatherPlace(*gfs, PlaceKind::LowDeck);
    ASSERT_TRUE(place.found);
    std::printf("  low deck: %s\n", describeWeatherPlace(place).c_str());
    ASSERT_GT(place.coverage[0], 0.8f);
    ASSERT_TRUE(std::isfinite(place.baseM[0]) && std::isfinite(place.topM[0]));

    // Below the deck, looking up 40 degrees (the lowest row looks 10 degrees above the horizon).
    const double eyeM = std::max(20.0, 0.5 * double(place.baseM[0]));
    const ViewRequest v = lookUpAt(place, eyeM, gfs->validTimeUnixS);
    RenderResult r = render(*gfs, v);
    const ImageStats s = cloudStats(r);
    const double fraction = double(s.cloudPixels) / double(s.skyPixels);
    std::printf("  eye %.0f m: cloud fraction above the horizon %.3f\n", eyeM, fraction);
    EXPECT_GE(fraction, 0.6);
    EXPECT_TRUE(s.allFinite);

    // The deck is where the data puts it: the cloud depth at the top centre pixel (70 degrees up)
    // lies between the slant distances to the data's base and top (with 20% slack for the profile).
    const CameraFrame cam = computeCameraFrame(v.pose);
    const uint32_t x = v.width / 2, y = 0;
    const glm::dvec3 ray = pixelRayEnu(cam, v, x + 0.5, y + 0.5);
    const float alpha = glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]);
    const double depthM = double(r.cloudDepthM[size_t(y) * r.width + x]);
    const double toBaseM = (double(place.baseM[0]) - eyeM) / ray.z, toTopM = (double(place.topM[0]) - eyeM) / ray.z;
    std::printf("  top-centre pixel: alpha %.2f, cloud depth %.0f m (base %.0f m, top %.0f m away)\n", double(alpha),
                depthM, toBaseM, toTopM);
    EXPECT_GT(alpha, 0.5f);
    EXPECT_GT(depthM, 0.8 * toBaseM);
    EXPECT_LT(depthM, 1.2 * toTopM);
}

TEST_F(Georef, GfsClearSkyWhereAllCoverIsZero)
{
    if (!std::filesystem::exists(kGfsPath))
        GTEST_SKIP() << kGfsPath << " not found";
    const WeatherSnapshot* gfs = gfsSnapshot();
    ASSERT_NE(gfs, nullptr) << "conversion gave no single snapshot";
    const WeatherPlace place = findWeatherPlace(*gfs, PlaceKind::Clear);
    ASSERT_TRUE(place.found);
    std::printf("  clear: %s, clear for %.0f rings of cells around\n", describeWeatherPlace(place).c_str(),
                place.score);
    for (int k = 0; k < 4; ++k)
        ASSERT_EQ(place.coverage[k], 0.0f);
    ASSERT_GE(place.score, 1.0) << "no clear cell with clear neighbours";

    RenderResult r = render(*gfs, lookUpAt(place, 300.0, gfs->validTimeUnixS));
    const ImageStats s = cloudStats(r);
    const double fraction = double(s.cloudPixels) / double(s.skyPixels);
    std::printf("  cloud fraction above the horizon %.4f, max alpha %.3f\n", fraction, double(s.maxAlpha));
    EXPECT_LE(fraction, 0.02);
    EXPECT_TRUE(s.allFinite);
}
#else
TEST_F(Georef, GfsLowDeckWhereLowCoverIsHigh) { GTEST_SKIP() << "built without sky_ingest (SKY_BUILD_INGEST=OFF)"; }
TEST_F(Georef, GfsClearSkyWhereAllCoverIsZero) { GTEST_SKIP() << "built without sky_ingest (SKY_BUILD_INGEST=OFF)"; }
#endif
