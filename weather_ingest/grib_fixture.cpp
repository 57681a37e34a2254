// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_fixture.h"

#include "weather_ingest/ingest_error.h"

#include <eccodes.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

namespace sky
{
namespace
{

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

struct HandleDeleter
{
    void operator()(codes_handle* h) const { codes_handle_delete(h); }
};
struct FileCloser
{
    void operator()(std::FILE* f) const { std::fclose(f); }
};

double wrap360(double deg)
{
    const double d = std::fmod(deg, 360.0);
    return d < 0 ? d + 360.0 : d;
}

/// An ecCodes handle being set up, with errors that name the fixture's path and the key.
class Message
{
  public:
    Message(const std::string& path, const std::string& sample) : path_(path)
    {
        h_.reset(codes_handle_new_from_samples(nullptr, sample.c_str()));
        if (!h_)
            throw IngestError(IngestErrorKind::Output, path, "", sample, "no such ecCodes sample");
    }
    codes_handle* get() const { return h_.get(); }
    void check(int err, const std::string& key) const
    {
        if (err != CODES_SUCCESS)
            throw IngestError(IngestErrorKind::Output, path_, "", key, codes_get_error_message(err));
    }
    void set(const char* key, double value) const { check(codes_set_double(get(), key, value), key); }
    void setLong(const char* key, long value) const { check(codes_set_long(get(), key, value), key); }
    void setString(const char* key, const char* value) const
    {
        size_t len = std::strlen(value);
        if (codes_set_string(get(), key, value, &len) != CODES_SUCCESS)
            check(codes_set_long(get(), key, std::atol(value)), key);
    }
    [[noreturn]] void fail(const std::string& key, const std::string& why) const
    {
        throw IngestError(IngestErrorKind::Output, path_, "", key, why);
    }
    void setValues(const std::vector<double>& values) const
    {
        check(codes_set_long(get(), "bitsPerValue", 16), "bitsPerValue");
        check(codes_set_double_array(get(), "values", values.data(), values.size()), "values");
    }
    /// Where ecCodes puts each of `count` points, in the order of the values.
    void locate(size_t count, std::vector<double>& latDeg, std::vector<double>& lonDeg) const
    {
        setValues(std::vector<double>(count, 0.0));
        int err = 0;
        codes_iterator* it = codes_grib_iterator_new(get(), 0, &err);
        check(err, "iterator");
        latDeg.clear();
        lonDeg.clear();
        double lat = 0, lon = 0, value = 0;
        while (codes_grib_iterator_next(it, &lat, &lon, &value) > 0)
        {
            latDeg.push_back(lat);
            lonDeg.push_back(lon);
        }
        codes_grib_iterator_delete(it);
        if (latDeg.size() != count)
            fail("iterator", "located " + std::to_string(latDeg.size()) + " of " + std::to_string(count) + " points");
    }

