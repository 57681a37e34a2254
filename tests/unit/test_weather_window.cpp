// SPDX-License-Identifier: MIT
// Resampling a WeatherSnapshot onto the camera-centred window (skyservice/weather/weather_window.h).
#include "skyservice/weather/weather_window.h"

#include "skyservice/sky/builtin_weather.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace
{

using sky::WeatherSnapshot;
using sky::WeatherWindow;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// One clear layer on the given grid: coverage 0, base 1000 m, top 2000 m, stratus, wind 7 m/s east.
WeatherSnapshot clearSnapshot(double lat0Deg, double dLatDeg, uint32_t nLat, double lon0Deg, double dLonDeg,
                              uint32_t nLon)
{
    WeatherSnapshot s;
    s.grid.lat0Deg = lat0Deg;
    s.grid.dLatDeg = dLatDeg;
    s.grid.nLat = nLat;
    s.grid.lon0Deg = lon0Deg;
    s.grid.dLonDeg = dLonDeg;
    s.grid.nLon = nLon;
    const size_t cells = s.grid.cellCount();
    sky::CloudLayerFields layer;
    layer.name = "low";
    layer.coverage.assign(cells, 0.0f);
    layer.baseAltitudeM.assign(cells, 1000.0f);
    layer.topAltitudeM.assign(cells, 2000.0f);
    layer.type.assign(cells, uint8_t(sky::CloudType::Stratus));
    layer.windEastMS.assign(cells, 7.0f);
    layer.windNorthMS.assign(cells, 0.0f);
    s.layers.push_back(layer);
    return s;
}

// Set one cell (given by its lat/lon, which must be a grid point) to full cumulus cover.
void setCell(WeatherSnapshot& s, double latDeg, double lonDeg)
{
    const double fy = (latDeg - s.grid.lat0Deg) / s.grid.dLatDeg;
    double dl = std::fmod(lonDeg - s.grid.lon0Deg, 360.0);
    if (dl < 0)
        dl += 360.0;
    const double fx = dl / s.grid.dLonDeg;
    ASSERT_NEAR(fy, std::round(fy), 1e-9);
    ASSERT_NEAR(fx, std::round(fx), 1e-9);
    const size_t c = s.grid.index(uint32_t(std::lround(fy)), uint32_t(std::lround(fx)));
    s.layers[0].coverage[c] = 1.0f;
    s.layers[0].type[c] = uint8_t(sky::CloudType::Cumulus);
}

struct Texel
{
    uint32_t i = 0, j = 0;
    float value = -1;
};

Texel maxCoverage(const WeatherWindow& w, uint32_t slice)
{
    Texel best;
    for (uint32_t j = 0; j < w.sizeTexels; ++j)
        for (uint32_t i = 0; i < w.sizeTexels; ++i)
            if (w.at(slice, i, j).x > best.value)
                best = {i, j, w.at(slice, i, j).x};
    return best;
}

// The texel that GeographicLib's forward projection puts a point in.
void expectedTexel(const WeatherWindow& w, double latDeg, double lonDeg, uint32_t& i, uint32_t& j)
{
    double x = 0;
    double y = 0;
    GeographicLib::AzimuthalEquidistant().Forward(w.centreLatDeg, w.centreLonDeg, latDeg, lonDeg, x, y);
    i = uint32_t(std::floor(x / w.texelSizeM + 0.5 * w.sizeTexels));
    j = uint32_t(std::floor(y / w.texelSizeM + 0.5 * w.sizeTexels));
}

// Where a single full cell lands: the texel that the forward projection puts it in must hold the
// bilinear tent weight of that cell at the texel centre (computed here independently), and be the
// brightest texel or next to it (the lat/lon tent is not aligned with the texel grid near a pole).
void expectIsolatedCellAt(const WeatherSnapshot& s, double centreLatDeg, double centreLonDeg, double cellLatDeg,
                          double cellLonDeg, double halfExtentM, uint32_t size)
{
    WeatherWindow w;
    sky::resampleWeatherWindow(s, centreLatDeg, centreLonDeg, halfExtentM, w, size);
    ASSERT_EQ(w.texels.size(), size_t(WEATHER_WINDOW_SLICES) * size * size);
    uint32_t i = 0;
    uint32_t j = 0;
    expectedTexel(w, cellLatDeg, cellLonDeg, i, j);
    ASSERT_LT(i, size);
    ASSERT_LT(j, size);
    double lat = 0;
    double lon = 0;
    GeographicLib::AzimuthalEquidistant().Reverse(centreLatDeg, centreLonDeg, w.texelEastingM(i),
                                                  w.texelNorthingM(j), lat, lon);
    double dLon = std::remainder(lon - cellLonDeg, 360.0);
    const double tent = std::max(0.0, 1.0 - std::abs((lat - cellLatDeg) / s.grid.dLatDeg)) *
                        std::max(0.0, 1.0 - std::abs(dLon / s.grid.dLonDeg));
    EXPECT_GT(tent, 0.3);
    EXPECT_NEAR(w.at(0, i, j).x, tent, 1e-5) << "texel " << i << ", " << j;
    const Texel best = maxCoverage(w, 0);
    EXPECT_LE(std::abs(int(best.i) - int(i)), 1);
    EXPECT_LE(std::abs(int(best.j) - int(j)), 1);
    EXPECT_EQ(w.at(0, best.i, best.j).w, float(CLOUD_TYPE_CUMULUS));  // nearest cell
    EXPECT_FLOAT_EQ(w.at(0, i, j).y, 1000.0f);
    EXPECT_FLOAT_EQ(w.at(1, i, j).x, 7.0f);
    // Far from the cell the sky is clear.
    EXPECT_EQ(w.at(0, 0, 0).x, 0.0f);
    EXPECT_EQ(w.at(0, size - 1, size - 1).x, 0.0f);
}

TEST(WeatherWindow, IsolatedCellLandsAtProjectedTexel)
{
    WeatherSnapshot s = clearSnapshot(45.0, 0.1, 21, 7.0, 0.1, 21);
    setCell(s, 46.3, 8.0);
    expectIsolatedCellAt(s, 46.0, 8.0, 46.3, 8.0, 50000.0, 64);
    WeatherWindow w;
    sky::resampleWeatherWindow(s, 46.0, 8.0, 50000.0, w, 64);
    EXPECT_EQ(w.sizeTexels, 64u);
    EXPECT_DOUBLE_EQ(w.texelSizeM, 100000.0 / 64.0);
    EXPECT_DOUBLE_EQ(w.texelEastingM(0), -50000.0 + 0.5 * w.texelSizeM);
}

TEST(WeatherWindow, AcrossTheAntimeridianRegionalGrid)
{
    // Regional grid from 179 E to 181 E (= 179 W); the cell at 179.8 W is column 12.
    WeatherSnapshot s = clearSnapshot(-11.0, 0.1, 21, 179.0, 0.1, 21);
    setCell(s, -10.0, -179.8);
    expectIsolatedCellAt(s, -10.1, 179.9, -10.0, -179.8, 50000.0, 64);
}

TEST(WeatherWindow, AcrossTheAntimeridianGlobalGrids)
{
    // The same global 0.5-degree field in both longitude conventions.
    for (const double lon0 : {0.0, -180.0})
    {
        WeatherSnapshot s = clearSnapshot(-90.0, 0.5, 361, lon0, 0.5, 720);
        setCell(s, 20.0, -179.5);
        expectIsolatedCellAt(s, 20.0, 179.9, 20.0, -179.5, 100000.0, 64);
    }
}

TEST(WeatherWindow, NearThePole)
{
    // North-to-south global grid; the window around 89.5 N crosses the pole.
    // 5-degree columns: 0.5-degree ones are under 1 km wide at 89 N, narrower than a texel.
    WeatherSnapshot s = clearSnapshot(90.0, -0.5, 361, 0.0, 5.0, 72);
    setCell(s, 89.0, 100.0);
    expectIsolatedCellAt(s, 89.5, -30.0, 89.0, 100.0, 180000.0, 128);
    WeatherWindow w;
    sky::resampleWeatherWindow(s, 89.5, -30.0, 200000.0, w, 64);
    for (const glm::vec4& t : w.texels)
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && std::isfinite(t.w));
}

