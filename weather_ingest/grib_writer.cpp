// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_writer.h"

#include "weather_ingest/ingest_error.h"

#include <eccodes.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

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

}  // namespace sky
