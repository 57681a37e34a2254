// SPDX-License-Identifier: MIT
// The built-in weather scene (skyservice/sky/builtin_weather.h): what the header documents holds.
#include "skyservice/sky/builtin_weather.h"

#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{

using sky::WeatherSnapshot;

class BuiltinWeather : public ::testing::Test
{
protected:
    static void SetUpTestSuite() { snapshot = new WeatherSnapshot(sky::makeBuiltinWeather(1700000000)); }
    static void TearDownTestSuite()
    {
        delete snapshot;
        snapshot = nullptr;
    }

    static size_t cellAt(double latDeg, double lonDeg)
    {
        const auto& g = snapshot->grid;
        const double fy = (latDeg - g.lat0Deg) / g.dLatDeg;
        const double fx = (lonDeg - g.lon0Deg) / g.dLonDeg;
        EXPECT_NEAR(fy, std::round(fy), 1e-6) << "not a grid latitude: " << latDeg;
        EXPECT_NEAR(fx, std::round(fx), 1e-6) << "not a grid longitude: " << lonDeg;
        return g.index(uint32_t(std::lround(fy)), uint32_t(std::lround(fx)));
    }
    static double latOf(uint32_t iLat) { return snapshot->grid.lat0Deg + iLat * snapshot->grid.dLatDeg; }
    static double lonOf(uint32_t iLon) { return snapshot->grid.lon0Deg + iLon * snapshot->grid.dLonDeg; }

    static WeatherSnapshot* snapshot;
};

WeatherSnapshot* BuiltinWeather::snapshot = nullptr;

struct Box
{
    double lonMin, lonMax, latMin, latMax;
    bool contains(double lat, double lon, double marginDeg) const
    {
        return lon >= lonMin - marginDeg && lon <= lonMax + marginDeg && lat >= latMin - marginDeg &&
               lat <= latMax + marginDeg;
    }
};

const Box kDeckBox = {0.5, 4.5, 43.0, 48.0};
const Box kCumulusBox = {6.0, 11.0, 43.0, 47.0};
const Box kAltocumulusBox = {1.0, 5.0, 47.0, 49.5};
const Box kCirrusBox = {3.0, 10.0, 44.0, 49.0};
// Edges move by up to 25 km and ramp over 25 km: 0.75 degrees is over 53 km even in longitude at 50 N.
constexpr double kOutsideMarginDeg = 0.75;

TEST_F(BuiltinWeather, GridAndMetadata)
{
    const auto& g = snapshot->grid;
    EXPECT_DOUBLE_EQ(g.lat0Deg, 40.0);
    EXPECT_DOUBLE_EQ(g.lon0Deg, 0.0);
    EXPECT_GE(g.dLatDeg, 0.02);
    EXPECT_LE(g.dLatDeg, 0.05);
    EXPECT_NEAR(g.lat0Deg + (g.nLat - 1) * g.dLatDeg, 50.0, 1e-9);
    EXPECT_NEAR(g.lon0Deg + (g.nLon - 1) * g.dLonDeg, 12.0, 1e-9);
    EXPECT_EQ(snapshot->validTimeUnixS, 1700000000);
    EXPECT_EQ(snapshot->provenance.at("source"), "builtin");
    ASSERT_EQ(snapshot->layers.size(), 3u);
    EXPECT_EQ(snapshot->layers[0].name, "low");
    EXPECT_EQ(snapshot->layers[1].name, "middle");
    EXPECT_EQ(snapshot->layers[2].name, "convective");
    const size_t cells = g.cellCount();
    for (const auto& layer : snapshot->layers)
    {
        EXPECT_EQ(layer.coverage.size(), cells);
        EXPECT_EQ(layer.baseAltitudeM.size(), cells);
        EXPECT_EQ(layer.topAltitudeM.size(), cells);
        EXPECT_EQ(layer.type.size(), cells);
        EXPECT_EQ(layer.precipitationMmH.size(), cells);
        EXPECT_EQ(layer.windEastMS.size(), cells);
        EXPECT_EQ(layer.windNorthMS.size(), cells);
    }
    EXPECT_EQ(snapshot->high.coverage.size(), cells);
    EXPECT_EQ(snapshot->capeJKg.size(), cells);
    EXPECT_EQ(snapshot->tropopauseAltitudeM.size(), cells);
}

