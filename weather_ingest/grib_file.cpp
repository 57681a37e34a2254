// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_file.h"

#include "weather_ingest/civil_time.h"
#include "weather_ingest/grib_framing.h"
#include "weather_ingest/ingest_error.h"

#include <eccodes.h>

#include <stdexcept>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace sky
{
namespace
{

// Value ecCodes writes into bitmap holes; set explicitly because the default (9999) is a plausible
// geopotential height.
constexpr double kMissingSentinel = 1.0e36;

// ecCodes prints its own errors to stderr; ours name file, message and field, so its are dropped.
void setUpEccodes()
{
    static const bool once = [] {
        codes_context_set_logging_proc(codes_context_get_default(), [](const grib_context*, int, const char*) {});
        return true;
    }();
    (void)once;
}

std::string messageLocation(int number) { return "message " + std::to_string(number); }

class KeyReader
{
public:
    KeyReader(grib_handle* h, const std::string& file, int number) : h_(h), file_(file), number_(number) {}

    bool has(const char* key) const { return codes_is_defined(h_, key) != 0; }

    long getLong(const char* key) const
    {
        long v = 0;
        check(codes_get_long(h_, key, &v), key);
        return v;
    }
    long getLong(const char* key, long fallback) const { return has(key) ? getLong(key) : fallback; }

    double getDouble(const char* key) const
    {
        double v = 0;
        check(codes_get_double(h_, key, &v), key);
        return v;
    }

    double getDoubleOr(const char* key) const { return has(key) && !missing(key) ? getDouble(key) : std::nan(""); }

    bool missing(const char* key) const
    {
        int err = 0;
        return codes_is_missing(h_, key, &err) != 0 && err == CODES_SUCCESS;
    }

    std::string getString(const char* key) const
    {
        if (!has(key))
            return {};
        char buf[256] = {};
        size_t len = sizeof buf;
        check(codes_get_string(h_, key, buf, &len), key);
        return std::string(buf);
    }

    void check(int err, const char* key) const
    {
        if (err != CODES_SUCCESS)
            throw IngestError(IngestErrorKind::Corrupt, file_, messageLocation(number_), key,
                              std::string("ecCodes: ") + codes_get_error_message(err));
    }

    [[noreturn]] void refuse(const char* key, const std::string& why) const
    {
        throw IngestError(IngestErrorKind::Corrupt, file_, messageLocation(number_), key, why);
    }

private:
    grib_handle* h_;
    const std::string& file_;
    int number_;
};

std::string format(const char* fmt, double a, double b = 0, double c = 0)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, fmt, a, b, c);
    return buf;
}

/// Grid type, size, resolution and projection, from whichever of ecCodes' keys the grid has.
std::string describeGrid(const KeyReader& k, const std::string& gridType)
{
    std::string d = gridType;
    const double ni = k.getDoubleOr("Ni"), nj = k.getDoubleOr("Nj");
    const double points = k.getDoubleOr("numberOfDataPoints");
    if (std::isfinite(ni) && std::isfinite(nj))
        d += format(" %.0f x %.0f", ni, nj);
    else if (std::isfinite(points))
        d += format(" %.0f points", points) + (std::isfinite(nj) ? format(" in %.0f rows", nj) : "");
    const double dx = k.getDoubleOr("DxInMetres"), dy = k.getDoubleOr("DyInMetres");
    const double di = k.getDoubleOr("iDirectionIncrementInDegrees"), dj = k.getDoubleOr("jDirectionIncrementInDegrees");
    const double gaussN = gridType.find("_gg") != std::string::npos ? k.getDoubleOr("N") : std::nan("");
    if (std::isfinite(dx) && dx > 0)
        d += format(", %.4g x %.4g km", dx / 1000.0, (std::isfinite(dy) ? dy : dx) / 1000.0);
    else if (std::isfinite(gaussN) && gaussN > 0)
        d += std::string(", ") + (k.getLong("isOctahedral", 0) != 0 ? "O" : "N") +
             format("%.0f (~%.3g deg)", gaussN, 90.0 / gaussN);
    else if (std::isfinite(di) && std::isfinite(dj))
        d += format(", %.4g x %.4g deg", di, dj);
    if (gridType == "lambert" || gridType == "lambert_lam")
        d += format(", standard parallels %g/%g, LoV %g", k.getDoubleOr("Latin1InDegrees"),
                    k.getDoubleOr("Latin2InDegrees"), k.getDoubleOr("LoVInDegrees"));
    else if (gridType == "polar_stereographic")
        d += format(", LoV %g, ", k.getDoubleOr("orientationOfTheGridInDegrees")) +
             (k.getLong("southPoleOnProjectionPlane", 0) != 0 ? "south" : "north") + " pole";
    else if (gridType.find("rotated") != std::string::npos)
        d += format(", south pole of rotation %g, %g", k.getDoubleOr("latitudeOfSouthernPoleInDegrees"),
                    k.getDoubleOr("longitudeOfSouthernPoleInDegrees"));
    const double lat1 = k.getDoubleOr("latitudeOfFirstGridPointInDegrees"),
                 lon1 = k.getDoubleOr("longitudeOfFirstGridPointInDegrees");
    if (gridType == "regular_ll")
        d += format(", lat %g .. %g", lat1, k.getDoubleOr("latitudeOfLastGridPointInDegrees")) +
             format(", lon %g .. %g", lon1, k.getDoubleOr("longitudeOfLastGridPointInDegrees"));
    else if (std::isfinite(lat1) && std::isfinite(lon1))
        d += format(", first point %g, %g", lat1, lon1);
    return d;
}