TEST(WeatherWindow, BilinearIsExactForLinearFields)
{
    WeatherSnapshot s = clearSnapshot(40.0, 0.25, 41, 0.0, 0.25, 49);
    for (uint32_t iLat = 0; iLat < s.grid.nLat; ++iLat)
        for (uint32_t iLon = 0; iLon < s.grid.nLon; ++iLon)
        {
            const double lat = s.grid.lat0Deg + iLat * s.grid.dLatDeg;
            const double lon = s.grid.lon0Deg + iLon * s.grid.dLonDeg;
            const size_t c = s.grid.index(iLat, iLon);
            s.layers[0].coverage[c] = float(0.5 + 0.04 * (lat - 45.0) - 0.03 * (lon - 6.0));
            s.layers[0].baseAltitudeM[c] = float(100.0 * lat + 30.0 * lon);
            s.layers[0].windNorthMS[c] = float(2.0 * lon - lat);
        }
    WeatherWindow w;
    sky::resampleWeatherWindow(s, 45.0, 6.0, 300000.0, w, 32);
    const GeographicLib::AzimuthalEquidistant projection;
    double worstBase = 0;
    for (uint32_t j = 0; j < w.sizeTexels; ++j)
        for (uint32_t i = 0; i < w.sizeTexels; ++i)
        {
            double lat = 0;
            double lon = 0;
            projection.Reverse(45.0, 6.0, w.texelEastingM(i), w.texelNorthingM(j), lat, lon);
            EXPECT_NEAR(w.at(0, i, j).x, 0.5 + 0.04 * (lat - 45.0) - 0.03 * (lon - 6.0), 1e-5);
            worstBase = std::max(worstBase, std::abs(double(w.at(0, i, j).y) - (100.0 * lat + 30.0 * lon)));
            EXPECT_NEAR(w.at(1, i, j).y, 2.0 * lon - lat, 1e-4);
        }
    EXPECT_LT(worstBase, 2e-3);  // float rounding of ~4700 m values
}

