// SPDX-License-Identifier: MIT
// sky-ingest: inspect weather model files and convert them to weather snapshots (README "sky-ingest").
#include "progress_bar.h"

#include "weather_ingest/civil_time.h"
#include "weather_ingest/cloud_type_rules.h"
#include "weather_ingest/ingest.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/snapshot_file.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>

namespace
{

constexpr int kExitInternal = 1;
constexpr int kExitUsage = 2;

int runInfo(const std::vector<std::string>& files, bool rules)
{
    int rc = 0;
    for (const std::string& f : files)
    {
        try
        {
            std::printf("%s\n", sky::describeFile(f).c_str());
        }
        catch (const sky::IngestError& e)
        {
            std::fprintf(stderr, "sky-ingest: error: %s\n", e.what());
            rc = rc ? rc : sky::exitCodeFor(e.kind());
        }
    }
    if (rules)
        std::printf("cloud-type rules (first match wins):\n%s", sky::cloudTypeRulesMarkdown().c_str());
    return rc;
}

int runConvert(const std::vector<std::string>& files, const std::string& output, bool quiet,
               const sky::MappingOptions& options)
{
    sky::ProgressBar bar(!quiet);
    const sky::ConvertResult result =
        sky::convertFiles(files, options, [&](double f, const std::string& stage) { bar.update(f, stage); });
    bar.update(1.0, "writing " + output);
    std::string error;
    if (!sky::writeSnapshotFile(output, result.snapshots, error))
        throw sky::IngestError(sky::IngestErrorKind::Output, output, "", "", error);
    bar.clear();
    for (const std::string& w : result.warnings)
        std::fprintf(stderr, "sky-ingest: warning: %s\n", w.c_str());
    if (!quiet)
    {
        const sky::LatLonGrid& g = result.snapshots.front().grid;
        std::printf("wrote %s: %zu snapshot(s), %u x %u grid, %s .. %s\n", output.c_str(), result.snapshots.size(),
                    g.nLon, g.nLat, sky::formatIso8601Utc(result.snapshots.front().validTimeUnixS).c_str(),
                    sky::formatIso8601Utc(result.snapshots.back().validTimeUnixS).c_str());
    }
    return 0;
}

/// Mean of the finite values and the fraction of cells with cloud (for check's summary).
void coverageStats(const std::vector<float>& v, double& mean, double& cloudy)
{
    double sum = 0;
    size_t n = 0, c = 0;
    for (float x : v)
        if (std::isfinite(x))
        {
            sum += double(x);
            ++n;
            c += x >= sky::kMinCloudCoverage ? 1u : 0u;
        }
    mean = n ? sum / double(n) : 0;
    cloudy = v.empty() ? 0 : double(c) / double(v.size());
}

int runCheck(const std::string& path, bool quiet)
{
    std::vector<sky::WeatherSnapshot> snapshots;
    std::string error;
    if (!sky::readSnapshotFile(path, snapshots, error))
    {
        std::fprintf(stderr, "sky-ingest: error: %s\n", error.c_str());
        return sky::exitCodeFor(sky::IngestErrorKind::Corrupt);
    }
    if (quiet)
        return 0;
    std::printf("%s: valid snapshot file, format version %u, %zu snapshot(s)\n", path.c_str(),
                sky::kSnapshotFormatVersion, snapshots.size());
    for (const sky::WeatherSnapshot& s : snapshots)
    {
        const sky::LatLonGrid& g = s.grid;
        std::printf("  %s  grid %u x %u from (%g, %g) step (%g, %g)\n", sky::formatIso8601Utc(s.validTimeUnixS).c_str(), g.nLon,
                    g.nLat, g.lat0Deg, g.lon0Deg, g.dLatDeg, g.dLonDeg);
        for (const sky::CloudLayerFields& l : s.layers)
        {
            double mean = 0, cloudy = 0;
            coverageStats(l.coverage, mean, cloudy);
            std::printf("    layer %-10s mean coverage %5.1f %%, cloudy cells %5.1f %%\n", l.name.c_str(), mean * 100,
                        cloudy * 100);
        }
        double mean = 0, cloudy = 0;
        coverageStats(s.high.coverage, mean, cloudy);
        std::printf("    high             mean coverage %5.1f %%, cloudy cells %5.1f %%\n", mean * 100, cloudy * 100);
        std::printf("    cape %s, tropopause %s, 3D fields %zu, provenance entries %zu\n",
                    s.capeJKg.empty() ? "absent" : "present", s.tropopauseAltitudeM.empty() ? "absent" : "present",
                    s.levelFields.size(), s.provenance.size());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"sky-ingest: inspect GRIB/NetCDF weather files and convert them to sky weather snapshots.\n"
                 "Exit codes: 0 ok, 1 internal error, 2 usage, 3 unreadable input, 4 not GRIB/NetCDF, 5 corrupt,\n"
                 "6 unsupported or absurd grid, 7 no usable fields, 8 bad values, 9 output not written."};
    app.require_subcommand(1);
    std::vector<std::string> files;
    std::string output;
    bool quiet = false, rules = false;
    sky::MappingOptions options;
    CLI::App* info = app.add_subcommand("info", "Print the inventory of weather files: grid, times, fields and mapping");
    info->add_option("FILE", files, "GRIB1/GRIB2 or NetCDF files")->required();
    info->add_flag("--rules", rules, "Also print the cloud-type rule table");
    CLI::App* convert = app.add_subcommand("convert", "Convert weather files into one snapshot file");
    convert->add_option("FILE", files, "GRIB1/GRIB2 or NetCDF files (mixed allowed)")->required();
    convert->add_option("-o,--output", output, "Snapshot file to write (atomically)")->required();
    convert->add_flag("-q,--quiet", quiet, "No progress bar and no summary");
    convert->add_flag("--lenient", options.lenient, "Repair bad values (clamp, swap, drop) with warnings");
    convert->add_flag("--with-3d", options.keepLevelFields, "Keep cloud mixing ratio / cover on pressure levels");
    convert->add_flag("--allow-large-output", options.allowLargeOutput,
                      "Allow decoded fields or output over max(64 MiB, 100 x the input's size)");
    CLI::App* check = app.add_subcommand("check", "Verify a snapshot file (checksum, structure) and summarise it");
    check->add_option("SNAPSHOT", output, "Snapshot file")->required();
    check->add_flag("-q,--quiet", quiet, "Print only errors");
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
        return app.exit(e) == 0 ? 0 : kExitUsage;
    }
    try
    {
        if (info->parsed())
            return runInfo(files, rules);
        if (convert->parsed())
            return runConvert(files, output, quiet, options);
        return runCheck(output, quiet);
    }
    catch (const sky::IngestError& e)
    {
        std::fprintf(stderr, "\nsky-ingest: error [%s]: %s\n", sky::kindName(e.kind()), e.what());
        return sky::exitCodeFor(e.kind());
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "\nsky-ingest: internal error: %s\n", e.what());
        return kExitInternal;
    }
}