// ecCodes 2.28 loops forever deriving validityDate from a GRIB2 time unit outside WMO Code Table 4.4
// (255, "missing", found by the fuzzer): such a message is refused before any step or date key is read.
void refuseUnknownTimeUnits(const KeyReader& k)
{
    for (const char* key : {"indicatorOfUnitOfTimeRange", "indicatorOfUnitForTimeRange"}) {
        if (!k.has(key))
            continue;
        const long unit = k.getLong(key);
        const bool inCodeTable = (unit >= 0 && unit <= 7) || (unit >= 10 && unit <= 13);
        if (!inCodeTable)
            k.refuse(key, "time unit " + std::to_string(unit) + " is not in WMO Code Table 4.4");
    }
}

GribMessageInfo readInfo(grib_handle* h, const std::string& file, int number)
{
    const KeyReader k(h, file, number);
    GribMessageInfo info;
    info.number = number;
    info.edition = k.getLong("editionNumber");
    info.shortName = k.getString("shortName");
    info.typeOfLevel = k.getString("typeOfLevel");
    info.units = k.getString("units");
    info.name = k.getString("name");
    info.gridType = k.getString("gridType");
    refuseUnknownTimeUnits(k);
    info.level = k.getLong("level", 0);
    info.centre = k.getLong("centre", 0);
    info.stepRange = k.getString("stepRange");
    const long date = k.getLong("validityDate");
    const long time = k.getLong("validityTime");
    info.validTimeUnixS = unixTimeFromCivil(int(date / 10000), int(date / 100 % 100), int(date % 100),
                                            int(time / 100), int(time % 100), 0);
    info.gridDescription = describeGrid(k, info.gridType);
    info.gridKey = k.getString("md5GridSection");
    info.uvRelativeToGrid = k.getLong("uvRelativeToGrid", 0) != 0;
    // Steps in hours whatever unit the message uses; a message that refuses the unit keeps its own.
    codes_set_string(h, "stepUnits", "h", nullptr);
    if (k.has("startStep") && k.has("endStep"))
        info.accumulationHours = double(k.getLong("endStep") - k.getLong("startStep"));
    return info;
}

}  // namespace

void GribMessage::HandleDeleter::operator()(grib_handle* h) const { codes_handle_delete(h); }

GribMessage::GribMessage() = default;
GribMessage::~GribMessage() = default;
GribMessage::GribMessage(GribMessage&&) noexcept = default;
GribMessage& GribMessage::operator=(GribMessage&&) noexcept = default;

