// SPDX-License-Identifier: MIT
// Small helpers shared by the ingest tests: a synthetic snapshot and temporary paths.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace sky::test
{

/// A fresh per-test temporary folder + name (removed/recreated by each test that calls it).
inline std::string tempPath(const std::string& name)
{
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "sky-ingest-tests" /
                                (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

inline std::vector<uint8_t> readBytes(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes)
{
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

/// A 3 x 4 grid with two layers and high cloud; coverage of layer "middle" is `coverage` everywhere.
inline WeatherSnapshot makeSnapshot(int64_t timeUnixS, float coverage)
{
    WeatherSnapshot s;
    s.grid = {.lat0Deg = 50, .lon0Deg = -10, .dLatDeg = -1, .dLonDeg = 2, .nLat = 3, .nLon = 4};
    s.validTimeUnixS = timeUnixS;
    const size_t n = s.grid.cellCount();
    for (const char* name : {"low", "middle"})
    {
        CloudLayerFields l;
        l.name = name;
        l.coverage.assign(n, coverage);
        l.baseAltitudeM.assign(n, 1000.0f + coverage * 1000.0f);
        l.baseAltitudeM[5] = NAN;
        l.topAltitudeM.assign(n, 3000.0f);
        l.type.assign(n, uint8_t(CloudType::Stratocumulus));
        l.precipitationMmH.assign(n, coverage * 2.0f);
        l.windEastMS.assign(n, 10.0f * coverage);
        l.windNorthMS.assign(n, -5.0f);
        s.layers.push_back(l);
    }
    s.layers[0].coverage[0] = 0.1f;
    s.high.coverage.assign(n, 0.3f);
    s.high.altitudeM.assign(n, 9000.0f);
    s.high.type.assign(n, uint8_t(CloudType::Cirrus));
    s.high.windEastMS.assign(n, 30.0f);
    s.high.windNorthMS.assign(n, 0.0f);
    s.capeJKg.assign(n, 100.0f);
    s.provenance["layers/0/coverage"] = "synthetic";
    return s;
}

}  // namespace sky::test
