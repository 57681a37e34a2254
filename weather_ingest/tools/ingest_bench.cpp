// SPDX-License-Identifier: MIT
// sky-ingest-bench: the ingest speed benchmark (README "Speed"). Writes a global 0.25° (1440 x 721)
// GFS-like GRIB2 file with ecCodes, regridded bilinearly from the 2.5° sample's fields that the mapping
// uses, then times `sky-ingest convert` on it in a child process (wall time and peak RSS from wait4) and
// the snapshot load. With --grid hrrr it writes instead an HRRR-sized Lambert conformal file (1799 x 1059
// at 3 km, the CONUS grid's keys, 40 messages of the fields the HRRR mapping uses, smooth synthetic values,
// grid-relative winds) and times its conversion. Not a test: timings depend on the machine.
#include "weather_ingest/grib_fields.h"
#include "weather_ingest/grib_writer.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/snapshot_file.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Writes the 0.25° input; returns the number of fields written.
size_t writeInput(const std::string& samplePath, const std::string& out, const std::string& packing)
{
    const std::set<long> levels = {1000, 850, 700, 500, 300, 200};  // enough for log-p heights and winds
    const sky::LatLonGrid target{.lat0Deg = 90, .lon0Deg = 0, .dLatDeg = -0.25, .dLonDeg = 0.25, .nLat = 721, .nLon = 1440};
    sky::GribFile file(samplePath);
    sky::GribMessage m;
    std::vector<sky::GribOutField> fields;
    while (file.next(m))
    {
        const sky::GribMessageInfo& info = m.info();
        const auto row = sky::gribRoleOf(info);
        if (!row || row->role == sky::GribRole::LevelCloudMixingRatio)
            continue;
        if (sky::isLevelRole(row->role) && !levels.count(info.level))
            continue;
        const sky::GridField source = m.decode(1u << 24);
        sky::GribOutField f;
        f.keys = {{"centre", "kwbc"}, {"dataDate", "20110110"}, {"dataTime", "1200"}, {"step", "120"},
                  {"typeOfLevel", info.typeOfLevel}, {"level", std::to_string(info.level)}, {"shortName", info.shortName}};
        f.grid = target;
        f.packingType = packing;
        f.bitsPerValue = 16;
        f.values.resize(target.cellCount());
        for (uint32_t r = 0; r < target.nLat; ++r)
            for (uint32_t c = 0; c < target.nLon; ++c)
            {
                const sky::GridPoint p =
                    source.grid.locate(target.lat0Deg + r * target.dLatDeg, target.lon0Deg + c * target.dLonDeg);
                f.values[target.index(r, c)] = p.inside ? source.grid.sample(source.values, p) : NAN;
            }
        fields.push_back(std::move(f));
    }
    sky::writeGribFile(out, fields);
    return fields.size();
}