GridField GribMessage::decodeRegular(size_t maxCells) const
{
    grib_handle* h = handle_.get();
    const std::string where = messageLocation(info_.number);
    const std::string field = info_.label();
    const KeyReader k(h, file_, info_.number);
    const long ni = k.getLong("Ni");
    const long nj = k.getLong("Nj");
    if (ni < 1 || nj < 1 || double(ni) * double(nj) > double(maxCells))
        throw IngestError(IngestErrorKind::TooLarge, file_, where, field,
                          "grid " + std::to_string(ni) + " x " + std::to_string(nj) + " is empty or exceeds " +
                              std::to_string(maxCells) + " points");
    // ecCodes sizes its buffers from these keys without checking them against each other (a damaged
    // message claiming 3e8 coded values for 12 points makes it allocate gigabytes), so they are checked here.
    const long dataPoints = k.getLong("numberOfDataPoints", ni * nj);
    const long codedValues = k.getLong("numberOfCodedValues", dataPoints);
    const long bitsPerValue = k.getLong("bitsPerValue", 0);
    if (dataPoints != ni * nj || codedValues < 0 || codedValues > dataPoints || bitsPerValue < 0 || bitsPerValue > 64)
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field,
                          "inconsistent sizes: " + std::to_string(ni) + " x " + std::to_string(nj) + " grid, " +
                              std::to_string(dataPoints) + " data points, " + std::to_string(codedValues) +
                              " coded values, " + std::to_string(bitsPerValue) + " bits per value");
    size_t count = 0;
    k.check(codes_get_size(h, "values", &count), "values");
    if (count != size_t(ni) * size_t(nj))
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field,
                          std::to_string(count) + " values for a " + std::to_string(ni) + " x " + std::to_string(nj) +
                              " grid");

    const double firstLat = k.getDouble("latitudeOfFirstGridPointInDegrees");
    const double firstLon = k.getDouble("longitudeOfFirstGridPointInDegrees");
    const double lastLat = k.getDouble("latitudeOfLastGridPointInDegrees");
    const double lastLon = k.getDouble("longitudeOfLastGridPointInDegrees");
    const bool iNegative = k.getLong("iScansNegatively", 0) != 0;
    const bool jPositive = k.getLong("jScansPositively", 0) != 0;
    const bool jConsecutive = k.getLong("jPointsAreConsecutive", 0) != 0;
    const bool alternateRows = k.getLong("alternativeRowScanning", 0) != 0;

    double dLon = 0;
    if (ni > 1)
    {
        double span = iNegative ? firstLon - lastLon : lastLon - firstLon;
        if (span < 0)
            span += 360.0;  // e.g. 180 .. 179.75 going east through 0
        dLon = span / double(ni - 1);
    }
    else
    {
        dLon = k.has("iDirectionIncrementInDegrees") ? std::abs(k.getDouble("iDirectionIncrementInDegrees")) : 1.0;
    }
    double dLat = 0;
    if (nj > 1)
        dLat = (lastLat - firstLat) / double(nj - 1);
    else
        dLat = (jPositive ? 1.0 : -1.0) *
               (k.has("jDirectionIncrementInDegrees") ? std::abs(k.getDouble("jDirectionIncrementInDegrees")) : 1.0);
    const bool latOk = std::abs(firstLat) <= 90.0 + 1e-6 && std::abs(lastLat) <= 90.0 + 1e-6;
    if (!(dLon > 0) || double(ni) * dLon > 360.0 + dLon * 0.5 || !latOk || (nj > 1 && dLat == 0) ||
        (nj > 1 && (dLat > 0) != jPositive))
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field,
                          "inconsistent grid: first (" + std::to_string(firstLat) + ", " + std::to_string(firstLon) +
                              "), last (" + std::to_string(lastLat) + ", " + std::to_string(lastLon) +
                              "), " + std::to_string(ni) + " x " + std::to_string(nj) + " points");

    GridField out;
    out.grid.nLon = uint32_t(ni);
    out.grid.nLat = uint32_t(nj);
    out.grid.dLonDeg = dLon;
    out.grid.dLatDeg = dLat;
    out.grid.lat0Deg = firstLat;
    out.grid.lon0Deg = wrapLongitudeDeg(iNegative ? firstLon - double(ni - 1) * dLon : firstLon);

    k.check(codes_set_double(h, "missingValue", kMissingSentinel), "missingValue");
    std::vector<double> raw(count);
    size_t got = count;
    k.check(codes_get_double_array(h, "values", raw.data(), &got), "values");
    if (got != count)
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field, "short read of values");
    const bool bitmap = k.getLong("bitmapPresent", 0) != 0;

    out.values.resize(count);
    const auto uni = size_t(ni);
    const auto unj = size_t(nj);
    for (size_t s = 0; s < count; ++s)
    {
        size_t i = jConsecutive ? s / unj : s % uni;
        const size_t j = jConsecutive ? s % unj : s / uni;
        if (alternateRows && !jConsecutive && (j & 1u))
            i = uni - 1 - i;
        const size_t column = iNegative ? uni - 1 - i : i;
        const double v = raw[s];
        const bool missing = bitmap && v == kMissingSentinel;
        const bool invalid = !missing && !std::isfinite(v);
        out.invalidCount += invalid ? 1u : 0u;
        out.values[j * uni + column] = missing || invalid ? NAN : static_cast<float>(v);
    }
    return out;
}

