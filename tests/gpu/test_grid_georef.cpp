// SPDX-License-Identifier: MIT
// Geo-referencing on every grid type ecCodes can locate: a cloud cell written at a known latitude/longitude on a
// Lambert, polar stereographic, Mercator, rotated, reduced Gaussian or reduced lat/lon grid (ecCodes, at
// test time), converted by sky_ingest and rendered, is seen from 50 km within 1 degree of the direction
// GeographicLib gives. GPU test on the available Vulkan device (lavapipe in CI), validation on, 160 x 90.
#include "skyservice/output/image_files.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/weather_places.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"
#include "weather_ingest/grib_fixture.h"
#include "weather_ingest/ingest.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace sky;
using namespace sky::testscenes;

namespace
{

struct GridCase
{
    friend void PrintTo(const GridCase& c, std::ostream* os) { *os << c.name; }
    const char* name;
    CloudDiscFixture fixture;
    double eyeBearingDeg; ///< where the eye is, seen from the cell
    /// How far beyond the cell's angular radius cloud may show (deg): the disc's tapered edge is interpolated
    /// between grid points, so it reaches about a grid spacing further (N1280: 7.7 km, 9 deg at 50 km).
    double edgeMarginDeg = 5.0;
};

class GridGeoref : public GpuFixture, public ::testing::WithParamInterface<GridCase>
{
};

/// Alpha-weighted mean of the cloud pixels' view directions, each pixel weighted by its solid angle too
/// (cos^3 of its angle off the axis), so the mean of a cell that is mirror-symmetric about the vertical
/// plane through the eye lies in that plane wherever the cell sits in the picture.
glm::dvec3 meanCloudDirection(const RenderResult& r, const CameraFrame& cam, const ViewRequest& v, float minAlpha,
                              uint32_t& pixels)
{
    glm::dvec3 sum(0.0);
    pixels = 0;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x)
        {
            const float alpha = glm::unpackHalf1x16(r.cloudRgbaHalf[(size_t(y) * r.width + x) * 4 + 3]);
            if (!(alpha > minAlpha))
                continue;
            ++pixels;
            const glm::dvec3 ray = pixelRayEnu(cam, v, x + 0.5, y + 0.5);
            const double c = glm::dot(ray, cam.forwardEnu);
            sum += double(alpha) * c * c * c * ray;
        }
    return glm::length(sum) > 0 ? glm::normalize(sum) : sum;
}

std::string tempFixturePath(const std::string& name)
{
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sky-grid-georef";
    std::filesystem::create_directories(dir);
    return (dir / (name + ".grib2")).string();
}

