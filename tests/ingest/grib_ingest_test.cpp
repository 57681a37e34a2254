// SPDX-License-Identifier: MIT
// GRIB decoding and the GFS/ECMWF mapping on fixtures written at test time, plus the real GFS sample.
#include "weather_ingest/grib_fields.h"
#include "weather_ingest/ingest.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/pressure_altitude.h"

#include "grib_fixtures.h"
#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace sky
{
namespace
{

ConvertResult convertOne(const std::string& path, bool lenient = false)
{
    MappingOptions o;
    o.lenient = lenient;
    return convertFiles({path}, o, {});
}

// log-pressure interpolation between gh(1000 hPa) = 100 m and gh(500 hPa) = 5500 m.
double expectedHeightM(double pPa) { return 100.0 + 5400.0 * std::log(100000.0 / pPa) / std::log(2.0); }

TEST(GribIngest, GfsLikeFieldsMapToLayersWithAltitudesWindsAndTypes)
{
    const std::string path = test::tempPath("gfs.grib2");
    writeGribFile(path, test::gfsLikeFields(test::smallGlobalGrid()));
    const ConvertResult r = convertOne(path);
    ASSERT_EQ(r.snapshots.size(), 1u);
    const WeatherSnapshot& s = r.snapshots[0];
    EXPECT_EQ(s.validTimeUnixS, 1294660800);  // 2011-01-10T12:00:00Z
    EXPECT_EQ(s.grid.nLat, 19u);
    EXPECT_DOUBLE_EQ(s.grid.dLatDeg, -10.0);
    ASSERT_EQ(s.layers.size(), 3u);
    EXPECT_EQ(s.layers[0].name, "low");
    EXPECT_EQ(s.layers[2].name, "convective");
    const size_t c = 40;
    EXPECT_NEAR(s.layers[0].coverage[c], 0.60f, 1e-3f);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[c], expectedHeightM(90000), 1.0);
    EXPECT_NEAR(s.layers[0].topAltitudeM[c], expectedHeightM(80000), 1.0);
    // Wind at the mid-layer pressure sqrt(900 * 800) hPa, between the 1000 and 500 hPa winds in ln p.
    const double midPa = std::sqrt(90000.0 * 80000.0);
    EXPECT_NEAR(s.layers[0].windEastMS[c], 10.0 + 10.0 * std::log(100000.0 / midPa) / std::log(2.0), 0.05);
    EXPECT_NEAR(s.layers[0].windNorthMS[c], -5.0f, 0.05f);
    EXPECT_EQ(s.layers[2].type[c], uint8_t(CloudType::Cumulonimbus));  // 2 mm/h convective, 9 km deep
    EXPECT_NEAR(s.layers[2].precipitationMmH[c], 2.0f, 0.01f);
    // 1 mm/h large-scale rain goes to the low layer (more cover than the middle one).
    EXPECT_NEAR(s.layers[0].precipitationMmH[c], 1.0f, 0.01f);
    EXPECT_EQ(s.layers[1].type[c], uint8_t(CloudType::Altocumulus));
    ASSERT_EQ(s.high.coverage.size(), s.grid.cellCount());
    EXPECT_NEAR(s.high.coverage[c], 0.5f, 1e-3f);
    EXPECT_EQ(s.high.type[c], uint8_t(CloudType::Cirrus));
    const double highMidPa = std::sqrt(30000.0 * 20000.0);  // between the 500 and 200 hPa winds
    EXPECT_NEAR(s.high.windEastMS[c], 20.0 + 10.0 * std::log(50000.0 / highMidPa) / std::log(2.5), 0.05);
    EXPECT_NEAR(s.capeJKg[c], 1500.0f, 1.0f);
    EXPECT_FALSE(s.provenance.at("layers/0/coverage").empty());
    EXPECT_NE(s.provenance.at("altitudes").find("geopotential"), std::string::npos);
}

TEST(GribIngest, WithoutGeopotentialTheStandardAtmosphereIsUsed)
{
    const std::string path = test::tempPath("nogh.grib2");
    const LatLonGrid g = test::smallGlobalGrid();
    writeGribFile(path, {test::layerField(g, "tcc", "lowCloudLayer", 50), test::layerField(g, "pres", "lowCloudBottom", 85000),
                         test::layerField(g, "pres", "lowCloudTop", 70000)});
    const WeatherSnapshot s = convertOne(path).snapshots.at(0);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[0], standardAtmosphereAltitudeM(85000), 0.5);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[0], 1457.0f, 2.0f);  // ICAO table: 850 hPa = 1457 m
    EXPECT_NE(s.provenance.at("altitudes").find("ICAO"), std::string::npos);
}

TEST(GribIngest, AnyScanningModeAndLongitudeConventionDecodesTheSame)
{
    // value = latitude * 1000 + longitude (0..360), written with each scanning mode.
    for (const bool iNeg : {false, true})
        for (const bool jPos : {false, true})
            for (const double lon0 : {0.0, -180.0})
            {
                LatLonGrid g = test::smallGlobalGrid();
                g.lon0Deg = lon0;
                GribOutField f = test::layerField(g, "tcc", "lowCloudLayer", 0);
                for (uint32_t r = 0; r < g.nLat; ++r)
                    for (uint32_t c = 0; c < g.nLon; ++c)
                    {
                        const double lat = g.lat0Deg + r * g.dLatDeg;
                        const double lon = std::fmod(lon0 + c * g.dLonDeg + 360.0, 360.0);
                        f.values[g.index(r, c)] = lat * 1000 + lon;
                    }
                f.iScansNegatively = iNeg;
                f.jScansPositively = jPos;
                f.bitsPerValue = 24;
                const std::string path = test::tempPath("scan.grib2");
                writeGribFile(path, {f});
                GribFile file(path);
                GribMessage m;
                ASSERT_TRUE(file.next(m));
                const GridField d = m.decode(1000000);
                for (const auto& [lat, lon] : {std::pair{80.0, 40.0}, std::pair{-30.0, 300.0}, std::pair{0.0, 180.0}})
                    EXPECT_NEAR(d.grid.sample(d.values, lat, lon), lat * 1000 + lon, 0.5)
                        << "iNeg " << iNeg << " jPos " << jPos << " lon0 " << lon0 << " at " << lat << "," << lon;
            }
}

