// SPDX-License-Identifier: MIT
// GridField: one 2D field on a regular latitude/longitude grid, the common currency of the decoders,
// and the few operations the mapping needs on it (sampling: LatLonGrid::sample, lat_lon_grid.h).
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <cstdint>
#include <vector>

namespace sky
{

/// Values on a LatLonGrid (row-major, see weather_snapshot.h); NaN = missing.
struct GridField
{
    LatLonGrid grid;
    std::vector<float> values;
    size_t invalidCount = 0;  ///< NaN/inf values in the data that were not flagged missing (stored as NaN)
};

/// @return true when both grids have the same shape and, within toleranceDeg, the same origin and
///   spacing (longitudes compared modulo 360, so 0..357.5 equals -180..177.5 only if the origins agree).
bool sameGrid(const LatLonGrid& a, const LatLonGrid& b, double toleranceDeg = 1e-6);

}  // namespace sky