TEST_F(BuiltinWeather, NamedPlacesHaveTheDocumentedCloud)
{
    const auto& low = snapshot->layers[0];
    const auto& middle = snapshot->layers[1];
    const auto& convective = snapshot->layers[2];
    const auto& high = snapshot->high;

    size_t c = cellAt(sky::kBuiltinDeckLatDeg, sky::kBuiltinDeckLonDeg);
    EXPECT_GE(low.coverage[c], 0.85f);
    EXPECT_LE(low.coverage[c], 0.95f);
    EXPECT_EQ(low.type[c], uint8_t(sky::CloudType::Stratocumulus));
    EXPECT_EQ(low.baseAltitudeM[c], 900.0f);
    EXPECT_EQ(low.topAltitudeM[c], 1700.0f);

    c = cellAt(sky::kBuiltinCumulusLatDeg, sky::kBuiltinCumulusLonDeg);
    EXPECT_GE(low.coverage[c], 0.35f);
    EXPECT_LE(low.coverage[c], 0.45f);
    EXPECT_EQ(low.type[c], uint8_t(sky::CloudType::Cumulus));
    EXPECT_EQ(low.baseAltitudeM[c], 1200.0f);
    EXPECT_EQ(low.topAltitudeM[c], 3200.0f);
    EXPECT_EQ(convective.coverage[c], 0.0f);

    c = cellAt(sky::kBuiltinAltocumulusLatDeg, sky::kBuiltinAltocumulusLonDeg);
    EXPECT_GE(middle.coverage[c], 0.45f);
    EXPECT_LE(middle.coverage[c], 0.55f);
    EXPECT_EQ(middle.type[c], uint8_t(sky::CloudType::Altocumulus));
    EXPECT_EQ(middle.baseAltitudeM[c], 4500.0f);
    EXPECT_EQ(middle.topAltitudeM[c], 5200.0f);

    c = cellAt(sky::kBuiltinCirrusLatDeg, sky::kBuiltinCirrusLonDeg);
    EXPECT_GE(high.coverage[c], 0.4f);
    EXPECT_LE(high.coverage[c], 0.6f);
    EXPECT_EQ(high.type[c], uint8_t(sky::CloudType::Cirrus));
    EXPECT_EQ(high.altitudeM[c], 9500.0f);

    c = cellAt(sky::kBuiltinCumulonimbusLatDeg, sky::kBuiltinCumulonimbusLonDeg);
    EXPECT_EQ(convective.coverage[c], 1.0f);
    EXPECT_EQ(convective.type[c], uint8_t(sky::CloudType::Cumulonimbus));
    EXPECT_EQ(convective.baseAltitudeM[c], 1000.0f);
    EXPECT_EQ(convective.topAltitudeM[c], 11500.0f);
    EXPECT_EQ(convective.precipitationMmH[c], 25.0f);
    EXPECT_EQ(snapshot->capeJKg[c], 2500.0f);

    c = cellAt(sky::kBuiltinClearLatDeg, sky::kBuiltinClearLonDeg);
    EXPECT_EQ(low.coverage[c], 0.0f);
    EXPECT_EQ(middle.coverage[c], 0.0f);
    EXPECT_EQ(convective.coverage[c], 0.0f);
    EXPECT_EQ(high.coverage[c], 0.0f);
    EXPECT_EQ(snapshot->capeJKg[c], 300.0f);
    EXPECT_EQ(snapshot->tropopauseAltitudeM[c], 11500.0f);
}

