// SPDX-License-Identifier: MIT
// Blending two snapshots on one grid, cell by cell: the rule the timeline uses between two valid times,
// and the compositor between a regional model and the grid under it.
//
// Rule: every continuous field is a*(1-w) + b*w. Where a value is NaN (unknown) on one side only, the
// known side's value is used unchanged; NaN on both sides stays NaN. Cloud type is categorical: it is
// taken from the side with the larger weight, unless that side has no cloud there (None), in which case
// the other side's type is used, so a cloud fading in or out keeps its genus. Layers are matched by
// name; a layer present on one side only fades in or out (its coverage is scaled by the weight of the
// side that has it). Level fields blend when both sides have the same levels, else a's are kept.
// dataWeight blends like any field, an absent one counting as 1.
#pragma once

#include "weather_ingest/weather_snapshot.h"

#include <vector>

namespace sky
{

/// The weight of snapshot b: one value for every cell, or one per cell.
struct BlendWeight
{
    float uniform = 0;                           ///< used when perCell is null
    const std::vector<float>* perCell = nullptr; ///< grid.cellCount() values in [0, 1]

    float at(size_t cell) const { return perCell ? (*perCell)[cell] : uniform; }
};

/// Blends the fields of a and b (same grid) into out (its grid, time and provenance are left alone;
/// its vectors are reused).
void blendSnapshotFields(const WeatherSnapshot& a, const WeatherSnapshot& b, const BlendWeight& w,
                         WeatherSnapshot& out);

} // namespace sky