TEST(WeatherWindow, NaNMeansClearAndIsLeftOutOfOtherFields)
{
    WeatherSnapshot s = clearSnapshot(45.0, 0.1, 21, 7.0, 0.1, 21);
    auto& layer = s.layers[0];
    std::fill(layer.coverage.begin(), layer.coverage.end(), 0.8f);
    const size_t hole = s.grid.index(10, 10);  // 46.0 N, 8.0 E, the window centre
    layer.coverage[hole] = kNaN;
    const size_t unknownBase = s.grid.index(5, 5);  // 45.5 N, 7.5 E
    layer.baseAltitudeM[unknownBase] = kNaN;
    layer.windEastMS[s.grid.index(10, 11)] = kNaN;
    layer.precipitationMmH.clear();  // missing vector: defaults to 0
    s.tropopauseAltitudeM.assign(s.grid.cellCount(), kNaN);
    s.capeJKg.assign(s.grid.cellCount(), 500.0f);

    WeatherWindow w;
    // An odd size puts texel (32, 32) exactly on the window centre, which is the NaN cell.
    sky::resampleWeatherWindow(s, 46.0, 8.0, 81250.0, w, 65);
    for (const glm::vec4& t : w.texels)
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && std::isfinite(t.w));
    EXPECT_LT(w.at(0, 32, 32).x, 1e-6f);
    EXPECT_LT(w.at(0, 31, 31).x, 0.5f);
    uint32_t i = 0;
    uint32_t j = 0;
    expectedTexel(w, 45.5, 7.5, i, j);
    ASSERT_LT(i, w.sizeTexels);
    ASSERT_LT(j, w.sizeTexels);
    EXPECT_LT(w.at(0, i, j).x, 0.3f);   // unknown base: the corner counts as clear
    EXPECT_FLOAT_EQ(w.at(0, i, j).y, 1000.0f);  // ...and the base comes from the other corners
    EXPECT_NEAR(w.at(0, 5, 5).x, 0.8f, 1e-6);   // far from both holes
    for (uint32_t jj = 0; jj < w.sizeTexels; ++jj)
        for (uint32_t ii = 0; ii < w.sizeTexels; ++ii)
        {
            ASSERT_FLOAT_EQ(w.at(1, ii, jj).x, 7.0f);  // the NaN wind corner is left out
            ASSERT_EQ(w.at(1, ii, jj).z, 0.0f);
            ASSERT_FLOAT_EQ(w.at(1, ii, jj).w, 500.0f);
            ASSERT_EQ(w.at(WEATHER_WINDOW_HIGH_SLICE + 1, ii, jj).z, sky::kDefaultTropopauseAltitudeM);
        }
}

