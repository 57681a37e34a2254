// SPDX-License-Identifier: MIT
// A weather snapshot resampled onto another latitude/longitude grid, for laying a CIGI host's regions over
// a gridded weather (cigi_weather_merge.h): the host's regions need cells of a few km around the ownship,
// a model's grid may have 25 km ones.
//
// The rules are the renderer's (skyservice/weather/weather_window.h), through the same sampler (wrap, edges
// and missing values: LatLonGrid, weather_ingest/lat_lon_grid.h), so a regridded snapshot draws as its
// source does: continuous fields bilinear, cloud type from the nearest cell, a corner whose coverage, base
// or top is missing counts as coverage 0, outside a regional grid the coverage is 0 and the other fields
// take the value at the nearest edge. The source's dataWeight is folded into every coverage (the result has
// none), so a host's weather laid over it is not faded out with the model's domain. Level fields are left
// out (the renderer does not draw them).
#pragma once

#include "weather_ingest/weather_snapshot.h"

namespace sky
{

/// `from` on `to` (see the top of this file).
WeatherSnapshot regridSnapshot(const WeatherSnapshot& from, const LatLonGrid& to);

/// Multiplies every coverage by the snapshot's dataWeight and clears it (the same weather drawn, but a
/// layer written over it later keeps its own coverage).
void foldDataWeight(WeatherSnapshot& w);

} // namespace sky