TEST(GribIngest, BitmapHolesAreUnknownAndGetDefaultsOnlyWhereCloudy)
{
    const LatLonGrid g = test::smallGlobalGrid();
    std::vector<GribOutField> f = {test::layerField(g, "tcc", "lowCloudLayer", 0),
                                   test::layerField(g, "pres", "lowCloudBottom", 90000),
                                   test::layerField(g, "pres", "lowCloudTop", 80000)};
    f[0].values[1] = 70;        // cloudy, base/top missing -> default 950..800 hPa
    f[1].values[1] = NAN;
    f[2].values[1] = NAN;
    f[1].values[2] = NAN;       // clear and missing -> NaN
    f[2].values[2] = NAN;
    const std::string path = test::tempPath("bitmap.grib2");
    writeGribFile(path, f);
    const WeatherSnapshot s = convertOne(path).snapshots.at(0);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[1], standardAtmosphereAltitudeM(95000), 1.0);
    EXPECT_TRUE(std::isnan(s.layers[0].baseAltitudeM[2]));
    EXPECT_EQ(s.layers[0].type[2], uint8_t(CloudType::None));
    EXPECT_EQ(s.layers[0].type[1], uint8_t(CloudType::Stratocumulus));
}

TEST(GribIngest, EcmwfGrib1NamesAndAccumulationsAreMapped)
{
    LatLonGrid g = test::smallGlobalGrid();
    const auto ec = [&](const char* shortName, double value, bool accumulated = false) {
        GribOutField f;
        f.sample = "regular_ll_sfc_grib1";
        f.keys = {{"centre", "ecmf"}, {"dataDate", "20240301"}, {"dataTime", "0"}, {"shortName", shortName}};
        if (accumulated)
            f.keys.insert(f.keys.end(), {{"stepType", "accum"}, {"startStep", "0"}, {"endStep", "6"}});
        else
            f.keys.insert(f.keys.end(), {{"stepType", "instant"}, {"step", "6"}});
        f.grid = g;
        f.values.assign(g.cellCount(), value);
        return f;
    };
    const std::string path = test::tempPath("ecmwf.grib1");
    writeGribFile(path, {ec("lcc", 0.9), ec("mcc", 0.2), ec("hcc", 0.8), ec("cbh", 400), ec("z", 9806.65), ec("cape", 50),
                         ec("tp", 0.006, true), ec("cp", 0.003, true)});
    const WeatherSnapshot s = convertOne(path).snapshots.at(0);
    EXPECT_EQ(s.validTimeUnixS, 1709272800);  // 2024-03-01T06:00:00Z
    EXPECT_NEAR(s.layers[0].coverage[3], 0.9f, 1e-3f);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[3], 1400.0f, 1.0f);  // 400 m above 1000 m ground
    EXPECT_NEAR(s.high.coverage[3], 0.8f, 1e-3f);
    EXPECT_EQ(s.high.type[3], uint8_t(CloudType::Cirrostratus));
    // 3 mm in 6 h convective (-> low layer, no convective layer), 3 mm large-scale.
    EXPECT_NEAR(s.layers[0].precipitationMmH[3], 1.0f, 0.01f);
    EXPECT_NE(s.provenance.at("layers/0/coverage").find("lcc"), std::string::npos);
}

TEST(GribIngest, RealGfsSampleGivesPlausibleLayers)
{
    const std::string path = std::string(SKY_SHARED_DIR) + "/weather/gfs-2p5deg-20110110-12z-f120.grib2";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared GFS sample not found at " << path;
    const WeatherSnapshot s = convertOne(path).snapshots.at(0);
    EXPECT_EQ(s.grid.nLon, 144u);
    EXPECT_EQ(s.grid.nLat, 73u);
    EXPECT_EQ(s.validTimeUnixS, 1295092800);  // 2011-01-15T12:00:00Z (+120 h)
    size_t cloudy = 0;
    for (size_t li = 0; li < 3; ++li)
        for (size_t i = 0; i < s.grid.cellCount(); ++i)
        {
            const CloudLayerFields& l = s.layers[li];
            if (!(l.coverage[i] >= 0.01f))
                continue;
            ++cloudy;
            ASSERT_TRUE(std::isfinite(l.baseAltitudeM[i]) && std::isfinite(l.topAltitudeM[i])) << li << " " << i;
            EXPECT_LE(l.baseAltitudeM[i], l.topAltitudeM[i]);
            EXPECT_GT(l.baseAltitudeM[i], -500.0f);
            EXPECT_LT(l.topAltitudeM[i], li == 2 ? 20000.0f : 12000.0f);
            EXPECT_NE(l.type[i], 0);
        }
    EXPECT_GT(cloudy, 3000u);
    for (size_t i = 0; i < s.grid.cellCount(); ++i)
        if (s.high.coverage[i] >= 0.01f)
        {
            EXPECT_GT(s.high.altitudeM[i], 4000.0f);
            EXPECT_LT(s.high.altitudeM[i], 20000.0f);  // tropical high cloud tops reach 70 hPa in GFS
        }
    EXPECT_FALSE(s.tropopauseAltitudeM.empty());
}

}  // namespace
}  // namespace sky
