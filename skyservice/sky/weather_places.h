// SPDX-License-Identifier: MIT
// Places in a weather snapshot where the weather is of a given kind: a low deck, a convective area,
// clear sky. The real-data GPU tests and the showcase pick their views from real model data
// with it, so that nobody hard-codes coordinates that only fit one file.
//
// Layers are read by their snapshot index as sky-ingest writes them (weather_ingest/README.md
// "Snapshot layers"): 0 low, 1 middle, 2 convective, plus the 2D high layer. NaN coverage counts as
// unknown, never as clear.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <cstdint>
#include <string>

namespace sky
{

enum class PlaceKind
{
    LowDeck,    ///< low-layer coverage > 80 % at the cell, as much as possible around it
    Convective, ///< the most convective cell: convective coverage, cumulonimbus type, CAPE
    Clear,      ///< every layer (low, middle, convective, high) at 0 % in the widest ring of cells
};

/// What to accept.
struct PlaceFilter
{
    double maxAbsLatDeg = 70.0;        ///< ignore cells nearer the poles than this (degrees)
    double minSunElevationDeg = -90.0; ///< at the snapshot's valid time (degrees); -90 accepts night
};

/// One chosen cell and what the snapshot says there.
struct WeatherPlace
{
    bool found = false;
    double latDeg = 0, lonDeg = 0;     ///< cell centre (degrees; longitude in [-180, 180))
    uint32_t iLat = 0, iLon = 0;       ///< grid indices
    double score = 0;                  ///< the kind's ranking value (larger is better)
    float coverage[4] = {};            ///< low, middle, convective, high (fraction; NaN unknown)
    float baseM[3] = {}, topM[3] = {}; ///< low, middle, convective base and top (m above the ellipsoid; NaN none)
    float highAltitudeM = 0;           ///< high layer altitude (m; NaN none)
    uint8_t type[4] = {};              ///< CloudType per layer (low, middle, convective, high)
    float capeJKg = 0;                 ///< NaN when the snapshot has none
    double sunElevationDeg = 0;        ///< at the valid time (degrees)
};

/**
 * Find the best cell of a kind.
 *
 * @param[in] snapshot the weather (at least 3 volumetric layers for LowDeck and Convective).
 * @param[in] kind what to look for (see PlaceKind for the ranking).
 * @param[in] filter which cells may be chosen.
 * @return the best cell, or found = false when no cell qualifies. Ties go to the first cell in grid
 *   order, so the choice is deterministic.
 *
 * Rankings: LowDeck: the smallest low coverage over the 3x3 cells around a cell whose own low coverage
 * exceeds 0.8 and whose base is known, + 0.1 x (1 - the larger of the middle and high coverage there).
 * Convective: convective coverage + 1 for a cumulonimbus
 * + min(CAPE / 2000 J/kg, 1). Clear: how many rings of neighbours (0..4) are also clear everywhere.
 **********************************************************************/
WeatherPlace findWeatherPlace(const WeatherSnapshot& snapshot, PlaceKind kind, const PlaceFilter& filter = {});

/// One line for logs and captions: "48.0N 22.5W: low 95% (stratus, 310-900 m), middle 0%, ...".
std::string describeWeatherPlace(const WeatherPlace& place);

/// Latitude and longitude as a short name, e.g. "48.0N 22.5W".
std::string formatLatLon(double latDeg, double lonDeg);

}  // namespace sky