TEST_F(BuiltinWeather, ClearOutsideTheRegionsAndDocumentedInside)
{
    const auto& g = snapshot->grid;
    const auto& low = snapshot->layers[0];
    const auto& middle = snapshot->layers[1];
    const auto& high = snapshot->high;
    size_t checkedInside = 0;
    for (uint32_t iLat = 0; iLat < g.nLat; ++iLat)
        for (uint32_t iLon = 0; iLon < g.nLon; ++iLon)
        {
            const double lat = latOf(iLat);
            const double lon = lonOf(iLon);
            const size_t c = g.index(iLat, iLon);
            if (!kDeckBox.contains(lat, lon, kOutsideMarginDeg) && !kCumulusBox.contains(lat, lon, kOutsideMarginDeg))
            {
                ASSERT_EQ(low.coverage[c], 0.0f) << lat << ", " << lon;
            }
            if (!kAltocumulusBox.contains(lat, lon, kOutsideMarginDeg))
            {
                ASSERT_EQ(middle.coverage[c], 0.0f) << lat << ", " << lon;
            }
            if (!kCirrusBox.contains(lat, lon, kOutsideMarginDeg))
            {
                ASSERT_EQ(high.coverage[c], 0.0f) << lat << ", " << lon;
            }
            // Deeper inside than edge ramp plus displacement: the documented coverage range.
            if (kDeckBox.contains(lat, lon, -kOutsideMarginDeg))
            {
                ASSERT_GE(low.coverage[c], 0.85f);
                ASSERT_LE(low.coverage[c], 0.95f);
                ++checkedInside;
            }
            if (kCumulusBox.contains(lat, lon, -kOutsideMarginDeg))
            {
                ASSERT_GE(low.coverage[c], 0.35f);
                ASSERT_LE(low.coverage[c], 0.45f);
            }
            if (kAltocumulusBox.contains(lat, lon, -kOutsideMarginDeg))
            {
                ASSERT_GE(middle.coverage[c], 0.45f);
                ASSERT_LE(middle.coverage[c], 0.55f);
            }
            if (kCirrusBox.contains(lat, lon, -kOutsideMarginDeg))
            {
                ASSERT_GE(high.coverage[c], 0.4f);
                ASSERT_LE(high.coverage[c], 0.6f);
            }
        }
    EXPECT_GT(checkedInside, 10000u);
}

TEST_F(BuiltinWeather, CumulonimbusIsARoundCellWithSmoothEdge)
{
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    const auto& g = snapshot->grid;
    const auto& cb = snapshot->layers[2];
    size_t covered = 0;
    for (uint32_t iLat = 0; iLat < g.nLat; ++iLat)
        for (uint32_t iLon = 0; iLon < g.nLon; ++iLon)
        {
            const size_t c = g.index(iLat, iLon);
            double distanceM = 0;
            geodesic.Inverse(sky::kBuiltinCumulonimbusLatDeg, sky::kBuiltinCumulonimbusLonDeg, latOf(iLat),
                             lonOf(iLon), distanceM);
            if (distanceM <= sky::kBuiltinCumulonimbusCoreRadiusM - 10.0)
            {
                ASSERT_EQ(cb.coverage[c], 1.0f) << distanceM;
            }
            else if (distanceM >= sky::kBuiltinCumulonimbusRadiusM + 10.0)
            {
                ASSERT_EQ(cb.coverage[c], 0.0f) << distanceM;
            }
            else
            {
                // smoothstep: 0.5 at the middle radius, within rounding of the distance formula
                const double t = (distanceM - sky::kBuiltinCumulonimbusCoreRadiusM) /
                                 (sky::kBuiltinCumulonimbusRadiusM - sky::kBuiltinCumulonimbusCoreRadiusM);
                ASSERT_NEAR(cb.coverage[c], 1.0 - t * t * (3.0 - 2.0 * t), 0.01) << distanceM;
            }
            ASSERT_NEAR(cb.precipitationMmH[c], 25.0f * cb.coverage[c], 1e-5f);
            covered += cb.coverage[c] > 0.0f ? 1 : 0;
            if (distanceM > 60000.0)
            {
                ASSERT_EQ(snapshot->capeJKg[c], 300.0f);
            }
        }
    // About pi * 7.5^2 km^2 in cells of 2.78 x 1.97 km.
    EXPECT_GT(covered, 20u);
    EXPECT_LT(covered, 60u);
}

