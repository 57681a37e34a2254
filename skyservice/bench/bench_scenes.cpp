// SPDX-License-Identifier: MIT
#include "skyservice/bench/bench_scenes.h"

#include "skyservice/sky/builtin_weather.h"

#include <cmath>

namespace sky
{
namespace
{

// Metres -> degrees of longitude at a latitude (spherical approximation is plenty to place an eye).
double lonOffsetDeg(double metres, double latDeg) { return metres / (111320.0 * std::cos(latDeg * M_PI / 180.0)); }

// 35 000 ft in metres (1 ft = 0.3048 m exactly, international foot).
constexpr double kFl350M = 35000.0 * 0.3048;

// Where the synthetic scenes put the eye: no place in particular, a mid-latitude summer morning.
constexpr double kSyntheticLatDeg = 45.0;
constexpr double kSyntheticLonDeg = 7.0;

WeatherSnapshot globalGrid()
{
    WeatherSnapshot w;
    w.grid = {-90.0, 0.0, 1.0, 1.0, 181, 360};  // 360 columns of 1 degree: wraps at the antimeridian
    w.provenance["source"] = "sky-bench synthetic";
    return w;
}

WeatherSnapshot cirrusSheet()
{
    WeatherSnapshot w = globalGrid();
    size_t n = w.grid.cellCount();
    w.high.coverage.assign(n, 0.5f);
    w.high.altitudeM.assign(n, kBuiltinCirrusAltitudeM);
    w.high.type.assign(n, uint8_t(CloudType::Cirrus));
    w.high.windEastMS.assign(n, 28.0f);
    w.high.windNorthMS.assign(n, 10.0f);
    return w;
}

std::vector<BenchScene> makeScenes()
{
    const double cbLat = kBuiltinCumulonimbusLatDeg, cbLon = kBuiltinCumulonimbusLonDeg;
    const double deckLat = kBuiltinDeckLatDeg, deckLon = kBuiltinDeckLonDeg;
    std::vector<BenchScene> s;
    s.push_back({"clear", "No cloud: sky and ground only, from 1500 m", "2026-06-21T10:00:00Z",
                 {kSyntheticLatDeg, kSyntheticLonDeg, 1500.0, 90.0, 10.0, 0.0}, 60.0, false});
    s.push_back({"scattered-cumulus", "Scattered cumulus at midday from 600 m", "2026-06-21T11:30:00Z",
                 {kBuiltinCumulusLatDeg - 0.35, kBuiltinCumulusLonDeg, 600.0, 10.0, 8.0, 0.0}, 60.0, true});
    s.push_back({"stratocumulus-deck", "Under the stratocumulus deck from 300 m", "2026-06-21T10:00:00Z",
                 {deckLat, deckLon, 300.0, 0.0, 20.0, 0.0}, 60.0, true});
    s.push_back({"cumulonimbus", "Cumulonimbus and anvil from 40 km at 4500 m", "2026-06-21T15:00:00Z",
                 {cbLat, cbLon - lonOffsetDeg(40000.0, cbLat), 4500.0, 90.0, 6.0, 0.0}, 60.0, true});
    s.push_back({"cirrus-only", "A cirrus sheet at 9500 m and nothing below", "2026-06-21T10:00:00Z",
                 {kSyntheticLatDeg, kSyntheticLonDeg, 1500.0, 180.0, 25.0, 0.0}, 60.0, false});
    s.push_back({"inside-cloud", "Inside the stratocumulus deck at 1300 m", "2026-06-21T10:00:00Z",
                 {deckLat, deckLon, 1300.0, 45.0, 0.0, 0.0}, 60.0, true});
    s.push_back({"above-deck-FL350", "The deck from FL350 (10 668 m), looking down 8 deg", "2026-06-21T09:30:00Z",
                 {deckLat, deckLon + 1.0, kFl350M, 250.0, -8.0, 0.0}, 70.0, true});
    s.push_back({"sunset", "Sunset over the stratocumulus deck from 2600 m", "2026-06-21T19:15:00Z",
                 {deckLat, deckLon + 0.6, 2600.0, 300.0, 1.0, 0.0}, 60.0, true});
    return s;
}

}  // namespace

const std::vector<BenchScene>& benchScenes()
{
    static const std::vector<BenchScene> scenes = makeScenes();
    return scenes;
}

bool selectBenchScenes(const std::string& spec, std::vector<BenchScene>& out, std::string& error)
{
    out.clear();
    if (spec == "all")
    {
        out = benchScenes();
        return true;
    }
    size_t start = 0;
    while (start <= spec.size())
    {
        size_t comma = spec.find(',', start);
        std::string name = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        bool found = false;
        for (const BenchScene& scene : benchScenes())
            if (scene.name == name)
            {
                out.push_back(scene);
                found = true;
            }
        if (!found)
        {
            error = "unknown scene \"" + name + "\"; known: all";
            for (const BenchScene& scene : benchScenes())
                error += ", " + scene.name;
            out.clear();
            return false;
        }
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    return !out.empty();
}

WeatherSnapshot makeBenchWeather(const BenchScene& scene, int64_t unixTimeS)
{
    WeatherSnapshot w;
    if (scene.builtinWeather)
        w = makeBuiltinWeather(unixTimeS);
    else if (scene.name == "cirrus-only")
        w = cirrusSheet();
    else
        w = globalGrid();
    w.validTimeUnixS = unixTimeS;
    return w;
}

}  // namespace sky