/// Writes the HRRR-like Lambert input; returns the number of fields written.
size_t writeHrrrInput(const std::string& out)
{
    constexpr long kNx = 1799, kNy = 1059;
    const std::vector<std::pair<std::string, std::string>> grid = {{"gridType", "lambert"},
                                                                   {"Nx", "1799"},
                                                                   {"Ny", "1059"},
                                                                   {"DxInMetres", "3000"},
                                                                   {"DyInMetres", "3000"},
                                                                   {"LaDInDegrees", "38.5"},
                                                                   {"LoVInDegrees", "262.5"},
                                                                   {"Latin1InDegrees", "38.5"},
                                                                   {"Latin2InDegrees", "38.5"},
                                                                   {"latitudeOfFirstGridPointInDegrees", "21.138123"},
                                                                   {"longitudeOfFirstGridPointInDegrees", "237.280472"},
                                                                   {"iScansNegatively", "0"},
                                                                   {"jScansPositively", "1"}};
    struct Spec
    {
        const char* shortName;
        const char* typeOfLevel;
        long level;
        double base, amplitude;
    };
    std::vector<Spec> specs = {{"lcc", "lowCloudLayer", 0, 40, 40},     {"mcc", "middleCloudLayer", 0, 30, 30},
                               {"hcc", "highCloudLayer", 0, 50, 45},    {"tcc", "entireAtmosphere", 0, 60, 40},
                               {"gh", "cloudBase", 0, 1500, 800},       {"gh", "cloudCeiling", 0, 2000, 900},
                               {"gh", "cloudTop", 0, 6000, 3000},       {"cape", "surface", 0, 800, 700},
                               {"prate", "surface", 0, 0.0004, 0.0004}, {"vis", "surface", 0, 20000, 15000}};
    const long levels[] = {1000, 925, 850, 700, 600, 500, 400, 300, 250, 200};
    for (const long hPa : levels)
    {
        const double z = 44330.8 * (1.0 - std::pow(double(hPa) / 1013.25, 0.190263)); // ICAO, for plausible gh
        specs.push_back({"gh", "isobaricInhPa", hPa, z, 50});
        specs.push_back({"u", "isobaricInhPa", hPa, 10 + 0.002 * z, 10});
        specs.push_back({"v", "isobaricInhPa", hPa, 2, 8});
    }
    const std::string part = out + ".part";
    std::FILE* dst = std::fopen(out.c_str(), "wb");
    if (!dst)
        throw sky::IngestError(sky::IngestErrorKind::Output, out, "", "", "cannot create");
    for (size_t n = 0; n < specs.size(); ++n)
    {
        const Spec& sp = specs[n];
        sky::GribOutField f;
        f.keys = {{"centre", "kwbc"},
                  {"dataDate", "20240301"},
                  {"dataTime", "1200"},
                  {"typeOfLevel", sp.typeOfLevel},
                  {"level", std::to_string(sp.level)},
                  {"shortName", sp.shortName}};
        f.keys.insert(f.keys.end(), grid.begin(), grid.end());
        if (sp.shortName == std::string("u") || sp.shortName == std::string("v"))
            f.keys.push_back({"uvRelativeToGrid", "1"});
        f.values.resize(size_t(kNx * kNy));
        for (long j = 0; j < kNy; ++j)
            for (long i = 0; i < kNx; ++i)
                f.values[size_t(j * kNx + i)] =
                    sp.base + sp.amplitude * std::sin(double(i) * 0.011 + double(n)) * std::cos(double(j) * 0.017);
        sky::writeGribFile(part, {f});
        std::FILE* src = std::fopen(part.c_str(), "rb");
        char buf[1 << 16];
        size_t got = 0;
        while (src && (got = std::fread(buf, 1, sizeof buf, src)) > 0)
            std::fwrite(buf, 1, got, dst);
        if (src)
            std::fclose(src);
    }
    std::fclose(dst);
    std::remove(part.c_str());
    return specs.size();
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"sky-ingest-bench: time sky-ingest convert on a global 0.25 degree GFS-like file"};
    std::string sample = std::string(SKY_SHARED_DIR) + "/weather/gfs-2p5deg-20110110-12z-f120.grib2";
    std::string work = "/tmp/sky-ingest-bench";
    std::string tool = (std::filesystem::path(argv[0]).parent_path() / "sky-ingest").string();
    std::string packing = "grid_simple";
    std::string gridKind = "gfs";
    app.add_option("--sample", sample, "2.5 degree GFS sample to regrid");
    app.add_option("--workdir", work, "where the input and snapshot go");
    app.add_option("--sky-ingest", tool, "sky-ingest executable to time");
    app.add_option("--packing", packing, "GRIB2 packing of the input (grid_simple, grid_complex_spatial_differencing, ...)");
    app.add_option("--grid", gridKind,
                   "gfs: global 0.25 degree regular grid; hrrr: 1799 x 1059 Lambert conformal at 3 km")
        ->check(CLI::IsMember({"gfs", "hrrr"}));
    CLI11_PARSE(app, argc, argv);
    try
    {
        std::filesystem::create_directories(work);
        const bool hrrr = gridKind == "hrrr";
        const std::string input = hrrr ? work + "/hrrr-lambert-3km.grib2" : work + "/gfs-0p25-" + packing + ".grib2";
        const std::string output = work + (hrrr ? "/hrrr.skywx" : "/gfs-0p25.skywx");
        const auto t0 = Clock::now();
        const size_t nFields = hrrr ? writeHrrrInput(input) : writeInput(sample, input, packing);
        const double pointsPerField = hrrr ? 1799.0 * 1059.0 : 1440.0 * 721.0;
        std::printf("input: %s, %zu fields, %.1f MB, written in %.1f s\n", input.c_str(), nFields,
                    double(std::filesystem::file_size(input)) / 1e6, secondsSince(t0));

        const auto t1 = Clock::now();
        const pid_t pid = fork();
        if (pid == 0)
        {
            execl(tool.c_str(), tool.c_str(), "convert", "--quiet", input.c_str(), "-o", output.c_str(), nullptr);
            _exit(127);
        }
        int status = 0;
        rusage usage = {};
        wait4(pid, &status, 0, &usage);
        const double wallS = secondsSince(t1);
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        {
            std::fprintf(stderr, "sky-ingest convert failed (status %d)\n", status);
            return 1;
        }
        const double cpuS = double(usage.ru_utime.tv_sec) + double(usage.ru_utime.tv_usec) * 1e-6 +
                            double(usage.ru_stime.tv_sec) + double(usage.ru_stime.tv_usec) * 1e-6;
        const double peakMb = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
        const double decodedMb = double(nFields) * pointsPerField * 4.0 / (1024.0 * 1024.0);

        double loadS = 1e9;
        std::vector<sky::WeatherSnapshot> snapshots;
        for (int i = 0; i < 3; ++i)
        {
            std::string error;
            const auto t2 = Clock::now();
            if (!sky::readSnapshotFile(output, snapshots, error))
            {
                std::fprintf(stderr, "%s\n", error.c_str());
                return 1;
            }
            loadS = std::min(loadS, secondsSince(t2));
        }
        std::printf("convert: %.2f s wall, %.2f s CPU, peak RSS %.0f MiB = %.1f x the %.0f MiB of decoded fields "
                    "(float32)\n",
                    wallS, cpuS, peakMb, peakMb / decodedMb, decodedMb);
        std::printf("snapshot: %.1f MB, loads in %.0f ms\n", double(std::filesystem::file_size(output)) / 1e6,
                    loadS * 1e3);
        std::printf("{\"fields\":%zu,\"convertWallS\":%.3f,\"convertCpuS\":%.3f,\"peakRssMiB\":%.1f,\"decodedMiB\":%.1f,"
                    "\"snapshotLoadMs\":%.1f}\n",
                    nFields, wallS, cpuS, peakMb, decodedMb, loadS * 1e3);
    }
    catch (const sky::IngestError& e)
    {
        std::fprintf(stderr, "sky-ingest-bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
