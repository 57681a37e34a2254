// SPDX-License-Identifier: MIT
// The built-in weather: a believable procedural scene over south-east France and north-west Italy,
// used when no weather file is loaded and by the showcase views and tests.
//
// Grid: regional, 0.025 degrees, latitude 40..50 N, longitude 0..12 E (401 x 481 cells). Altitudes
// are meters above the WGS84 ellipsoid. Regions are rectangles with 80 km rounded corners and soft
// edges: the coverage fades in over 25 km inside an edge line that value noise (periods 150, 60 and
// 25 km) moves in or out by up to 25 km. Well inside (over 50 km from the nominal edge) the coverage
// varies smoothly within the ranges below; over 25 km outside it is exactly 0. Cloud types are set
// everywhere in a layer (coverage 0 alone means clear), so that nearest-texel type lookups never
// meet "none" at a soft edge.
//
//   layer 0 "low":        stratocumulus deck, coverage 0.86..0.94, 900..1700 m, lon 0.5..4.5 E,
//                         lat 43..48 N; scattered cumulus, coverage 0.36..0.44, 1200..3200 m,
//                         lon 6..11 E, lat 43..47 N; wind 6 m/s from the south-west.
//   layer 1 "middle":     altocumulus, coverage 0.45..0.55, 4500..5200 m, lon 1..5 E, lat 47..49.5 N;
//                         wind 15 m/s from the west-south-west.
//   layer 2 "convective": one cumulonimbus at 45.30 N, 8.50 E: coverage 1 within 3.5 km of the centre,
//                         falling smoothly to 0 at 7.5 km; 1000..11500 m; precipitation 25 mm/h times
//                         the coverage; wind 25 m/s from the west (the anvil is pushed east).
//   high:                 cirrus, coverage 0.42..0.58, 9500 m, lon 3..10 E, lat 44..49 N,
//                         wind 30 m/s from the west-south-west.
//   CAPE 2500 J/kg at the cumulonimbus, falling to 300 J/kg beyond 60 km; tropopause 11500 m.
//   provenance: {"source": "builtin"}.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <cstdint>

namespace sky
{

/// Centre of the cumulonimbus cell (degrees).
inline constexpr double kBuiltinCumulonimbusLatDeg = 45.30;
inline constexpr double kBuiltinCumulonimbusLonDeg = 8.50;
/// Within this distance of the centre the cell's coverage is 1 (meters).
inline constexpr double kBuiltinCumulonimbusCoreRadiusM = 3500.0;
/// Beyond this distance of the centre the cell's coverage is 0 (meters).
inline constexpr double kBuiltinCumulonimbusRadiusM = 7500.0;
inline constexpr float kBuiltinCumulonimbusBaseM = 1000.0f;
inline constexpr float kBuiltinCumulonimbusTopM = 11500.0f;
inline constexpr float kBuiltinCumulonimbusPrecipitationMmH = 25.0f;
inline constexpr float kBuiltinCumulonimbusCapeJKg = 2500.0f;

/// A point well inside the stratocumulus deck (degrees); coverage 0.86..0.94 there.
inline constexpr double kBuiltinDeckLatDeg = 45.50;
inline constexpr double kBuiltinDeckLonDeg = 2.50;
inline constexpr float kBuiltinDeckBaseM = 900.0f;
inline constexpr float kBuiltinDeckTopM = 1700.0f;

/// A point well inside the scattered cumulus field, 80 km from the cumulonimbus (degrees);
/// coverage 0.36..0.44 there.
inline constexpr double kBuiltinCumulusLatDeg = 44.50;
inline constexpr double kBuiltinCumulusLonDeg = 7.50;
inline constexpr float kBuiltinCumulusBaseM = 1200.0f;
inline constexpr float kBuiltinCumulusTopM = 3200.0f;

/// A point well inside the altocumulus patch (degrees); coverage 0.45..0.55 there.
inline constexpr double kBuiltinAltocumulusLatDeg = 48.25;
inline constexpr double kBuiltinAltocumulusLonDeg = 3.00;
inline constexpr float kBuiltinAltocumulusBaseM = 4500.0f;
inline constexpr float kBuiltinAltocumulusTopM = 5200.0f;

/// A point well inside the cirrus sheet (degrees); coverage 0.42..0.58 there.
inline constexpr double kBuiltinCirrusLatDeg = 46.50;
inline constexpr double kBuiltinCirrusLonDeg = 6.50;
inline constexpr float kBuiltinCirrusAltitudeM = 9500.0f;

/// A point under clear sky in every layer (degrees).
inline constexpr double kBuiltinClearLatDeg = 41.00;
inline constexpr double kBuiltinClearLonDeg = 11.50;

inline constexpr float kBuiltinTropopauseM = 11500.0f;
/// CAPE far from the cumulonimbus (J/kg).
inline constexpr float kBuiltinBackgroundCapeJKg = 300.0f;

/**
 * Build the built-in weather scene described above. Deterministic: the same valid time gives the
 * same snapshot bit for bit, and the fields do not depend on the valid time.
 *
 * @param[in] validTimeUnixS valid time to stamp on the snapshot (seconds since 1970-01-01T00:00:00Z).
 * @return the snapshot (3 layers "low", "middle", "convective", plus high cloud).
 **********************************************************************/
WeatherSnapshot makeBuiltinWeather(int64_t validTimeUnixS);

}  // namespace sky