TEST_F(BuiltinWeather, FieldsInRangeAndWindsAsDocumented)
{
    const size_t cells = snapshot->grid.cellCount();
    auto expectWind = [&](const std::vector<float>& east, const std::vector<float>& north, double speed,
                          double fromDeg) {
        const double fromRad = fromDeg * M_PI / 180.0;
        for (size_t c = 0; c < cells; c += 997)
        {
            ASSERT_NEAR(east[c], -speed * std::sin(fromRad), 1e-4);
            ASSERT_NEAR(north[c], -speed * std::cos(fromRad), 1e-4);
        }
    };
    const auto& layers = snapshot->layers;
    expectWind(layers[0].windEastMS, layers[0].windNorthMS, 6.0, 225.0);
    expectWind(layers[2].windEastMS, layers[2].windNorthMS, 25.0, 270.0);
    expectWind(snapshot->high.windEastMS, snapshot->high.windNorthMS, 30.0, 247.5);
    EXPECT_GT(layers[2].windEastMS[0], 24.9f);  // from the west: blows east, anvil pushed east

    for (const auto& layer : layers)
        for (size_t c = 0; c < cells; ++c)
        {
            ASSERT_GE(layer.coverage[c], 0.0f);
            ASSERT_LE(layer.coverage[c], 1.0f);
            ASSERT_GT(layer.baseAltitudeM[c], 0.0f);
            ASSERT_LT(layer.baseAltitudeM[c], layer.topAltitudeM[c]);
            ASSERT_LE(layer.topAltitudeM[c], snapshot->tropopauseAltitudeM[c]);
            ASSERT_GE(layer.type[c], 1);
            ASSERT_LE(layer.type[c], 10);
            ASSERT_GE(layer.precipitationMmH[c], 0.0f);
            ASSERT_LE(layer.precipitationMmH[c], 25.0f);
        }
    for (size_t c = 0; c < cells; ++c)
    {
        ASSERT_GE(snapshot->high.coverage[c], 0.0f);
        ASSERT_LE(snapshot->high.coverage[c], 0.6f);
        ASSERT_GE(snapshot->capeJKg[c], 300.0f);
        ASSERT_LE(snapshot->capeJKg[c], 2500.0f);
        ASSERT_EQ(snapshot->tropopauseAltitudeM[c], 11500.0f);
    }
}

// The regions must not be flat rectangles: the edges are soft (intermediate values, no jumps between
// neighbouring cells) and wander (where the deck starts differs from row to row).
TEST_F(BuiltinWeather, EdgesAreSoftAndIrregular)
{
    const auto& g = snapshot->grid;
    const auto& low = snapshot->layers[0];
    float worstStep = 0;
    size_t intermediate = 0;
    double firstCloudyLonMin = 1e9;
    double firstCloudyLonMax = -1e9;
    for (uint32_t iLat = 0; iLat < g.nLat; ++iLat)
    {
        bool found = false;
        for (uint32_t iLon = 0; iLon + 1 < g.nLon; ++iLon)
        {
            const float a = low.coverage[g.index(iLat, iLon)];
            const float b = low.coverage[g.index(iLat, iLon + 1)];
            worstStep = std::max(worstStep, std::abs(a - b));
            if (iLat + 1 < g.nLat)
                worstStep = std::max(worstStep, std::abs(a - low.coverage[g.index(iLat + 1, iLon)]));
            intermediate += (a > 0.1f && a < 0.8f && lonOf(iLon) < 5.25) ? 1 : 0;
            const double lat = latOf(iLat);
            if (!found && lat > 44.0 && lat < 47.0 && a > 0.45f)
            {
                found = true;
                firstCloudyLonMin = std::min(firstCloudyLonMin, lonOf(iLon));
                firstCloudyLonMax = std::max(firstCloudyLonMax, lonOf(iLon));
            }
        }
    }
    EXPECT_LT(worstStep, 0.25f);
    EXPECT_GT(intermediate, 500u);
    EXPECT_GT(firstCloudyLonMax - firstCloudyLonMin, 0.1);
}

TEST(BuiltinWeatherDeterminism, SameInputSameSnapshot)
{
    const WeatherSnapshot a = sky::makeBuiltinWeather(42);
    const WeatherSnapshot b = sky::makeBuiltinWeather(42);
    ASSERT_EQ(a.layers.size(), b.layers.size());
    for (size_t k = 0; k < a.layers.size(); ++k)
    {
        EXPECT_EQ(a.layers[k].coverage, b.layers[k].coverage);
        EXPECT_EQ(a.layers[k].baseAltitudeM, b.layers[k].baseAltitudeM);
        EXPECT_EQ(a.layers[k].type, b.layers[k].type);
        EXPECT_EQ(a.layers[k].precipitationMmH, b.layers[k].precipitationMmH);
    }
    EXPECT_EQ(a.high.coverage, b.high.coverage);
    EXPECT_EQ(a.capeJKg, b.capeJKg);
    // The fields do not depend on the valid time.
    const WeatherSnapshot later = sky::makeBuiltinWeather(42 + 86400);
    EXPECT_EQ(later.validTimeUnixS, 42 + 86400);
    EXPECT_EQ(a.layers[0].coverage, later.layers[0].coverage);
}

}  // namespace
