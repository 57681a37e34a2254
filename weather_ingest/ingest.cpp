// SPDX-License-Identifier: MIT
#include "weather_ingest/ingest.h"

#include "weather_ingest/civil_time.h"
#include "weather_ingest/grib_mapping.h"
#include "weather_ingest/grid_composite.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/netcdf_file.h"
#include "weather_ingest/snapshot_file.h"
#include "weather_ingest/wrf_mapping.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

namespace sky
{
namespace
{

bool startsWith(const std::vector<uint8_t>& b, const char* magic, size_t n)
{
    return b.size() >= n && std::memcmp(b.data(), magic, n) == 0;
}

std::string looksLike(const std::vector<uint8_t>& b)
{
    if (startsWith(b, "\x89PNG", 4))
        return "a PNG image";
    if (startsWith(b, "\xFF\xD8\xFF", 3))
        return "a JPEG image";
    if (startsWith(b, "\x1F\x8B", 2))
        return "gzip-compressed data (decompress it first)";
    if (startsWith(b, "BZh", 3))
        return "bzip2-compressed data (decompress it first)";
    if (startsWith(b, "\x89SKYWX", 6))
        return "a sky weather snapshot (use `sky-ingest check`)";
    const bool text = std::all_of(b.begin(), b.end(), [](uint8_t c) { return c == '\n' || c == '\r' || c == '\t' || (c >= 32 && c < 127); });
    return text ? "a text file" : "unknown binary data";
}

bool isCover(GribRole role)
{
    return role == GribRole::CoverLow || role == GribRole::CoverMiddle || role == GribRole::CoverHigh ||
           role == GribRole::CoverConvective || role == GribRole::CoverBoundaryLayer;
}

/// The snapshot of one valid time: one per grid the records are on, then composited.
WeatherSnapshot mapTime(const std::vector<const GribRecord*>& records, const MappingOptions& options,
                        std::vector<std::string>& warnings)
{
    std::vector<std::vector<const GribRecord*>> groups;
    for (const GribRecord* r : records)
    {
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const auto& g) { return sameGrid(g.front()->field.grid, r->field.grid); });
        if (it == groups.end())
            groups.push_back({r});
        else
            it->push_back(r);
    }
    std::vector<WeatherSnapshot> parts;
    for (const std::vector<const GribRecord*>& g : groups)
    {
        const bool hasCover = std::any_of(g.begin(), g.end(), [](const GribRecord* r) { return isCover(r->row.role); });
        const std::string gridName = g.front()->grid ? g.front()->grid->description() : "?";
        if (!hasCover)
        {
            if (groups.size() > 1)
            {
                warnings.push_back(g.front()->source + " and " + std::to_string(g.size() - 1) +
                                   " other messages on grid " + gridName + " not used: no cloud cover on that grid");
                continue;
            }
        }
        WeatherSnapshot s = mapGribRecords(g, options, warnings);
        if (const std::shared_ptr<const GribGrid>& grid = g.front()->grid)
        {
            s.dataWeight = grid->dataWeight();
            s.provenance["grid"] =
                gridName + (grid->gridType() == "regular_ll"
                                ? ""
                                : " -> regular " + std::to_string(s.grid.nLon) + " x " + std::to_string(s.grid.nLat) +
                                      " at " + std::to_string(s.grid.dLatDeg) + " deg");
        }
        parts.push_back(std::move(s));
    }
    if (parts.empty())
        return mapGribRecords(records, options, warnings); // names what is missing
    return compositeSnapshots(std::move(parts), kMaxCompositeCells, warnings);
}

/// MappingOptions' amplification guard: decoded and written bytes against the input's size.
class AmplificationGuard
{
public:
    AmplificationGuard(const MappingOptions& o, uint64_t inputBytes)
        : off_(o.allowLargeOutput), inputBytes_(inputBytes),
          budgetBytes_(std::max(double(o.amplificationFloorBytes), o.maxAmplification * double(inputBytes)))
    {
    }
    /// The most cells one message may decode to, given what is decoded already.
    size_t maxCells(uint64_t decodedBytes) const
    {
        if (off_)
            return kMaxSnapshotCells;
        const double leftBytes = std::max(0.0, budgetBytes_ - double(decodedBytes));
        return size_t(std::clamp(leftBytes / sizeof(float), 1.0, double(kMaxSnapshotCells)));
    }
    void check(uint64_t bytes, const std::string& what, const std::string& path) const
    {
        if (off_ || double(bytes) <= budgetBytes_)
            return;
        throw IngestError(IngestErrorKind::TooLarge, path, "", "",
                          what + " " + std::to_string(bytes) + " bytes from " + std::to_string(inputBytes_) +
                              " bytes of input, over the limit of " + std::to_string(uint64_t(budgetBytes_)) +
                              " bytes; pass --allow-large-output if that is expected");
    }

private:
    bool off_;
    uint64_t inputBytes_;
    double budgetBytes_;
};

