// SPDX-License-Identifier: MIT
// The scenes that sky-bench times: each is a weather snapshot, one view and a UTC time.
//
// Most scenes are places in the built-in weather (skyservice/sky/builtin_weather.h) so that the
// distant horizon holds the same mixture of cloud the product shows. Two need a sky the built-in
// scene cannot give anywhere within the 800 km weather window: "clear" (no cloud at all) and
// "cirrus-only" (a high sheet and nothing below), so they use small synthetic snapshots.
#pragma once

#include "skyservice/render/render_types.h"
#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

/// One benchmark scene.
struct BenchScene
{
    std::string name;         ///< command-line name, e.g. "stratocumulus-deck"
    std::string description;  ///< one line for humans (table, JSON, contact sheet)
    std::string timeIso;      ///< UTC time of the view, ISO 8601
    EyePose pose;             ///< where the eye is and where it looks
    double fovYDeg = 60.0;    ///< vertical field of view (degrees)
    bool builtinWeather = true;  ///< true: makeBuiltinWeather(); false: makeBenchWeather(name)
};

/**
 * The eight benchmark scenes, in a fixed order: clear, scattered-cumulus, stratocumulus-deck,
 * cumulonimbus, cirrus-only, inside-cloud, above-deck-FL350, sunset.
 *
 * @return the scenes (poses are valid; times parse with parseIso8601Utc).
 **********************************************************************/
const std::vector<BenchScene>& benchScenes();

/**
 * Select scenes by name.
 *
 * @param[in] spec "all", one scene name, or several names separated by commas.
 * @param[out] out the selected scenes, in the order given (all: the order of benchScenes()).
 * @param[out] error on failure, a message naming the unknown scene and listing the known ones.
 * @return true when every name is known and at least one scene is selected.
 **********************************************************************/
bool selectBenchScenes(const std::string& spec, std::vector<BenchScene>& out, std::string& error);

/**
 * The weather of a scene.
 *
 * @param[in] scene the scene.
 * @param[in] unixTimeS the view time (s since 1970), stamped as the snapshot's valid time so that the
 *   cloud animation is at its origin.
 * @return the built-in weather, or the scene's synthetic snapshot (clear: no layers on a global
 *   1-degree grid; cirrus-only: a uniform cirrus sheet at 9500 m, coverage 0.5, on the same grid).
 **********************************************************************/
WeatherSnapshot makeBenchWeather(const BenchScene& scene, int64_t unixTimeS);

}  // namespace sky