  private:
    std::string path_;
    std::unique_ptr<codes_handle, HandleDeleter> h_;
};

size_t scaled(double base, const CloudDiscFixture& f)
{
    return size_t(std::max(2L, std::lround(base * f.scale * f.extent)));
}

/// Polar stereographic plane (sphere of ecCodes' default radius, true at 60°, oriented along 0° E): where a
/// point lies, and back. Only used to move the grid's first point; ecCodes places the points.
constexpr double kEarthRadiusM = 6371229.0;
void toPolarPlane(bool south, double latDeg, double lonDeg, double& xM, double& yM)
{
    const double k = kEarthRadiusM * (1.0 + std::sin(60.0 * kRadPerDeg));
    const double rho = k * std::tan(std::numbers::pi / 4 - (south ? -latDeg : latDeg) * kRadPerDeg / 2);
    xM = rho * std::sin(lonDeg * kRadPerDeg);
    yM = (south ? 1.0 : -1.0) * rho * std::cos(lonDeg * kRadPerDeg);
}
void fromPolarPlane(bool south, double xM, double yM, double& latDeg, double& lonDeg)
{
    const double k = kEarthRadiusM * (1.0 + std::sin(60.0 * kRadPerDeg));
    const double lat = 90.0 - 2.0 * std::atan(std::hypot(xM, yM) / k) / kRadPerDeg;
    latDeg = south ? -lat : lat;
    lonDeg = std::atan2(xM, south ? yM : -yM) / kRadPerDeg;
}

/// Lambert, polar stereographic and Mercator grids: defined by their first point and spacing in metres.
/// The first point is moved until ecCodes puts the point a third of the way along both axes (in scanning
/// order) on the disc (a few passes: the offset from the first point to it changes slowly with the place),
/// so the disc lands there on any projection. Not the middle: a grid read mirrored would move the disc.
size_t setUpProjected(const Message& m, const CloudDiscFixture& f)
{
    const bool lambert = f.kind == FixtureGrid::Lambert || f.kind == FixtureGrid::LambertTwoParallels;
    const bool polar = f.kind == FixtureGrid::PolarNorth || f.kind == FixtureGrid::PolarSouth;
    const bool south = f.kind == FixtureGrid::PolarSouth;
    const size_t nx = scaled(60, f), ny = scaled(polar ? 60 : 50, f);
    const double spacingM = (polar ? 50000.0 : 20000.0) / f.scale;
    if (!polar)
        m.setString("gridType", lambert ? "lambert" : "mercator");
    m.setLong("Nx", long(nx));
    m.setLong("Ny", long(ny));
    m.set(polar || lambert ? "DxInMetres" : "DiInMetres", spacingM);
    m.set(polar || lambert ? "DyInMetres" : "DjInMetres", spacingM);
    if (lambert)
    {
        const bool two = f.kind == FixtureGrid::LambertTwoParallels;
        m.set("LaDInDegrees", f.latDeg);
        m.set("LoVInDegrees", wrap360(f.lonDeg));
        m.set("Latin1InDegrees", two ? f.latDeg - 7 : f.latDeg);
        m.set("Latin2InDegrees", two ? f.latDeg + 5 : f.latDeg);
    }
    else if (polar)
    {
        m.set("LaDInDegrees", south ? -60 : 60);
        m.set("orientationOfTheGridInDegrees", 0);
        m.setLong("southPoleOnProjectionPlane", south ? 1 : 0);
    }
    else
    {
        m.set("LaDInDegrees", f.latDeg);
        m.set("orientationOfTheGridInDegrees", 0);
    }
    m.setLong("iScansNegatively", f.iScansNegatively);
    m.setLong("jScansPositively", f.jScansPositively);
    const auto place = [&](double latDeg, double lonDeg)
    {
        m.set("latitudeOfFirstGridPointInDegrees", latDeg);
        m.set("longitudeOfFirstGridPointInDegrees", wrap360(lonDeg));
        if (!polar && !lambert)
        {
            m.set("latitudeOfLastGridPointInDegrees", latDeg);
            m.set("longitudeOfLastGridPointInDegrees", wrap360(lonDeg));
        }
    };
    // Start a third of the grid's size south-west of the disc (on the polar plane: x and y).
    const double toFirstXM = double(nx / 3) * spacingM, toFirstYM = double(ny / 3) * spacingM;
    double firstLat = f.latDeg - toFirstYM / 111000.0;
    double firstLon = f.lonDeg - toFirstXM / (111000.0 * std::max(0.2, std::cos(f.latDeg * kRadPerDeg)));
    double discX = 0, discY = 0;
    if (polar)
    {
        toPolarPlane(south, f.latDeg, f.lonDeg, discX, discY);
        fromPolarPlane(south, discX - toFirstXM, discY - toFirstYM, firstLat, firstLon);
    }
    std::vector<double> lat, lon;
    const size_t third = (ny / 3) * nx + nx / 3;
    for (int pass = 0; pass < 8; ++pass)
    {
        place(firstLat, firstLon);
        m.locate(nx * ny, lat, lon);
        if (polar)
        {
            double atX = 0, atY = 0, firstX = 0, firstY = 0;
            toPolarPlane(south, lat[third], lon[third], atX, atY);
            toPolarPlane(south, firstLat, firstLon, firstX, firstY);
            if (std::hypot(discX - atX, discY - atY) < 1.0)
                break;
            fromPolarPlane(south, firstX + discX - atX, firstY + discY - atY, firstLat, firstLon);
            continue;
        }
        const double dLat = f.latDeg - lat[third], dLon = std::remainder(f.lonDeg - lon[third], 360.0);
        if (std::abs(dLat) < 1e-5 && std::abs(dLon) < 1e-5)
            break;
        firstLat += dLat;
        firstLon += dLon;
    }
    if (!polar && !lambert) // Mercator also states its last point: the one ecCodes finds there
    {
        m.locate(nx * ny, lat, lon);
        m.set("latitudeOfLastGridPointInDegrees", lat.back());
        m.set("longitudeOfLastGridPointInDegrees", wrap360(lon.back()));
    }
    return nx * ny;
}

size_t setUpRotated(const Message& m, const CloudDiscFixture& f)
{
    const size_t ni = scaled(81, f), nj = scaled(61, f);
    const double d = 0.25 / f.scale;
    // The disc at the rotated grid's (0, 0), a third of the way from its west and south edges.
    const double westLon = -d * double(ni / 3), eastLon = westLon + d * double(ni - 1);
    const double southLat = -d * double(nj / 3), northLat = southLat + d * double(nj - 1);
    m.setLong("Ni", long(ni));
    m.setLong("Nj", long(nj));
    // The rotated grid's (0, 0) lies 90° north of its southern pole, on the pole's meridian.
    m.set("latitudeOfSouthernPoleInDegrees", f.latDeg - 90.0);
    m.set("longitudeOfSouthernPoleInDegrees", wrap360(f.lonDeg));
    m.set("angleOfRotationInDegrees", 0);
    m.setLong("iScansNegatively", f.iScansNegatively);
    m.setLong("jScansPositively", f.jScansPositively);
    m.set("latitudeOfFirstGridPointInDegrees", f.jScansPositively ? southLat : northLat);
    m.set("latitudeOfLastGridPointInDegrees", f.jScansPositively ? northLat : southLat);
    m.set("longitudeOfFirstGridPointInDegrees", f.iScansNegatively ? eastLon : westLon);
    m.set("longitudeOfLastGridPointInDegrees", f.iScansNegatively ? westLon : eastLon);
    m.set("iDirectionIncrementInDegrees", d);
    m.set("jDirectionIncrementInDegrees", d);
    return ni * nj;
}

/// Keeps the rows (latitudes given) within the band, with their point counts; returns the points.
size_t setRows(const Message& m, const std::vector<double>& rowLatDeg, const std::vector<long>& pl)
{
    const long widest = *std::max_element(pl.begin(), pl.end());
    m.setLong("Nj", long(pl.size()));
    m.check(codes_set_long_array(m.get(), "pl", pl.data(), pl.size()), "pl");
    m.set("latitudeOfFirstGridPointInDegrees", rowLatDeg.front());
    m.set("latitudeOfLastGridPointInDegrees", rowLatDeg.back());
    m.set("longitudeOfFirstGridPointInDegrees", 0);
    m.set("longitudeOfLastGridPointInDegrees", 360.0 - 360.0 / double(widest));
    size_t points = 0;
    for (const long n : pl)
        points += size_t(n);
    return points;
}

size_t setUpReducedGaussian(const Message& m, const CloudDiscFixture& f)
{
    long n = 0;
    m.check(codes_get_long(m.get(), "N", &n), "N");
    size_t rows = 0;
    m.check(codes_get_size(m.get(), "pl", &rows), "pl");
    std::vector<long> pl(rows);
    m.check(codes_get_long_array(m.get(), "pl", pl.data(), &rows), "pl");
    long points = 0;
    m.check(codes_get_long(m.get(), "numberOfDataPoints", &points), "numberOfDataPoints");
    if (f.bandHalfWidthDeg <= 0)
        return size_t(points);
    std::vector<double> gaussianLatDeg(size_t(2 * n));
    m.check(codes_get_gaussian_latitudes(n, gaussianLatDeg.data()), "Gaussian latitudes");
    std::vector<double> keptLat;
    std::vector<long> keptPl;
    for (size_t j = 0; j < rows && j < gaussianLatDeg.size(); ++j)
        if (std::abs(gaussianLatDeg[j] - f.latDeg) <= f.bandHalfWidthDeg)
        {
            keptLat.push_back(gaussianLatDeg[j]);
            keptPl.push_back(pl[j]);
        }
    if (keptPl.size() < 2)
        m.fail("bandHalfWidthDeg", "fewer than 2 rows in the band");
    return setRows(m, keptLat, keptPl);
}

size_t setUpReducedLatLon(const Message& m, const CloudDiscFixture& f)
{
    if (f.scale == 1 && f.bandHalfWidthDeg <= 0)
    {
        long points = 0;
        m.check(codes_get_long(m.get(), "numberOfDataPoints", &points), "numberOfDataPoints");
        return size_t(points);
    }
    const double d = 0.36 / f.scale;
    const auto rowCount = size_t(std::lround(180.0 / d)) + 1;
    std::vector<double> keptLat;
    std::vector<long> keptPl;
    for (size_t j = 0; j < rowCount; ++j)
    {
        const double lat = 90.0 - double(j) * d;
        if (f.bandHalfWidthDeg > 0 && std::abs(lat - f.latDeg) > f.bandHalfWidthDeg)
            continue;
        keptLat.push_back(lat);
        keptPl.push_back(std::max(1L, std::lround(360.0 / d * std::cos(lat * kRadPerDeg))));
    }
    m.set("jDirectionIncrementInDegrees", d);
    return setRows(m, keptLat, keptPl);
}

const char* sampleOf(const CloudDiscFixture& f, std::string& gaussianName)
{
    switch (f.kind)
    {
    case FixtureGrid::PolarNorth:
    case FixtureGrid::PolarSouth:
        return "polar_stereographic_sfc_grib2";
    case FixtureGrid::Rotated:
        return "rotated_ll_sfc_grib2";
    case FixtureGrid::ReducedGaussian:
        gaussianName = "reduced_gg_pl_" + std::to_string(std::lround(32 * f.scale)) + "_grib2";
        return gaussianName.c_str();
    case FixtureGrid::ReducedLatLon:
        return "reduced_ll_sfc_grib2";
    default:
        return "regular_ll_sfc_grib2";
    }
}

} // namespace

void writeCloudDiscFixture(const std::string& path, const CloudDiscFixture& f)
{
    if (!(f.scale > 0) || !(f.extent > 0) || !(f.radiusKm > 0))
        throw IngestError(IngestErrorKind::Output, path, "", "fixture", "scale, extent and radius must be positive");
    std::string gaussianName;
    const Message m(path, sampleOf(f, gaussianName));
    m.setString("centre", "kwbc");
    m.setString("dataDate", "20240301");
    m.setString("dataTime", "1200");
    m.setString("typeOfLevel", "lowCloudLayer");
    m.setString("shortName", "tcc");
    size_t points = 0;
    switch (f.kind)
    {
    case FixtureGrid::Rotated:
        points = setUpRotated(m, f);
        break;
    case FixtureGrid::ReducedGaussian:
        points = setUpReducedGaussian(m, f);
        break;
    case FixtureGrid::ReducedLatLon:
        points = setUpReducedLatLon(m, f);
        break;
    default:
        points = setUpProjected(m, f);
        break;
    }
    std::vector<double> lat, lon;
    m.locate(points, lat, lon);
    std::vector<double> values(points, 0.0);
    const double centreLat = f.latDeg * kRadPerDeg, centreLon = f.lonDeg * kRadPerDeg;
    for (size_t k = 0; k < points; ++k)
    {
        const double p = lat[k] * kRadPerDeg, l = lon[k] * kRadPerDeg;
        const double cosAngle =
            std::sin(p) * std::sin(centreLat) + std::cos(p) * std::cos(centreLat) * std::cos(l - centreLon);
        const double r = 6371.0 * std::acos(std::clamp(cosAngle, -1.0, 1.0)) / f.radiusKm;
        values[k] = r > 1.0 ? 0.0 : f.tapered ? f.coveragePercent * (1.0 - r * r * r) : f.coveragePercent;
    }
    m.setValues(values);
    const void* bytes = nullptr;
    size_t size = 0;
    m.check(codes_get_message(m.get(), &bytes, &size), "message");
    std::unique_ptr<std::FILE, FileCloser> out(std::fopen(path.c_str(), "wb"));
    if (!out || std::fwrite(bytes, 1, size, out.get()) != size || std::fflush(out.get()) != 0)
        throw IngestError(IngestErrorKind::Output, path, "", "", "write failed");
}

} // namespace sky
