// SPDX-License-Identifier: MIT
// --weather builtin|FILE: the built-in scene, or a snapshot file (sky-ingest convert) sampled at a time.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <string>

namespace sky
{

/// @param[in] source "builtin" or the path of a snapshot file.
/// @param[in] unixTimeS the time to sample a multi-time snapshot file at (s since 1970, UTC).
/// @param[out] out the weather. @param[out] error why the file was refused.
bool loadWeatherSource(const std::string& source, int64_t unixTimeS, WeatherSnapshot& out, std::string& error);

}  // namespace sky