GridField GribMessage::decode(size_t maxCells) const
{
    GribGridCache grids;
    return decode(maxCells, grids);
}

GridField GribMessage::decode(size_t maxCells, GribGridCache& grids, std::shared_ptr<const GribGrid>* gridOut) const
{
    const std::string where = messageLocation(info_.number);
    const std::string field = info_.label();
    std::shared_ptr<const GribGrid> grid = grids.find(info_.gridKey);
    if (info_.gridType == "regular_ll")
    {
        GridField out = decodeRegular(maxCells);
        if (!grid || !sameGrid(grid->target(), out.grid))
        {
            grid = std::make_shared<const GribGrid>(out.grid, info_.gridDescription);
            grids.add(info_.gridKey, grid);
        }
        if (gridOut)
            *gridOut = grid;
        return out;
    }
    if (!grid)
    {
        const GribGridPoints points = locatePoints(maxCells);
        try
        {
            grid = std::make_shared<const GribGrid>(points, maxCells);
        }
        catch (const std::length_error&)
        {
            throw IngestError(IngestErrorKind::TooLarge, file_, where, field,
                              "grid " + info_.gridDescription + ": resampled onto a regular grid it exceeds " +
                                  std::to_string(maxCells) + " cells");
        }
        catch (const std::invalid_argument& e)
        {
            throw IngestError(IngestErrorKind::UnsupportedGrid, file_, where, field,
                              "grid " + info_.gridDescription + ": " + e.what());
        }
        grids.add(info_.gridKey, grid);
    }
    grib_handle* h = handle_.get();
    const KeyReader k(h, file_, info_.number);
    const long dataPoints = k.getLong("numberOfDataPoints", -1);
    const long codedValues = k.getLong("numberOfCodedValues", dataPoints);
    const long bitsPerValue = k.getLong("bitsPerValue", 0);
    size_t count = 0;
    k.check(codes_get_size(h, "values", &count), "values");
    if (dataPoints < 0 || size_t(dataPoints) != grid->sourcePoints() || count != grid->sourcePoints() ||
        codedValues < 0 || codedValues > dataPoints || bitsPerValue < 0 || bitsPerValue > 64)
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field,
                          "grid " + info_.gridDescription +
                              ": inconsistent sizes: " + std::to_string(grid->sourcePoints()) + " grid points, " +
                              std::to_string(dataPoints) + " data points, " + std::to_string(count) + " values, " +
                              std::to_string(codedValues) + " coded values");
    k.check(codes_set_double(h, "missingValue", kMissingSentinel), "missingValue");
    std::vector<double> raw(count);
    size_t got = count;
    k.check(codes_get_double_array(h, "values", raw.data(), &got), "values");
    if (got != count)
        throw IngestError(IngestErrorKind::Corrupt, file_, where, field, "short read of values");
    const bool bitmap = k.getLong("bitmapPresent", 0) != 0;
    GridField out;
    for (double& v : raw)
    {
        const bool missing = bitmap && v == kMissingSentinel;
        const bool invalid = !missing && !std::isfinite(v);
        out.invalidCount += invalid ? 1u : 0u;
        if (missing || invalid)
            v = NAN;
    }
    out.grid = grid->target();
    out.values = grid->resample(raw);
    if (gridOut)
        *gridOut = grid;
    return out;
}