uint64_t payloadBytes(const WeatherSnapshot& s)
{
    uint64_t n = s.capeJKg.size() + s.tropopauseAltitudeM.size() + s.dataWeight.size() + s.high.coverage.size() +
                 s.high.altitudeM.size() + s.high.windEastMS.size() + s.high.windNorthMS.size();
    n *= sizeof(float);
    n += s.high.type.size();
    for (const CloudLayerFields& l : s.layers)
        n += sizeof(float) * (l.coverage.size() + l.baseAltitudeM.size() + l.topAltitudeM.size() +
                              l.precipitationMmH.size() + l.windEastMS.size() + l.windNorthMS.size()) +
             l.type.size();
    for (const PressureLevelField& f : s.levelFields)
        n += sizeof(float) * f.values.size();
    return n;
}

}  // namespace

InputFormat detectFormat(const std::string& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw IngestError(IngestErrorKind::Io, path, "", "", "is a directory");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f)
        throw IngestError(IngestErrorKind::Io, path, "", "", std::string("cannot open: ") + std::strerror(errno));
    std::vector<uint8_t> head(4096);
    head.resize(std::fread(head.data(), 1, head.size(), f.get()));
    if (head.empty())
        throw IngestError(IngestErrorKind::NotRecognized, path, "", "", "empty file (0 bytes)");
    if (startsWith(head, "CDF\x01", 4) || startsWith(head, "CDF\x02", 4) || startsWith(head, "CDF\x05", 4) ||
        startsWith(head, "\x89HDF\r\n\x1A\n", 8))
        return InputFormat::NetCdf;
    static const char kGrib[] = "GRIB";
    if (std::search(head.begin(), head.end(), kGrib, kGrib + 4) != head.end())
        return InputFormat::Grib;
    throw IngestError(IngestErrorKind::NotRecognized, path, "", "",
                      "neither GRIB nor NetCDF: looks like " + looksLike(head));
}

ConvertResult convertFiles(const std::vector<std::string>& paths, const MappingOptions& options,
                           const ProgressFn& progress)
{
    ConvertResult result;
    uint64_t inputBytes = 0;
    for (const std::string& path : paths)
    {
        std::error_code ec;
        const uintmax_t bytes = std::filesystem::file_size(path, ec);
        inputBytes += ec ? 0 : uint64_t(bytes);
    }
    const AmplificationGuard guard(options, inputBytes);
    uint64_t decodedBytes = 0, outputBytes = 0;
    std::deque<std::vector<GribRecord>> gribFiles;  // deque: pointers into it stay valid
    GribGridCache grids;
    const double perFile = 0.9 / double(std::max<size_t>(paths.size(), 1));
    for (size_t fi = 0; fi < paths.size(); ++fi)
    {
        const std::string& path = paths[fi];
        const ProgressFn fileProgress = [&](double fraction, const std::string& stage) {
            if (progress)
                progress(double(fi) * perFile + fraction * perFile,
                         std::filesystem::path(path).filename().string() + ": " + stage);
        };
        if (detectFormat(path) == InputFormat::Grib)
        {
            GribFile file(path);
            // One message is at most kMaxSnapshotCells values; the sum over messages is guarded here.
            try
            {
                gribFiles.push_back(readGribRecords(file, guard.maxCells(decodedBytes), fileProgress, grids));
            }
            catch (const IngestError& e)
            {
                if (e.kind() != IngestErrorKind::TooLarge || options.allowLargeOutput)
                    throw;
                throw IngestError(IngestErrorKind::TooLarge, path, "", "",
                                  std::string(e.what()) + " (decoding is limited by the input's size; pass "
                                                          "--allow-large-output if that is expected)");
            }
            for (const GribRecord& r : gribFiles.back())
                decodedBytes += r.field.values.size() * sizeof(float);
            guard.check(decodedBytes, "decoding " + path + " takes", path);
        }
        else
        {
            const NcFile file(path);
            std::vector<WeatherSnapshot> s = mapWrfFile(file, options, result.warnings, fileProgress);
            for (WeatherSnapshot& w : s)
            {
                outputBytes += payloadBytes(w);
                result.snapshots.push_back(std::move(w));
            }
            guard.check(outputBytes, "the snapshot file would take", path);
        }
    }
    std::map<int64_t, std::vector<const GribRecord*>> byTime;
    for (const std::vector<GribRecord>& records : gribFiles)
        for (const GribRecord& r : records)
            byTime[r.info.validTimeUnixS].push_back(&r);
    size_t done = 0;
    for (const auto& [time, records] : byTime)
    {
        if (progress)
            progress(0.9 + 0.1 * double(done++) / double(byTime.size()), "mapping " + formatIso8601Utc(time));
        result.snapshots.push_back(mapTime(records, options, result.warnings));
        outputBytes += payloadBytes(result.snapshots.back());
        guard.check(outputBytes, "the snapshot file would take", paths.front());
    }
    std::stable_sort(result.snapshots.begin(), result.snapshots.end(),
                     [](const WeatherSnapshot& a, const WeatherSnapshot& b) { return a.validTimeUnixS < b.validTimeUnixS; });
    for (size_t i = 0; i < result.snapshots.size(); ++i)
    {
        std::string error;
        if (!validateSnapshot(result.snapshots[i], error))
            throw IngestError(IngestErrorKind::BadValues, paths.front(), "snapshot " + formatIso8601Utc(result.snapshots[i].validTimeUnixS),
                              "", error);
        if (i > 0 && result.snapshots[i].validTimeUnixS == result.snapshots[i - 1].validTimeUnixS)
            throw IngestError(IngestErrorKind::BadValues, paths.front(), "", "",
                              "two inputs give the valid time " + formatIso8601Utc(result.snapshots[i].validTimeUnixS) +
                                  "; convert them separately");
    }
    if (result.snapshots.empty())
        throw IngestError(IngestErrorKind::MissingFields, paths.empty() ? "" : paths.front(), "", "",
                          "no snapshot could be made");
    if (progress)
        progress(1.0, "done");
    return result;
}

