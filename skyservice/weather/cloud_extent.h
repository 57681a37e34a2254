// SPDX-License-Identifier: MIT
// Where in a layer cloud can be (shaders/lib/cloud_extent.glsl, compiled here as C++): the height fractions
// of a genus at a coverage, for the column bounds (column_bounds.h).
#pragma once

namespace sky
{

/// Height fractions (0 at the base, 1 at the top) between which a layer may hold cloud; empty when hi < lo.
struct HeightFractionRange
{
    float lo = 0.0f;
    float hi = 1.0f;
    bool empty() const { return hi < lo; }
};

/**
 * The height fractions where a layer may hold cloud (layerMayHoldCloud of shaders/lib/cloud_extent.glsl)
 * at any coverage up to `maxCoverage`: wider than the exact ones by a step of the tabulation, never
 * narrower (the coverage is rounded up; the range only grows with it).
 *
 * @param[in] cloudType the genus as the shaders read it (rounded type channel); anything the shaders do
 *   not know takes their default profile.
 * @param[in] maxCoverage the largest coverage a bilinear lookup can see; NaN: the whole layer.
 * @return the range; [0, 1] for a NaN coverage.
 **********************************************************************/
HeightFractionRange layerCloudRange(int cloudType, float maxCoverage);

}  // namespace sky