namespace
{

/// Each point's latitude and longitude from ecCodes' iterator, checked: count of them, finite, on the sphere.
template <typename Unsupported, typename Corrupt>
void locatePointPositions(grib_handle* h, size_t count, GribGridPoints& p, const Unsupported& unsupported,
                          const Corrupt& corrupt)
{
    int err = 0;
    codes_iterator* it = codes_grib_iterator_new(h, 0, &err);
    if (!it || err != CODES_SUCCESS)
    {
        if (it)
            codes_grib_iterator_delete(it);
        throw unsupported(std::string("ecCodes cannot locate its points (") + codes_get_error_message(err) +
                          "); only grids whose points ecCodes can iterate are read (not spectral or unstructured)");
    }
    p.latDeg.reserve(count);
    p.lonDeg.reserve(count);
    double lat = 0, lon = 0, value = 0;
    while (p.latDeg.size() <= count && codes_grib_iterator_next(it, &lat, &lon, &value) > 0)
    {
        p.latDeg.push_back(lat);
        p.lonDeg.push_back(lon);
    }
    codes_grib_iterator_delete(it);
    if (p.latDeg.size() != count)
        throw corrupt("ecCodes located " + std::to_string(p.latDeg.size()) + " points for " + std::to_string(count) +
                      " values");
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(p.latDeg[i]) || !std::isfinite(p.lonDeg[i]) || std::abs(p.latDeg[i]) > 90.0 + 1e-6)
            throw unsupported("ecCodes gives point " + std::to_string(i + 1) + " no valid position (" +
                              std::to_string(p.latDeg[i]) + ", " + std::to_string(p.lonDeg[i]) + ")");
}

}  // namespace