TEST(WeatherWindow, MissingLayersAndOutsideTheGridAreClear)
{
    WeatherSnapshot s = clearSnapshot(45.0, 0.1, 21, 7.0, 0.1, 21);  // 45..47 N, 7..9 E
    std::fill(s.layers[0].coverage.begin(), s.layers[0].coverage.end(), 1.0f);
    s.capeJKg.assign(s.grid.cellCount(), 1200.0f);
    WeatherWindow w;
    // 46 N, 9.5 E: the grid's east edge is 39 km to the west; the window reaches 100 km.
    sky::resampleWeatherWindow(s, 46.0, 9.5, 100000.0, w, 32);
    EXPECT_EQ(w.at(0, 0, 16).x, 1.0f);                  // inside, west
    EXPECT_EQ(w.at(0, 31, 16).x, 0.0f);                 // outside, east
    EXPECT_FLOAT_EQ(w.at(0, 31, 16).y, 1000.0f);        // edge value kept for filtering
    EXPECT_FLOAT_EQ(w.at(0, 31, 16).z, 2000.0f);
    for (uint32_t k = 1; k < MAX_CLOUD_LAYERS; ++k)
        for (uint32_t j = 0; j < w.sizeTexels; ++j)
            for (uint32_t i = 0; i < w.sizeTexels; ++i)
            {
                ASSERT_EQ(w.at(2 * k, i, j).x, 0.0f);
                ASSERT_EQ(w.at(WEATHER_WINDOW_HIGH_SLICE, i, j).x, 0.0f);  // no high cloud given
            }
    EXPECT_FLOAT_EQ(w.at(3, 0, 16).w, 1200.0f);  // CAPE repeated for every layer slot

    // A layer whose top is missing cannot be drawn: clear.
    s.layers[0].topAltitudeM.clear();
    sky::resampleWeatherWindow(s, 46.0, 8.0, 100000.0, w, 16);
    for (uint32_t j = 0; j < w.sizeTexels; ++j)
        for (uint32_t i = 0; i < w.sizeTexels; ++i)
            ASSERT_EQ(w.at(0, i, j).x, 0.0f);
}

// Not a timing test (tests never assert on time): checks the full-size window of the built-in
// weather around the cumulonimbus and prints how long the resampling took.
TEST(WeatherWindow, FullSizeWindowOfBuiltinWeather)
{
    const WeatherSnapshot s = sky::makeBuiltinWeather(0);
    WeatherWindow w;
    const auto start = std::chrono::steady_clock::now();
    sky::resampleWeatherWindow(s, sky::kBuiltinCumulonimbusLatDeg, sky::kBuiltinCumulonimbusLonDeg, 800000.0, w);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("resampleWeatherWindow %u^2 texels: %.1f ms\n", w.sizeTexels, ms);
    ASSERT_EQ(w.sizeTexels, uint32_t(WEATHER_WINDOW_SIZE));
    const uint32_t centre = WEATHER_WINDOW_SIZE / 2;
    // The 6.25 km texels around the centre straddle the 3.5 km core: mostly covered.
    EXPECT_GT(w.at(4, centre, centre).x, 0.5f);
    EXPECT_EQ(w.at(4, centre, centre).w, float(CLOUD_TYPE_CUMULONIMBUS));
    EXPECT_FLOAT_EQ(w.at(4, centre, centre).z, sky::kBuiltinCumulonimbusTopM);
    EXPECT_EQ(w.at(4, 0, 0).x, 0.0f);
    EXPECT_GT(w.at(5, centre, centre).w, 2000.0f);  // CAPE
}

}  // namespace

// A snapshot with no grid at all (what the renderer draws when it was given no weather) resamples to a
// clear window, reading no field (it once read cells of the empty vectors).
TEST(WeatherWindow, AnEmptySnapshotGivesAClearWindow)
{
    WeatherWindow w;
    sky::resampleWeatherWindow(WeatherSnapshot{}, 46.0, 8.0, 50000.0, w, 16);
    ASSERT_EQ(w.texels.size(), size_t(WEATHER_WINDOW_SLICES) * 16 * 16);
    for (uint32_t j = 0; j < 16; ++j)
        for (uint32_t i = 0; i < 16; ++i)
            EXPECT_EQ(w.at(0, j, i).x, 0.0f) << i << " " << j;  // layer 0 coverage
}
