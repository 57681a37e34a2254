// SPDX-License-Identifier: MIT
// Combining snapshots of one valid time from different grids (a regional model over a global one) into
// one snapshot: the finer grid wins where it has data, blending into the coarser over its soft edge.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <string>
#include <vector>

namespace sky
{

/// Largest grid a composite gets (cells): a global grid at about 0.06°. A composite of a global model
/// and a finer regional one is made at the finest spacing that fits (a warning says when the regional
/// grid is coarsened; convert it alone to keep its resolution).
inline constexpr size_t kMaxCompositeCells = 12u * 1024u * 1024u;

/// Resamples a snapshot onto another grid: continuous fields bilinearly (NaN corners left out), cloud
/// types from the nearest cell, dataWeight 0 outside the source grid.
WeatherSnapshot resampleSnapshot(const WeatherSnapshot& source, const LatLonGrid& target);

/// Combines snapshots of one valid time on different grids.
///
/// @param[in] parts at least one; one part is returned unchanged.
/// @param[in] maxCells largest target grid.
/// @param[out] warnings appended (e.g. a finer grid coarsened to fit maxCells).
/// @return the composite: the union of the parts' areas at the finest spacing (coarsened to fit
///   maxCells). Parts are laid coarsest first; each finer one is blended over what is below with its
///   own dataWeight as the weight (blendSnapshotFields), and the composite's dataWeight is
///   w + (1 - w) * below (empty when 1 everywhere).
WeatherSnapshot compositeSnapshots(std::vector<WeatherSnapshot> parts, size_t maxCells,
                                   std::vector<std::string>& warnings);

} // namespace sky
