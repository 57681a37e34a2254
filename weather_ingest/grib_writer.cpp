// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_writer.h"

#include "weather_ingest/ingest_error.h"

#include <eccodes.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>

namespace sky
{
namespace
{

struct HandleDeleter
{
    void operator()(codes_handle* h) const { codes_handle_delete(h); }
};
struct FileCloser
{
    void operator()(std::FILE* f) const { std::fclose(f); }
};

constexpr double kMissing = 9999.0e20;  // outside every real value, inside the float range

}  // namespace

void writeGribFile(const std::string& path, const std::vector<GribOutField>& fields)
{
    std::unique_ptr<std::FILE, FileCloser> out(std::fopen(path.c_str(), "wb"));
    if (!out)
        throw IngestError(IngestErrorKind::Output, path, "", "", "cannot create");
    int number = 0;
    for (const GribOutField& f : fields)
    {
        ++number;
        const std::string where = "message " + std::to_string(number);
        std::unique_ptr<codes_handle, HandleDeleter> h(codes_handle_new_from_samples(nullptr, f.sample.c_str()));
        if (!h)
            throw IngestError(IngestErrorKind::Output, path, where, f.sample, "no such ecCodes sample");
        const auto check = [&](int err, const std::string& key) {
            if (err != CODES_SUCCESS)
                throw IngestError(IngestErrorKind::Output, path, where, key, codes_get_error_message(err));
        };
        for (const auto& [key, value] : f.keys)
        {
            size_t len = value.size();
            if (codes_set_string(h.get(), key.c_str(), value.c_str(), &len) != CODES_SUCCESS)
                check(codes_set_long(h.get(), key.c_str(), std::atol(value.c_str())), key);
        }
        const LatLonGrid& g = f.grid;
        if (g.cellCount() == 0 && !f.values.empty()) // a grid set by keys: values in its own scanning order
        {
            check(codes_set_long(h.get(), "bitsPerValue", f.bitsPerValue), "bitsPerValue");
            check(codes_set_double_array(h.get(), "values", f.values.data(), f.values.size()), "values");
        }
        if (g.cellCount() == 0) // keep the sample's own grid (e.g. a reduced Gaussian sample)
        {
            const void* bytes = nullptr;
            size_t size = 0;
            check(codes_get_message(h.get(), &bytes, &size), "message");
            if (std::fwrite(bytes, 1, size, out.get()) != size)
                throw IngestError(IngestErrorKind::Output, path, where, "", "write failed");
            continue;
        }
        const double lastLat = g.lat0Deg + g.dLatDeg * double(g.nLat - 1);
        const double lastLon = g.lon0Deg + g.dLonDeg * double(g.nLon - 1);
        const double firstLatOut = f.jScansPositively ? std::min(g.lat0Deg, lastLat) : std::max(g.lat0Deg, lastLat);
        const double lastLatOut = f.jScansPositively ? std::max(g.lat0Deg, lastLat) : std::min(g.lat0Deg, lastLat);
        check(codes_set_long(h.get(), "Ni", g.nLon), "Ni");
        check(codes_set_long(h.get(), "Nj", g.nLat), "Nj");
        check(codes_set_long(h.get(), "iScansNegatively", f.iScansNegatively), "iScansNegatively");
        check(codes_set_long(h.get(), "jScansPositively", f.jScansPositively), "jScansPositively");
        check(codes_set_double(h.get(), "latitudeOfFirstGridPointInDegrees", firstLatOut), "latitudeOfFirstGridPoint");
        check(codes_set_double(h.get(), "latitudeOfLastGridPointInDegrees", lastLatOut), "latitudeOfLastGridPoint");
        check(codes_set_double(h.get(), "longitudeOfFirstGridPointInDegrees", f.iScansNegatively ? lastLon : g.lon0Deg),
              "longitudeOfFirstGridPoint");
        check(codes_set_double(h.get(), "longitudeOfLastGridPointInDegrees", f.iScansNegatively ? g.lon0Deg : lastLon),
              "longitudeOfLastGridPoint");
        check(codes_set_double(h.get(), "iDirectionIncrementInDegrees", g.dLonDeg), "iDirectionIncrement");
        check(codes_set_double(h.get(), "jDirectionIncrementInDegrees", std::abs(g.dLatDeg)), "jDirectionIncrement");
        if (!f.packingType.empty())
        {
            size_t len = f.packingType.size();
            check(codes_set_string(h.get(), "packingType", f.packingType.c_str(), &len), "packingType");
        }
        check(codes_set_long(h.get(), "bitsPerValue", f.bitsPerValue), "bitsPerValue");

        // Canonical order (rows from lat0, columns eastwards) -> the requested scanning order.
        const bool flipRows = f.jScansPositively != (g.dLatDeg > 0);
        std::vector<double> v(g.cellCount());
        bool anyMissing = false;
        for (uint32_t r = 0; r < g.nLat; ++r)
            for (uint32_t c = 0; c < g.nLon; ++c)
            {
                const double x = f.values[g.index(flipRows ? g.nLat - 1 - r : r, f.iScansNegatively ? g.nLon - 1 - c : c)];
                const bool hole = std::isnan(x) && !f.nanAsValue;
                anyMissing = anyMissing || hole;
                v[size_t(r) * g.nLon + c] = hole ? kMissing : x;
            }
        if (anyMissing)
        {
            check(codes_set_double(h.get(), "missingValue", kMissing), "missingValue");
            check(codes_set_long(h.get(), "bitmapPresent", 1), "bitmapPresent");
        }
        check(codes_set_double_array(h.get(), "values", v.data(), v.size()), "values");
        const void* bytes = nullptr;
        size_t size = 0;
        check(codes_get_message(h.get(), &bytes, &size), "message");
        if (std::fwrite(bytes, 1, size, out.get()) != size)
            throw IngestError(IngestErrorKind::Output, path, where, "", "write failed");
    }
    if (std::fflush(out.get()) != 0)
        throw IngestError(IngestErrorKind::Output, path, "", "", "write failed");
}

namespace
{

struct GridSetup
{
    const char* sample;
    const char* gridType;                             // set first (nullptr: the sample's)
    std::vector<std::pair<const char*, double>> keys; // set as double (ecCodes converts)
};

GridSetup fixtureGrid(FixtureGrid kind, double latDeg, double lonDeg, int scale)
{
    switch (kind)
    {
    case FixtureGrid::Lambert:
    case FixtureGrid::LambertTwoParallels:
    {
        const bool two = kind == FixtureGrid::LambertTwoParallels;
        return {"regular_ll_sfc_grib2",
                "lambert",
                {{"Nx", 60 * scale},
                 {"Ny", 50 * scale},
                 {"DxInMetres", 20000.0 / scale},
                 {"DyInMetres", 20000.0 / scale},
                 {"LaDInDegrees", latDeg},
                 {"LoVInDegrees", lonDeg < 0 ? lonDeg + 360 : lonDeg},
                 {"Latin1InDegrees", two ? latDeg - 7 : latDeg},
                 {"Latin2InDegrees", two ? latDeg + 5 : latDeg},
                 {"latitudeOfFirstGridPointInDegrees", latDeg - 4},
                 {"longitudeOfFirstGridPointInDegrees", lonDeg - 7 < 0 ? lonDeg + 353 : lonDeg - 7}}};
    }
    case FixtureGrid::PolarNorth:
    case FixtureGrid::PolarSouth:
    {
        const bool south = kind == FixtureGrid::PolarSouth;
        return {"polar_stereographic_sfc_grib2",
                nullptr,
                {{"Nx", 60},
                 {"Ny", 60},
                 {"DxInMetres", 50000},
                 {"DyInMetres", 50000},
                 {"LaDInDegrees", south ? -60 : 60},
                 {"orientationOfTheGridInDegrees", 0},
                 {"southPoleOnProjectionPlane", south ? 1 : 0},
                 {"latitudeOfFirstGridPointInDegrees", south ? -70 : 70},
                 {"longitudeOfFirstGridPointInDegrees", south ? 225 : 315}}};
    }
    case FixtureGrid::Rotated:
        return {"rotated_ll_sfc_grib2",
                nullptr,
                {{"Ni", 81},
                 {"Nj", 61},
                 {"latitudeOfSouthernPoleInDegrees", -40},
                 {"longitudeOfSouthernPoleInDegrees", 10},
                 {"angleOfRotationInDegrees", 0},
                 {"latitudeOfFirstGridPointInDegrees", -7.5},
                 {"longitudeOfFirstGridPointInDegrees", -10},
                 {"latitudeOfLastGridPointInDegrees", 7.5},
                 {"longitudeOfLastGridPointInDegrees", 10},
                 {"iDirectionIncrementInDegrees", 0.25},
                 {"jDirectionIncrementInDegrees", 0.25}}};
    case FixtureGrid::ReducedGaussian:
        return {"reduced_gg_pl_32_grib2", nullptr, {}};
    }
    return {};
}

} // namespace

void writeCloudDiscFixture(const std::string& path, FixtureGrid kind, double latDeg, double lonDeg, double radiusKm,
                           double coveragePercent, bool iScansNegatively, bool jScansPositively, int lambertScale)
{
    const GridSetup setup = fixtureGrid(kind, latDeg, lonDeg, std::max(lambertScale, 1));
    std::unique_ptr<codes_handle, HandleDeleter> h(codes_handle_new_from_samples(nullptr, setup.sample));
    const auto check = [&](int err, const std::string& key)
    {
        if (err != CODES_SUCCESS)
            throw IngestError(IngestErrorKind::Output, path, "", key, codes_get_error_message(err));
    };
    if (!h)
        throw IngestError(IngestErrorKind::Output, path, "", setup.sample, "no such ecCodes sample");
    const std::pair<const char*, const char*> keys[] = {{"centre", "kwbc"},
                                                        {"dataDate", "20240301"},
                                                        {"dataTime", "1200"},
                                                        {"typeOfLevel", "lowCloudLayer"},
                                                        {"shortName", "tcc"}};
    for (const auto& [key, value] : keys)
    {
        size_t len = std::strlen(value);
        if (codes_set_string(h.get(), key, value, &len) != CODES_SUCCESS)
            check(codes_set_long(h.get(), key, std::atol(value)), key);
    }
    if (setup.gridType)
    {
        size_t len = std::strlen(setup.gridType);
        check(codes_set_string(h.get(), "gridType", setup.gridType, &len), "gridType");
    }
    for (const auto& [key, value] : setup.keys)
        check(codes_set_double(h.get(), key, value), key);
    if (kind != FixtureGrid::ReducedGaussian)
    {
        check(codes_set_long(h.get(), "iScansNegatively", iScansNegatively), "iScansNegatively");
        check(codes_set_long(h.get(), "jScansPositively", jScansPositively), "jScansPositively");
    }
    long points = 0;
    check(codes_get_long(h.get(), "numberOfDataPoints", &points), "numberOfDataPoints");
    if (kind != FixtureGrid::ReducedGaussian)
    {
        long nx = 0, ny = 0;
        check(codes_get_long(h.get(), "Ni", &nx), "Ni");
        check(codes_get_long(h.get(), "Nj", &ny), "Nj");
        points = nx * ny;
    }
    std::vector<double> values(size_t(points), 0.0);
    check(codes_set_long(h.get(), "bitsPerValue", 16), "bitsPerValue");
    check(codes_set_double_array(h.get(), "values", values.data(), values.size()), "values");
    // Where ecCodes puts each point: the disc is drawn in those positions.
    int err = 0;
    codes_iterator* it = codes_grib_iterator_new(h.get(), 0, &err);
    check(err, "iterator");
    const double centreLat = latDeg * std::numbers::pi / 180.0, centreLon = lonDeg * std::numbers::pi / 180.0;
    double lat = 0, lon = 0, value = 0;
    size_t k = 0;
    while (codes_grib_iterator_next(it, &lat, &lon, &value) > 0 && k < values.size())
    {
        const double p = lat * std::numbers::pi / 180.0, l = lon * std::numbers::pi / 180.0;
        const double cosAngle =
            std::sin(p) * std::sin(centreLat) + std::cos(p) * std::cos(centreLat) * std::cos(l - centreLon);
        const double km = 6371.0 * std::acos(std::clamp(cosAngle, -1.0, 1.0));
        values[k++] = km <= radiusKm ? coveragePercent : 0.0;
    }
    codes_grib_iterator_delete(it);
    check(codes_set_double_array(h.get(), "values", values.data(), values.size()), "values");
    const void* bytes = nullptr;
    size_t size = 0;
    check(codes_get_message(h.get(), &bytes, &size), "message");
    std::unique_ptr<std::FILE, FileCloser> out(std::fopen(path.c_str(), "wb"));
    if (!out || std::fwrite(bytes, 1, size, out.get()) != size || std::fflush(out.get()) != 0)
        throw IngestError(IngestErrorKind::Output, path, "", "", "write failed");
}

}  // namespace sky
