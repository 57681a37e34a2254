// SPDX-License-Identifier: MIT
// Writes the fuzzers' seed corpora into <dir>/snapshot and <dir>/grib (small inputs that reach deep).
#include "weather_ingest/grib_writer.h"
#include "weather_ingest/snapshot_file.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

int main(int argc, char** argv)
{
    if (argc != 2)
        return 2;
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir / "snapshot");
    std::filesystem::create_directories(dir / "grib");

    sky::WeatherSnapshot s;
    s.grid = {.lat0Deg = 10, .lon0Deg = 0, .dLatDeg = -1, .dLonDeg = 1, .nLat = 2, .nLon = 3};
    s.validTimeUnixS = 1000;
    s.layers.resize(1);
    s.layers[0].name = "low";
    s.layers[0].coverage = {0.1f, 0.5f, NAN, 1.0f, 0.0f, 0.2f};
    s.layers[0].type = {9, 9, 0, 10, 0, 7};
    s.high.altitudeM.assign(6, 9000.0f);
    s.provenance["x"] = "seed";
    std::string error;
    sky::WeatherSnapshot s2 = s;
    s2.validTimeUnixS = 4600;
    if (!sky::writeSnapshotFile((dir / "snapshot" / "two.skywx").string(), {s, s2}, error) ||
        !sky::writeSnapshotFile((dir / "snapshot" / "one.skywx").string(), {s}, error))
    {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }

    const sky::LatLonGrid g{.lat0Deg = 60, .lon0Deg = -10, .dLatDeg = -10, .dLonDeg = 10, .nLat = 3, .nLon = 4};
    const auto field = [&](const char* typeOfLevel, const char* shortName, double value, const char* level = "0") {
        sky::GribOutField f;
        f.keys = {{"centre", "kwbc"}, {"typeOfLevel", typeOfLevel}, {"level", level}, {"shortName", shortName}};
        f.grid = g;
        f.values.assign(g.cellCount(), value);
        f.values[1] = NAN;  // a bitmap
        return f;
    };
    sky::writeGribFile((dir / "grib" / "gfs.grib2").string(),
                       {field("lowCloudLayer", "tcc", 50), field("lowCloudBottom", "pres", 90000),
                        field("lowCloudTop", "pres", 80000), field("isobaricInhPa", "gh", 1500, "850"),
                        field("isobaricInhPa", "u", 10, "850"), field("surface", "cape", 800)});
    sky::GribOutField e;
    e.sample = "regular_ll_sfc_grib1";
    e.keys = {{"centre", "ecmf"}, {"shortName", "lcc"}};
    e.grid = g;
    e.jScansPositively = true;
    e.values.assign(g.cellCount(), 0.4);
    sky::writeGribFile((dir / "grib" / "ecmwf.grib1").string(), {e});
    return 0;
}