namespace
{

std::string describeGrib(const std::string& path)
{
    GribFile file(path);
    GribMessage m;
    std::map<std::string, int> grids, times, editions, mappings;
    std::map<GribRole, std::vector<GribMessageInfo>> used;
    std::map<std::string, int> unused;
    int count = 0;
    while (file.next(m))
    {
        const GribMessageInfo& info = m.info();
        ++count;
        ++grids[info.gridDescription];
        ++times[formatIso8601Utc(info.validTimeUnixS)];
        ++editions["GRIB" + std::to_string(info.edition)];
        ++mappings[mappingName(info.centre, info.gridType)];
        if (const auto row = gribRoleOf(info))
            used[row->role].push_back(info);
        else
            ++unused[info.shortName + "/" + info.typeOfLevel];
    }
    if (count == 0)
        throw IngestError(IngestErrorKind::NotRecognized, path, "", "", "no GRIB message found");
    std::string s = "file:        " + path + "\nformat:      ";
    for (const auto& [e, n] : editions)
        s += e + " (" + std::to_string(n) + " messages) ";
    s += "\ngrids:\n";
    for (const auto& [g, n] : grids)
        s += "  " + g + "  [" + std::to_string(n) + " messages]" +
             (g.rfind("regular_ll", 0) == 0 ? "" : "  (resampled to a regular lat/lon grid)") + "\n";
    s += "mapping:     ";
    for (const auto& [name, n] : mappings)
        s += name + " names [" + std::to_string(n) + " messages]  ";
    s += "\n";
    s += "valid times:\n";
    for (const auto& [t, n] : times)
        s += "  " + t + "  [" + std::to_string(n) + " messages]\n";
    s += "fields used:\n";
    for (const auto& [role, infos] : used)
    {
        const std::optional<GribRoleRow> row = gribRoleOf(infos.front());
        char line[400];
        if (isLevelRole(role))
        {
            long lo = infos.front().level, hi = lo;
            for (const GribMessageInfo& i : infos)
            {
                lo = std::min(lo, i.level);
                hi = std::max(hi, i.level);
            }
            std::snprintf(line, sizeof line, "  %-26s %2zu levels %ld..%ld %s: %s -> %s\n",
                          (infos.front().shortName + "/" + infos.front().typeOfLevel).c_str(), infos.size(), lo, hi,
                          infos.front().typeOfLevel == "isobaricInPa" ? "Pa" : "hPa", row->meaning, row->target);
        }
        else
        {
            std::snprintf(line, sizeof line, "  %-26s message %d: %s -> %s\n",
                          (infos.front().shortName + "/" + infos.front().typeOfLevel).c_str(), infos.front().number,
                          row->meaning, row->target);
        }
        s += line;
    }
    s += "not found (used when present):\n";
    std::set<GribRole> listed;
    for (const GribRoleRow& row : gribRoleTable())
    {
        if (used.count(row.role) || listed.count(row.role))
            continue;
        listed.insert(row.role);
        s += std::string("  ") + row.meaning + " [" + row.source + ": " + row.shortNames + " on " + row.typeOfLevels +
             "]\n";
    }
    s += "not used: " + std::to_string(count - int([&] { size_t n = 0; for (auto& [r, v] : used) n += v.size(); return n; }())) +
         " messages (";
    size_t shown = 0;
    for (const auto& [name, n] : unused)
        if (shown++ < 12)
            s += (shown > 1 ? ", " : "") + name;
    s += unused.size() > 12 ? ", ...)\n" : ")\n";
    if (used.empty())
        s += "=> no cloud field: `convert` will fail with exit code 7\n";
    return s;
}

std::string describeNetCdf(const std::string& path)
{
    const NcFile f(path);
    std::string s = "file:        " + path + "\nformat:      " + f.formatName() + "\n";
    const std::vector<std::string> names = f.variableNames();
    s += "variables:   " + std::to_string(names.size()) + "\n";
    std::string missing;
    for (const char* v : kWrfRequired)
        if (!f.hasVariable(v))
            missing += std::string(missing.empty() ? "" : ", ") + v;
    if (!missing.empty())
    {
        s += "model:       not WRF output (missing " + missing + ")\n";
        s += "=> `convert` will fail with exit code 7: no supported variables\n";
        return s;
    }
    const NcFile::Variable q = f.variable("QCLOUD");
    s += "model:       WRF";
    if (q.shape.size() == 4)
        s += ", " + std::to_string(q.shape[3]) + " x " + std::to_string(q.shape[2]) + " columns, " +
             std::to_string(q.shape[1]) + " levels";
    const std::optional<double> proj = f.globalNumber("MAP_PROJ");
    const char* projNames[] = {"?", "Lambert conformal", "polar stereographic", "Mercator"};
    if (proj && *proj >= 1 && *proj <= 3)
        s += std::string(", ") + projNames[int(*proj)] + " projection";
    s += "\nvalid times:\n";
    for (const std::string& t : f.readStrings("Times"))
        s += "  " + t + "\n";
    s += "variables used:\n";
    const std::pair<const char*, const char*> uses[] = {
        {"XLAT", "latitude of columns -> resampling onto a regular lat/lon grid"},
        {"XLONG", "longitude of columns -> resampling"},
        {"PH", "perturbation geopotential -> level heights (PH+PHB)/g"},
        {"PHB", "base geopotential -> level heights"},
        {"QCLOUD", "cloud water -> cloudy levels, layer base/top/coverage"},
        {"QICE", "cloud ice -> cloudy levels"},
        {"QRAIN", "rain water -> water path (coverage)"},
        {"U", "x-wind (staggered) -> layer winds"},
        {"V", "y-wind (staggered) -> layer winds"},
        {"P", "perturbation pressure -> air density"},
        {"PB", "base pressure -> air density"},
        {"T", "perturbation potential temperature -> air density"},
        {"RAINC", "accumulated convective precipitation -> convective rate"},
        {"RAINSH", "accumulated shallow-cumulus precipitation -> convective rate"},
        {"RAINNC", "accumulated grid-scale precipitation -> large-scale rate"},
        {"COSALPHA", "grid rotation -> earth-relative winds"},
        {"SINALPHA", "grid rotation -> earth-relative winds"}};
    std::string absent;
    for (const auto& [name, use] : uses)
    {
        if (f.hasVariable(name))
        {
            char line[200];
            std::snprintf(line, sizeof line, "  %-9s %s\n", name, use);
            s += line;
        }
        else
        {
            absent += std::string(absent.empty() ? "" : ", ") + name;
        }
    }
    s += "not found (used when present): " + (absent.empty() ? std::string("none") : absent) + "\n";
    return s;
}

}  // namespace

std::string describeFile(const std::string& path)
{
    return detectFormat(path) == InputFormat::Grib ? describeGrib(path) : describeNetCdf(path);
}

}  // namespace sky