GribGridPoints GribMessage::locatePoints(size_t maxCells) const
{
    grib_handle* h = handle_.get();
    const std::string where = messageLocation(info_.number);
    const std::string field = info_.label();
    const std::string grid = "grid " + info_.gridDescription;
    const KeyReader k(h, file_, info_.number);
    const auto unsupported = [&](const std::string& why)
    { return IngestError(IngestErrorKind::UnsupportedGrid, file_, where, field, grid + ": " + why); };
    const auto corrupt = [&](const std::string& why)
    { return IngestError(IngestErrorKind::Corrupt, file_, where, field, grid + ": " + why); };
    GribGridPoints p;
    p.gridType = info_.gridType;
    p.description = info_.gridDescription;
    const long dataPoints = k.getLong("numberOfDataPoints", -1);
    if (dataPoints < 4 || size_t(dataPoints) > maxCells)
        throw IngestError(IngestErrorKind::TooLarge, file_, where, field,
                          grid + ": " + std::to_string(dataPoints) + " points is too few or exceeds " +
                              std::to_string(maxCells));
    if (info_.gridType == "lambert" || info_.gridType == "lambert_lam")
    {
        // Cone constant n (Snyder, "Map Projections: A Working Manual", eq. 15-3); n = 0 (parallels
        // symmetric about the equator, or on it) is a cylinder, not a cone.
        constexpr double kPi = 3.14159265358979323846;
        constexpr double kRad = kPi / 180.0;
        const double p1 = k.getDoubleOr("Latin1InDegrees") * kRad, p2 = k.getDoubleOr("Latin2InDegrees") * kRad;
        const double n = std::abs(p1 - p2) < 1e-9
                             ? std::sin(p1)
                             : std::log(std::cos(p1) / std::cos(p2)) /
                                   std::log(std::tan(0.25 * kPi + 0.5 * p2) / std::tan(0.25 * kPi + 0.5 * p1));
        if (!std::isfinite(n) || std::abs(n) < 1e-6 || std::abs(n) > 1.0 + 1e-9)
            throw unsupported("degenerate Lambert cone: standard parallels " + std::to_string(p1 / kRad) + " and " +
                              std::to_string(p2 / kRad) + " give cone constant " + std::to_string(n) +
                              " (they must lie in one hemisphere, off the equator)");
    }
    // ecCodes sizes its iterator from these keys without checking them against each other.
    if (k.has("pl") && info_.gridType.rfind("reduced", 0) == 0)
    {
        size_t rows = 0;
        k.check(codes_get_size(h, "pl", &rows), "pl");
        p.pl.resize(rows);
        size_t got = rows;
        if (rows > 0)
            k.check(codes_get_long_array(h, "pl", p.pl.data(), &got), "pl");
        long sum = 0;
        for (const long count : p.pl)
            sum += count > 0 ? count : 0;
        p.nj = rows;
        if (rows < 2 || sum != dataPoints)
            throw corrupt("inconsistent sizes: the " + std::to_string(rows) + " row lengths (pl) add up to " +
                          std::to_string(sum) + " points, the message declares " + std::to_string(dataPoints));
    }
    else if (!k.has("Ni") || !k.has("Nj") || k.missing("Ni") || k.missing("Nj"))
    {
        throw unsupported("ecCodes cannot locate its points (no rows and columns: spectral or unstructured); only "
                          "grids whose points ecCodes can iterate are read");
    }
    else
    {
        const long ni = k.getLong("Ni", -1);
        const long nj = k.missing("Nj") ? -1 : k.getLong("Nj", -1);
        if (ni < 2 || nj < 2 || double(ni) * double(nj) != double(dataPoints))
            throw corrupt("inconsistent sizes: " + std::to_string(ni) + " x " + std::to_string(nj) +
                          " points declared, the message has " + std::to_string(dataPoints) + " data points");
        p.ni = size_t(ni);
        p.nj = size_t(nj);
    }
    size_t count = 0;
    k.check(codes_get_size(h, "values", &count), "values");
    if (count != size_t(dataPoints))
        throw corrupt(std::to_string(count) + " values for " + std::to_string(dataPoints) + " data points");
    p.iScansNegatively = k.getLong("iScansNegatively", 0) != 0;
    p.jPointsAreConsecutive = k.getLong("jPointsAreConsecutive", 0) != 0;
    p.alternativeRowScanning = k.getLong("alternativeRowScanning", 0) != 0;

    locatePointPositions(h, count, p, unsupported, corrupt);
    return p;
}

GribFile::GribFile(const std::string& path) : path_(path)
{
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f)
        throw IngestError(IngestErrorKind::Io, path, "", "", std::string("cannot open: ") + std::strerror(errno));
    setUpEccodes();
    char buf[1 << 16];
    size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0)
        bytes_.insert(bytes_.end(), buf, buf + n);
    if (std::ferror(f.get()))
        throw IngestError(IngestErrorKind::Io, path, "", "", "read error");
}

GribFile::GribFile(const std::string& name, const void* data, size_t size)
    : path_(name), bytes_(static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size)
{
    setUpEccodes();
}

GribFile::~GribFile() = default;

double GribFile::fractionRead() const
{
    return bytes_.empty() ? 1.0 : double(offset_) / double(bytes_.size());
}

bool GribFile::next(GribMessage& message)
{
    const int number = count_ + 1;
    if (pending_.empty())
    {
        GribFrame frame;
        std::string error;
        const int found = nextGribFrame(bytes_.data(), bytes_.size(), offset_, frame, error);
        if (found == 0)
            return false;
        if (found < 0)
            throw IngestError(IngestErrorKind::Corrupt, path_, messageLocation(number), "", error);
        for (std::vector<uint8_t>& field : frame.fields)
            pending_.push_back(std::move(field));
    }
    grib_handle* h = codes_handle_new_from_message_copy(nullptr, pending_.front().data(), pending_.front().size());
    pending_.pop_front();
    if (!h)
        throw IngestError(IngestErrorKind::Corrupt, path_, messageLocation(number), "", "ecCodes cannot decode it");
    message.handle_.reset(h);
    message.file_ = path_;
    count_ = number;
    message.info_ = readInfo(h, path_, number);
    return true;
}

}  // namespace sky