// The cell (coverage 100 % tapering to 0 at its radius, a few grid spacings) is written on the grid where
// ecCodes locates the points and converted as a user's file would be. The eye is 50 km away at the layer's
// mid-height, looking level at it with the cell 4 degrees right of the picture's centre: seen edge-on the
// cell is symmetric about the direction of its centre at mid-height, whatever its size and profile, so the
// mean direction of its pixels must lie within 1 degree of the direction GeographicLib gives to that point,
// and no cloud may appear beyond the cell's angular radius plus 5 degrees.
TEST_P(GridGeoref, CellAppearsInItsGeodesicDirection)
{
    const GridCase& c = GetParam();
    const CloudDiscFixture& f = c.fixture;
    const std::string path = tempFixturePath(c.name);
    writeCloudDiscFixture(path, f);
    ConvertResult converted = convertFiles({path}, MappingOptions{}, {});
    ASSERT_EQ(converted.snapshots.size(), 1u);
    const WeatherSnapshot& w = converted.snapshots[0];
    ASSERT_FALSE(w.layers.empty());
    const LatLonGrid& g = w.grid;
    const auto row = uint32_t(std::lround((f.latDeg - g.lat0Deg) / g.dLatDeg));
    const auto col = uint32_t(std::lround(std::remainder(f.lonDeg - g.lon0Deg, 360.0) / g.dLonDeg + g.nLon) % g.nLon);
    ASSERT_LT(row, g.nLat);
    const size_t cell = g.index(row, col);
    const CloudLayerFields& layer = w.layers[0];
    ASSERT_GT(layer.coverage[cell], 0.8f) << "no cloud at the cell's place in the snapshot";
    const double midM = 0.5 * double(layer.baseAltitudeM[cell] + layer.topAltitudeM[cell]);

    // The eye: 50 km from the cell along the bearing (on the cell's tangent plane), at mid-height.
    const CameraFrame atCell = computeCameraFrame({f.latDeg, f.lonDeg, midM, 0.0, 0.0, 0.0});
    const double b = c.eyeBearingDeg * M_PI / 180.0;
    double eyeLatDeg = 0, eyeLonDeg = 0, ignoredM = 0;
    enuToGeodetic(atCell, {50000.0 * std::sin(b), 50000.0 * std::cos(b), 0.0}, eyeLatDeg, eyeLonDeg, ignoredM);
    const CameraFrame level = computeCameraFrame({eyeLatDeg, eyeLonDeg, midM, 0.0, 0.0, 0.0});
    const glm::dvec3 target = geodeticToEnu(level, f.latDeg, f.lonDeg, midM);
    double azimuthDeg = 0, elevationDeg = 0;
    enuDirectionToAzimuthElevation(target, azimuthDeg, elevationDeg);
    const double distanceKm = glm::length(target) / 1000.0;

    ViewRequest v;
    v.pose = {eyeLatDeg, eyeLonDeg, midM, azimuthDeg - 4.0, 0.0, 0.0};
    v.fovYDeg = 36.0;
    v.width = 160;
    v.height = 90;
    v.unixTimeS = w.validTimeUnixS;
    setWeather(*renderer, w);
    const RenderResult r = renderOk(v, testQuality());
    if (const char* dir = std::getenv("SKY_TEST_IMAGE_DIR"))
    {
        std::string error;
        EXPECT_TRUE(
            writePng(std::string(dir) + "/grid_georef_" + c.name + ".png", {r.width, r.height, r.displayRgba8}, error))
            << error;
    }

    const CameraFrame cam = computeCameraFrame(v.pose);
    uint32_t pixels = 0;
    const glm::dvec3 seen = meanCloudDirection(r, cam, v, 0.01f, pixels);
    ASSERT_GT(pixels, 30u) << "the cell is not in the picture";
    double seenAzimuthDeg = 0, seenElevationDeg = 0;
    enuDirectionToAzimuthElevation(seen, seenAzimuthDeg, seenElevationDeg);
    const double errorDeg = std::acos(std::clamp(glm::dot(seen, glm::normalize(target)), -1.0, 1.0)) * 180.0 / M_PI;
    const double cellDeg = std::asin(std::min(1.0, f.radiusKm / distanceKm)) * 180.0 / M_PI;
    uint32_t stray = 0;
    const double spreadDeg = maxCloudAngleDeg(r, cam, v, target, 0.01f, cellDeg + c.edgeMarginDeg, stray);
    std::printf("  %s (%s): eye %s, %.1f km at %.0f m; expected az %.3f el %.3f, seen az %.3f el %.3f (%u px): "
                "error %.3f deg, cloud up to %.1f deg away (cell %.1f deg)\n",
                c.name, w.provenance.at("grid").c_str(), formatLatLon(eyeLatDeg, eyeLonDeg).c_str(), distanceKm, midM,
                azimuthDeg, elevationDeg, seenAzimuthDeg, seenElevationDeg, pixels, errorDeg, spreadDeg, cellDeg);
    EXPECT_GT(distanceKm, 49.0);
    EXPECT_LT(distanceKm, 51.0);
    EXPECT_LT(errorDeg, 1.0);
    EXPECT_EQ(stray, 0u) << "cloud pixels beyond the cell (up to " << spreadDeg << " deg)";
    std::filesystem::remove(path);
}

// Spacings of 2.5-4 km (the reduced Gaussian: N1280, 7.8 km), cells of about 2.5 spacings' radius, domains a
// few hundred km wide; reduced grids as a band of whole rows round the globe.
CloudDiscFixture disc(FixtureGrid kind, double latDeg, double lonDeg, double radiusKm, double scale, double extent,
                      double bandHalfWidthDeg = 0)
{
    return {.kind = kind,
            .latDeg = latDeg,
            .lonDeg = lonDeg,
            .radiusKm = radiusKm,
            .coveragePercent = 100,
            .tapered = true,
            .scale = scale,
            .extent = extent,
            .bandHalfWidthDeg = bandHalfWidthDeg};
}

INSTANTIATE_TEST_SUITE_P(
    GridTypes, GridGeoref,
    ::testing::Values(GridCase{"lambert", disc(FixtureGrid::Lambert, 38, -98, 7, 8, 0.25), 225},
                      GridCase{"lambert_two_parallels", disc(FixtureGrid::LambertTwoParallels, 45, 10, 7, 8, 0.25), 90},
                      GridCase{"polar_north", disc(FixtureGrid::PolarNorth, 80, 30, 7, 20, 0.1), 180},
                      GridCase{"polar_south", disc(FixtureGrid::PolarSouth, -84, 100, 7, 20, 0.1), 300},
                      GridCase{"mercator", disc(FixtureGrid::Mercator, 20, -60, 7, 8, 0.25), 0},
                      GridCase{"rotated", disc(FixtureGrid::Rotated, 52, 14, 7, 10, 0.15), 135},
                      GridCase{"reduced_gaussian", disc(FixtureGrid::ReducedGaussian, 30, 60, 20, 40, 1, 1.5), 45, 10.0},
                      GridCase{"reduced_latlon", disc(FixtureGrid::ReducedLatLon, -35, 150, 10, 10, 1, 0.8), 270}),
    [](const ::testing::TestParamInfo<GridCase>& p) { return std::string(p.param.name); });

} // namespace
