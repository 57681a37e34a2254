// SPDX-License-Identifier: MIT
// WRF NetCDF: a synthetic rotated (Lambert-like) file made at test time, and the real Katrina file with
// the timeline over its four times. Also the small pure pieces: rules, ICAO atmosphere, resampler.
#include "weather_ingest/cloud_type_rules.h"
#include "weather_ingest/curvilinear_resampler.h"
#include "weather_ingest/ingest.h"
#include "weather_ingest/pressure_altitude.h"
#include "weather_ingest/weather_timeline.h"
#include "weather_ingest/wrf_mapping.h"

#include "snapshot_test_util.h"

#include <gtest/gtest.h>

#include <netcdf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>

namespace sky
{
namespace
{

/// A rotated 8 x 10 domain (20° rotation), 4 levels 0/1/2/3/4 km, cloud water in level 1 (1-2 km)
/// everywhere and a 12 km deep column of cloud at (j, i) = (4, 5); two times 3 h apart, NetCDF-3 classic.
std::string writeSyntheticWrf(const std::string& path)
{
    const size_t nt = 2, nz = 4, ny = 8, nx = 10;
    int id = 0;
    EXPECT_EQ(nc_create(path.c_str(), NC_CLOBBER, &id), NC_NOERR);
    int dT, dS, dZ, dZs, dY, dX, dXs, dYs;
    nc_def_dim(id, "Time", nt, &dT);
    nc_def_dim(id, "DateStrLen", 19, &dS);
    nc_def_dim(id, "bottom_top", nz, &dZ);
    nc_def_dim(id, "bottom_top_stag", nz + 1, &dZs);
    nc_def_dim(id, "south_north", ny, &dY);
    nc_def_dim(id, "west_east", nx, &dX);
    nc_def_dim(id, "west_east_stag", nx + 1, &dXs);
    nc_def_dim(id, "south_north_stag", ny + 1, &dYs);
    int vTimes, vLat, vLon, vPh, vPhb, vQc, vU, vV, vRc, vRnc;
    const int dimsTimes[] = {dT, dS}, dims2[] = {dT, dY, dX}, dims3[] = {dT, dZ, dY, dX}, dims3s[] = {dT, dZs, dY, dX};
    const int dimsU[] = {dT, dZ, dY, dXs}, dimsV[] = {dT, dZ, dYs, dX};
    nc_def_var(id, "Times", NC_CHAR, 2, dimsTimes, &vTimes);
    nc_def_var(id, "XLAT", NC_FLOAT, 3, dims2, &vLat);
    nc_def_var(id, "XLONG", NC_FLOAT, 3, dims2, &vLon);
    nc_def_var(id, "PH", NC_FLOAT, 4, dims3s, &vPh);
    nc_def_var(id, "PHB", NC_FLOAT, 4, dims3s, &vPhb);
    nc_def_var(id, "QCLOUD", NC_FLOAT, 4, dims3, &vQc);
    nc_def_var(id, "U", NC_FLOAT, 4, dimsU, &vU);
    nc_def_var(id, "V", NC_FLOAT, 4, dimsV, &vV);
    nc_def_var(id, "RAINC", NC_FLOAT, 3, dims2, &vRc);
    nc_def_var(id, "RAINNC", NC_FLOAT, 3, dims2, &vRnc);
    EXPECT_EQ(nc_enddef(id), NC_NOERR);
    const char times[] = "2020-06-01_00:00:002020-06-01_03:00:00";
    nc_put_var_text(id, vTimes, times);
    const double rot = 20.0 * std::numbers::pi / 180.0;
    std::vector<float> lat, lon, ph, phb, qc, u, v, rc, rnc;
    for (size_t t = 0; t < nt; ++t)
    {
        for (size_t j = 0; j < ny; ++j)
            for (size_t i = 0; i < nx; ++i)
            {
                const double x = double(i) * 0.1, y = double(j) * 0.1;  // degrees, rotated by 20°
                lat.push_back(float(45.0 + x * std::sin(rot) + y * std::cos(rot)));
                lon.push_back(float(10.0 + (x * std::cos(rot) - y * std::sin(rot)) / std::cos(45.0 * std::numbers::pi / 180)));
                rc.push_back(t == 0 ? 0.0f : (j == 4 && i == 5 ? 9.0f : 0.0f));  // 9 mm in 3 h at the tower
                rnc.push_back(float(t) * 1.5f);                                    // 0.5 mm/h everywhere
            }
        for (size_t k = 0; k <= nz; ++k)
            for (size_t c = 0; c < ny * nx; ++c)
            {
                ph.push_back(0.0f);
                phb.push_back(float(k) * (k == nz ? 12000.0f / 4.0f * 4.0f : 1000.0f) * 9.81f);
            }
        for (size_t k = 0; k < nz; ++k)
            for (size_t j = 0; j < ny; ++j)
                for (size_t i = 0; i < nx; ++i)
                    qc.push_back(k == 1 || (j == 4 && i == 5) ? 3e-4f : 0.0f);
        for (size_t k = 0; k < nz; ++k)
            for (size_t j = 0; j < ny; ++j)
                for (size_t i = 0; i <= nx; ++i)
                    u.push_back(8.0f);
        for (size_t k = 0; k < nz; ++k)
            for (size_t j = 0; j <= ny; ++j)
                for (size_t i = 0; i < nx; ++i)
                    v.push_back(0.0f);
    }
    // Level 4 top at 12 km: the tower at (4, 5) spans 0..12 km.
    EXPECT_EQ(nc_put_var_float(id, vLat, lat.data()), NC_NOERR);
    nc_put_var_float(id, vLon, lon.data());
    nc_put_var_float(id, vPh, ph.data());
    nc_put_var_float(id, vPhb, phb.data());
    nc_put_var_float(id, vQc, qc.data());
    nc_put_var_float(id, vU, u.data());
    nc_put_var_float(id, vV, v.data());
    nc_put_var_float(id, vRc, rc.data());
    nc_put_var_float(id, vRnc, rnc.data());
    const int proj = 6;  // lat-lon: winds are earth-relative already
    nc_put_att_int(id, NC_GLOBAL, "MAP_PROJ", NC_INT, 1, &proj);
    EXPECT_EQ(nc_close(id), NC_NOERR);
    return path;
}

TEST(WrfIngest, SyntheticRotatedDomainIsResampledAndLayered)
{
    const std::string path = writeSyntheticWrf(test::tempPath("wrf.nc"));
    const ConvertResult r = convertFiles({path}, MappingOptions{}, {});
    ASSERT_EQ(r.snapshots.size(), 2u);
    EXPECT_EQ(r.snapshots[1].validTimeUnixS - r.snapshots[0].validTimeUnixS, 3 * 3600);
    const WeatherSnapshot& s = r.snapshots[1];
    EXPECT_NEAR(s.grid.dLatDeg, 0.1, 0.01);
    // The cell at the domain centre (well inside): low cloud 1-2 km.
    const double latC = 45.0 + 0.45 * std::sin(0.349) + 0.35 * std::cos(0.349);
    const double lonC = 10.0 + (0.45 * std::cos(0.349) - 0.35 * std::sin(0.349)) / std::cos(0.785);
    const auto cell = [&](double lat, double lon) {
        const auto iLat = uint32_t(std::lround((lat - s.grid.lat0Deg) / s.grid.dLatDeg));
        const auto iLon = uint32_t(std::lround((lon - s.grid.lon0Deg) / s.grid.dLonDeg));
        return s.grid.index(iLat, iLon);
    };
    const size_t c = cell(latC - 0.1, lonC - 0.1);
    EXPECT_NEAR(s.layers[0].baseAltitudeM[c], 1000.0f, 5.0f);
    EXPECT_NEAR(s.layers[0].topAltitudeM[c], 2000.0f, 5.0f);
    EXPECT_GT(s.layers[0].coverage[c], 0.5f);
    EXPECT_NEAR(s.layers[0].windEastMS[c], 8.0f, 1e-3f);
    EXPECT_NEAR(s.layers[0].precipitationMmH[c], 0.5f, 0.05f);
    // The deep tower becomes the convective layer with a cumulonimbus (3 mm/h convective rain).
    float maxConv = 0;
    uint8_t type = 0;
    for (size_t i = 0; i < s.grid.cellCount(); ++i)
        if (s.layers[2].coverage[i] > maxConv)
        {
            maxConv = s.layers[2].coverage[i];
            type = s.layers[2].type[i];
        }
    EXPECT_GT(maxConv, 0.2f);  // one source column, spread by bilinear weights
    EXPECT_EQ(type, uint8_t(CloudType::Cumulonimbus));
    // Corners of the bounding box lie outside the rotated domain: unknown.
    EXPECT_TRUE(std::isnan(s.layers[0].coverage[0]));
}

TEST(WrfIngest, KatrinaFourTimesThroughTheTimeline)
{
    const std::string path = std::string(SKY_SHARED_DIR) + "/weather/wrf-katrina-d02-20050828.nc";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "shared WRF sample not found at " << path;
    ConvertResult r = convertFiles({path}, MappingOptions{}, {});
    ASSERT_EQ(r.snapshots.size(), 4u);
    const int64_t t0 = 1125230400;  // 2005-08-28T12:00:00Z
    for (size_t i = 0; i < 4; ++i)
        EXPECT_EQ(r.snapshots[i].validTimeUnixS, t0 + int64_t(i) * 10800);
    const LatLonGrid g = r.snapshots[0].grid;
    EXPECT_NEAR(g.lat0Deg, 21.8, 0.1);
    EXPECT_GT(g.nLat, 40u);
    size_t cloudy = 0;
    for (const WeatherSnapshot& s : r.snapshots)
        for (size_t i = 0; i < g.cellCount(); ++i)
            if (s.layers[0].coverage[i] > 0.05f)
            {
                ++cloudy;
                EXPECT_LE(s.layers[0].baseAltitudeM[i], s.layers[0].topAltitudeM[i]);
            }
    EXPECT_GT(cloudy, 100u);  // a hurricane has cloud

    const std::vector<WeatherSnapshot> copy = r.snapshots;
    WeatherTimeline tl;
    std::string error;
    ASSERT_TRUE(tl.setSnapshots(std::move(r.snapshots), error)) << error;
    const WeatherSnapshot mid = tl.sample(double(t0 + 10800 + 2700));  // a quarter from 15:00 to 18:00
    for (size_t i = 0; i < g.cellCount(); ++i)
    {
        const float a = copy[1].layers[1].coverage[i], b = copy[2].layers[1].coverage[i];
        if (std::isfinite(a) && std::isfinite(b))
        {
            ASSERT_NEAR(mid.layers[1].coverage[i], 0.75f * a + 0.25f * b, 1e-5f) << i;
        }
    }
    EXPECT_TRUE(tl.bracket(double(t0 - 1)).clamped);
    EXPECT_EQ(tl.sample(double(t0 + 99999)).layers[0].coverage, copy[3].layers[0].coverage);
}

TEST(CloudTypeRules, EachGenusIsReachable)
{
    const auto type = [](LayerKind l, float cover, float thick, float precip, float cape, float conv) {
        return classifyCloud({l, cover, thick, precip, cape, conv});
    };
    EXPECT_EQ(type(LayerKind::Convective, 0.5f, 8000, 0, 2000, 0), CloudType::Cumulonimbus);
    EXPECT_EQ(type(LayerKind::Convective, 0.5f, 2000, 0, 2000, 0), CloudType::Cumulus);
    EXPECT_EQ(type(LayerKind::Low, 0.9f, 2000, 1.0f, 0, 0), CloudType::Nimbostratus);
    EXPECT_EQ(type(LayerKind::Low, 0.4f, 800, 0, 500, 0), CloudType::Cumulus);
    EXPECT_EQ(type(LayerKind::Low, 0.9f, 500, 0, 0, 0), CloudType::Stratus);
    EXPECT_EQ(type(LayerKind::Low, 0.6f, 1200, 0, 0, 0), CloudType::Stratocumulus);
    EXPECT_EQ(type(LayerKind::Middle, 0.8f, 1000, 0, 0, 0), CloudType::Altostratus);
    EXPECT_EQ(type(LayerKind::Middle, 0.3f, 1000, 0, 0, 0), CloudType::Altocumulus);
    EXPECT_EQ(type(LayerKind::Middle, 0.9f, 3000, 2.0f, 0, 0), CloudType::Nimbostratus);
    EXPECT_EQ(type(LayerKind::High, 0.8f, NAN, 0, 0, 0), CloudType::Cirrostratus);
    EXPECT_EQ(type(LayerKind::High, 0.3f, NAN, 0, 400, 0), CloudType::Cirrocumulus);
    EXPECT_EQ(type(LayerKind::High, 0.3f, NAN, 0, 0, 0), CloudType::Cirrus);
    EXPECT_EQ(type(LayerKind::Low, 0.005f, 500, 0, 0, 0), CloudType::None);
    EXPECT_EQ(type(LayerKind::Low, NAN, 500, 0, 0, 0), CloudType::None);
    EXPECT_NE(cloudTypeRulesMarkdown().find("| Cumulonimbus |"), std::string::npos);
}

TEST(PressureAltitude, MatchesTheIcaoTable)
{
    // ICAO Doc 7488/3 tabulated values.
    EXPECT_NEAR(standardAtmosphereAltitudeM(101325.0), 0.0, 0.01);
    EXPECT_NEAR(standardAtmosphereAltitudeM(50000.0), 5574.0, 1.0);
    EXPECT_NEAR(standardAtmosphereAltitudeM(22632.06), 11000.0, 0.5);
    EXPECT_NEAR(standardAtmosphereAltitudeM(5474.889), 20000.0, 0.5);
    EXPECT_NEAR(standardAtmosphereAltitudeM(868.0187), 32000.0, 1.0);
    for (double h : {-300.0, 0.0, 3000.0, 10999.0, 15000.0, 25000.0})
        EXPECT_NEAR(standardAtmosphereAltitudeM(standardAtmospherePressurePa(h)), h, 1e-6);
}

TEST(CurvilinearResampler, ReproducesALinearFieldOnARotatedGrid)
{
    const size_t ny = 12, nx = 15;
    std::vector<float> lat, lon, field;
    for (size_t j = 0; j < ny; ++j)
        for (size_t i = 0; i < nx; ++i)
        {
            lat.push_back(float(-10.0 + 0.2 * double(j) + 0.05 * double(i)));
            lon.push_back(float(179.0 + 0.2 * double(i) - 0.05 * double(j)));  // crosses the antimeridian
            field.push_back(lat.back() * 3.0f);
        }
    const CurvilinearResampler r(lat, lon, ny, nx, 1000000);
    const std::vector<float> out = r.resample(field);
    size_t inside = 0;
    for (size_t c = 0; c < out.size(); ++c)
        if (std::isfinite(out[c]))
        {
            ++inside;
            const double cellLat = r.grid().lat0Deg + double(c / r.grid().nLon) * r.grid().dLatDeg;
            ASSERT_NEAR(out[c], cellLat * 3.0, 1e-3) << c;
        }
    EXPECT_GT(inside, out.size() / 2);
    EXPECT_GT(r.coveredFraction(), 0.5);
}

}  // namespace
}  // namespace sky
