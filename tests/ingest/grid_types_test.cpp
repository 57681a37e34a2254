// SPDX-License-Identifier: MIT
// Every grid type ecCodes can locate: fixtures written from Debian's ecCodes samples at test
// time, a cloud disc at a known latitude/longitude found at that place in the snapshot; regional data
// blending into the grid under it without a step; bad grids named in the error.
#include "weather_ingest/grib_fixture.h"
#include "weather_ingest/grib_writer.h"
#include "weather_ingest/ingest.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/regular_grid.h"

#include "grib_fixtures.h"
#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <numbers>

namespace sky
{
namespace
{

constexpr double kRad = std::numbers::pi / 180.0;

double distanceKm(double lat1, double lon1, double lat2, double lon2)
{
    const double c = std::sin(lat1 * kRad) * std::sin(lat2 * kRad) +
                     std::cos(lat1 * kRad) * std::cos(lat2 * kRad) * std::cos((lon2 - lon1) * kRad);
    return 6371.0 * std::acos(std::clamp(c, -1.0, 1.0));
}

double cellLat(const LatLonGrid& g, size_t c)
{
    return g.lat0Deg + double(c / g.nLon) * g.dLatDeg;
}
double cellLon(const LatLonGrid& g, size_t c)
{
    return g.lon0Deg + double(c % g.nLon) * g.dLonDeg;
}

WeatherSnapshot convertOne(const std::string& path)
{
    ConvertResult r = convertFiles({path}, MappingOptions{}, {});
    EXPECT_EQ(r.snapshots.size(), 1u);
    return std::move(r.snapshots.at(0));
}

struct DiscCase
{
    friend void PrintTo(const DiscCase& c, std::ostream* os) { *os << c.name; }
    const char* name;
    FixtureGrid kind;
    double latDeg, lonDeg, radiusKm, toleranceKm;
    bool iScansNegatively = false, jScansPositively = true;
};

class CloudDisc : public ::testing::TestWithParam<DiscCase>
{
};

// The disc's cells (coverage >= 40 %) must be centred on the known point within about half the grid's
// spacing (Lambert and Mercator 20 km: 10 km; rotated 0.25°: 14 km; reduced lat/lon 0.36°: 20 km; N32
// Gaussian ~280 km: 140 km; polar 50 km: 40 km, its resampled cells near the pole are wider), the cell
// there must be cloudy, and beyond the radius plus twice that there must be none.
TEST_P(CloudDisc, LandsAtItsLatitudeAndLongitude)
{
    const DiscCase& c = GetParam();
    const std::string path = test::tempPath(std::string("disc-") + c.name + ".grib2");
    writeCloudDiscFixture(path, {.kind = c.kind,
                                 .latDeg = c.latDeg,
                                 .lonDeg = c.lonDeg,
                                 .radiusKm = c.radiusKm,
                                 .iScansNegatively = c.iScansNegatively,
                                 .jScansPositively = c.jScansPositively});
    const WeatherSnapshot s = convertOne(path);
    const LatLonGrid& g = s.grid;
    const std::vector<float>& cover = s.layers.at(0).coverage;
    double x = 0, y = 0, z = 0, nearestKm = 1e9, farthestCloudKm = 0;
    size_t nearest = 0, cloudy = 0;
    for (size_t i = 0; i < g.cellCount(); ++i)
    {
        const double lat = cellLat(g, i), lon = cellLon(g, i), d = distanceKm(lat, lon, c.latDeg, c.lonDeg);
        if (d < nearestKm)
            nearestKm = d, nearest = i;
        if (!(cover[i] >= 0.4f))
            continue;
        ++cloudy;
        farthestCloudKm = std::max(farthestCloudKm, d);
        x += std::cos(lat * kRad) * std::cos(lon * kRad);
        y += std::cos(lat * kRad) * std::sin(lon * kRad);
        z += std::sin(lat * kRad);
    }
    ASSERT_GT(cloudy, 3u) << c.name;
    const double centroidLat = std::atan2(z, std::hypot(x, y)) / kRad, centroidLon = std::atan2(y, x) / kRad;
    const double offKm = distanceKm(centroidLat, centroidLon, c.latDeg, c.lonDeg);
    std::printf("  %s: %zu cloudy cells centred %.1f km from the disc's centre, farthest %.0f km (radius %.0f)\n",
                c.name, cloudy, offKm, farthestCloudKm, c.radiusKm);
    EXPECT_LT(offKm, c.toleranceKm)
        << c.name << ": disc centred at " << centroidLat << ", " << centroidLon;
    EXPECT_LT(farthestCloudKm, c.radiusKm + 2 * c.toleranceKm) << c.name;
    EXPECT_GT(cover[nearest], 0.6f) << c.name << " at the known point";
    const bool global = c.kind == FixtureGrid::ReducedGaussian || c.kind == FixtureGrid::ReducedLatLon;
    const char* named = c.kind == FixtureGrid::ReducedGaussian ? "reduced_gg"
                        : c.kind == FixtureGrid::ReducedLatLon ? "reduced_ll"
                                                               : "->";
    EXPECT_NE(s.provenance.at("grid").find(named), std::string::npos) << s.provenance.at("grid");
    if (global)
    {
        EXPECT_TRUE(s.dataWeight.empty()) << "a global grid has data everywhere";
        EXPECT_NEAR(double(g.nLon) * g.dLonDeg, 360.0, 1e-9);
    }
    else
    {
        // A regional grid: data weight 0 (and no cloud, no values) somewhere outside its domain.
        ASSERT_EQ(s.dataWeight.size(), g.cellCount());
        size_t outside = 0;
        for (size_t i = 0; i < g.cellCount(); ++i)
            if (s.dataWeight[i] == 0.0f)
            {
                ++outside;
                EXPECT_FALSE(cover[i] > 0.0f) << i;
            }
        EXPECT_GT(outside, 0u);
        EXPECT_EQ(s.dataWeight[nearest], 1.0f);
    }
}

INSTANTIATE_TEST_SUITE_P(
    GridTypes, CloudDisc,
    ::testing::Values(DiscCase{"lambert", FixtureGrid::Lambert, 38, -98, 150, 10},
                      DiscCase{"lambert_i_negative", FixtureGrid::Lambert, 38, -98, 150, 10, true, true},
                      DiscCase{"lambert_north_to_south", FixtureGrid::Lambert, 38, -98, 150, 10, false, false},
                      DiscCase{"lambert_two_parallels", FixtureGrid::LambertTwoParallels, 45, 10, 150, 10},
                      DiscCase{"polar_north", FixtureGrid::PolarNorth, 80, 30, 300, 40},
                      DiscCase{"polar_north_at_pole", FixtureGrid::PolarNorth, 90, 0, 300, 40},
                      DiscCase{"polar_south", FixtureGrid::PolarSouth, -84, 100, 300, 40},
                      DiscCase{"mercator", FixtureGrid::Mercator, 20, -60, 150, 10},
                      DiscCase{"mercator_north_to_south", FixtureGrid::Mercator, 20, -60, 150, 10, false, false},
                      DiscCase{"rotated", FixtureGrid::Rotated, 52, 14, 150, 14},
                      DiscCase{"rotated_i_negative", FixtureGrid::Rotated, 52, 14, 150, 14, true, false},
                      DiscCase{"reduced_gaussian", FixtureGrid::ReducedGaussian, 30, 60, 700, 140},
                      DiscCase{"reduced_latlon", FixtureGrid::ReducedLatLon, -35, 150, 300, 20}),
    [](const ::testing::TestParamInfo<DiscCase>& p) { return std::string(p.param.name); });

TEST(GridComposite, RegionalOverCoarserGridHasNoStepAtTheEdge)
{
    // Coarse: 1° lat/lon over North America, low cloud 20 %. Fine: Lambert at 6.7 km, 80 % everywhere.
    const LatLonGrid coarse{.lat0Deg = 70, .lon0Deg = -140, .dLatDeg = -1, .dLonDeg = 1, .nLat = 61, .nLon = 91};
    const std::string coarsePath = test::tempPath("coarse.grib2");
    writeGribFile(
        coarsePath,
        {test::field(coarse, {{"dataDate", "20240301"}, {"typeOfLevel", "lowCloudLayer"}, {"shortName", "tcc"}}, 20)});
    const std::string finePath = test::tempPath("fine.grib2");
    writeCloudDiscFixture(finePath,
                          {.kind = FixtureGrid::Lambert, .latDeg = 38, .lonDeg = -98, .radiusKm = 50000, .scale = 3});
    MappingOptions options;
    options.allowLargeOutput = true;  // constant fields pack to a few hundred bytes: 93 MB out is expected here
    ConvertResult r = convertFiles({coarsePath, finePath}, options, {});
    ASSERT_EQ(r.snapshots.size(), 1u);
    const WeatherSnapshot& s = r.snapshots[0];
    const LatLonGrid& g = s.grid;
    EXPECT_LT(std::abs(g.dLatDeg), 0.1) << "the composite keeps the finer spacing";
    // Profile along 38° N from 115° W (coarse only) to 98° W (well inside the Lambert domain).
    const auto row = uint32_t(std::lround((38.0 - g.lat0Deg) / g.dLatDeg));
    std::vector<float> profile;
    for (uint32_t c = 0; c < g.nLon; ++c)
    {
        const double lon = wrapLongitudeDeg(g.lon0Deg + c * g.dLonDeg);
        if (lon >= -115 && lon <= -98)
            profile.push_back(s.layers[0].coverage[g.index(row, c)]);
    }
    ASSERT_GT(profile.size(), 20u);
    EXPECT_NEAR(profile.front(), 0.2f, 0.01f);
    EXPECT_NEAR(profile.back(), 0.8f, 0.01f);
    float maxStep = 0;
    for (size_t i = 1; i < profile.size(); ++i)
    {
        EXPECT_GE(profile[i], profile[i - 1] - 1e-4f) << "monotonic across the margin, cell " << i;
        maxStep = std::max(maxStep, profile[i] - profile[i - 1]);
    }
    EXPECT_LT(maxStep, 0.3f * 0.6f) << "a wall would rise by 0.6 in one cell";
    EXPECT_NE(s.provenance.at("grid").find(" over "), std::string::npos) << s.provenance.at("grid");
}

/// The section of a GRIB2 message with this number: its offset in bytes.
size_t section(const std::vector<char>& b, int number)
{
    size_t at = 16;
    while (at + 5 <= b.size())
    {
        const uint32_t length = uint32_t(uint8_t(b[at])) << 24 | uint32_t(uint8_t(b[at + 1])) << 16 |
                                uint32_t(uint8_t(b[at + 2])) << 8 | uint32_t(uint8_t(b[at + 3]));
        if (b[at + 4] == number)
            return at;
        at += length;
    }
    return 0;
}

IngestError convertError(const std::string& path)
{
    try
    {
        convertFiles({path}, MappingOptions{}, {});
    }
    catch (const IngestError& e)
    {
        return e;
    }
    ADD_FAILURE() << "no error for " << path;
    return IngestError(IngestErrorKind::Output, "", "", "", "no error");
}

TEST(BadGrid, DeclaredSizesThatDisagreeWithTheData)
{
    const std::string path = test::tempPath("lambert-bad-size.grib2");
    writeCloudDiscFixture(path, {.kind = FixtureGrid::Lambert, .latDeg = 38, .lonDeg = -98, .radiusKm = 150});
    std::vector<char> bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const size_t s3 = section(bytes, 3);
    ASSERT_GT(s3, 0u);
    bytes[s3 + 33] = char(61); // Nx (octets 31-34 of template 3.30): 61 instead of 60
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    const IngestError e = convertError(path);
    EXPECT_EQ(e.kind(), IngestErrorKind::Corrupt);
    const std::string m = e.what();
    EXPECT_NE(m.find("lambert 61 x 50"), std::string::npos) << m;
    EXPECT_NE(m.find("message 1"), std::string::npos) << m;
    EXPECT_NE(m.find("inconsistent sizes"), std::string::npos) << m;
}

TEST(BadGrid, ProjectionEcCodesCannotIterate)
{
    GribOutField f;
    f.sample = "sh_sfc_grib2";
    f.keys = {{"centre", "kwbc"}, {"typeOfLevel", "lowCloudLayer"}, {"shortName", "tcc"}};
    const std::string path = test::tempPath("spectral.grib2");
    writeGribFile(path, {f});
    const IngestError e = convertError(path);
    EXPECT_EQ(e.kind(), IngestErrorKind::UnsupportedGrid);
    const std::string m = e.what();
    EXPECT_NE(m.find("grid sh"), std::string::npos) << m;
    EXPECT_NE(m.find("message 1"), std::string::npos) << m;
    EXPECT_NE(m.find("cannot locate"), std::string::npos) << m;
}

TEST(BadGrid, DegenerateLambertCone)
{
    GribOutField f;
    f.sample = "regular_ll_sfc_grib2";
    f.keys = {{"centre", "kwbc"},
              {"typeOfLevel", "lowCloudLayer"},
              {"shortName", "tcc"},
              {"gridType", "lambert"},
              {"Nx", "10"},
              {"Ny", "8"},
              {"DxInMetres", "20000"},
              {"DyInMetres", "20000"},
              {"LaDInDegrees", "30"},
              {"Latin1InDegrees", "30"},
              {"Latin2InDegrees", "-30"}};
    const std::string path = test::tempPath("lambert-cylinder.grib2");
    writeGribFile(path, {f});
    const IngestError e = convertError(path);
    EXPECT_EQ(e.kind(), IngestErrorKind::UnsupportedGrid);
    const std::string m = e.what();
    EXPECT_NE(m.find("grid lambert"), std::string::npos) << m;
    EXPECT_NE(m.find("message 1"), std::string::npos) << m;
    EXPECT_NE(m.find("degenerate Lambert cone"), std::string::npos) << m;
}

} // namespace
} // namespace sky
