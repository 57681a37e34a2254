// SPDX-License-Identifier: MIT
// LatLonGrid: a regular latitude/longitude grid, and the one way a value is read off it between its
// nodes. The ingest (compositing grids), the service (laying a host's weather over a model's) and the
// renderer (the camera-centred window) all sample through LatLonGrid::locate and LatLonGrid::sample,
// so a field reads the same wherever it is drawn.
//
// Rules:
//  - Global wrap: a grid whose nLon * dLonDeg is 360 within kGlobalSpanToleranceDeg goes all the way
//    round; its last column blends into its first, and any longitude convention finds its cell. Such a
//    grid has no edge in latitude either: beyond its first or last row it is clamped (the poles).
//  - Edges: a point within half a cell of the outermost rows and columns of a regional grid is inside
//    (each node stands for the cell around it); further out it is outside. Either way the corners are
//    clamped to the nearest edge of the grid (in longitude, the nearer of the east and west edges), so a
//    field read outside takes its value at the edge; callers that want nothing there test `inside`.
//  - Missing values: a corner whose value is not finite (NaN, or inf) is left out and the others are
//    re-weighted. When every corner with weight is missing, a known corner of zero weight gives its value
//    (a point on a missing node next to known ones); when all four are missing, the caller's `missing`.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

namespace sky
{

/// 1e-4 degrees: grids whose spacing is written as a decimal string (0.1 deg) do not add up to 360
/// exactly.
inline constexpr double kGlobalSpanToleranceDeg = 1e-4;

/// @return lon wrapped into [-180, 180) (degrees).
double wrapLongitudeDeg(double lonDeg);

/// Where a point falls on a LatLonGrid: the four cells around it, their bilinear weights, and the
/// nearest of them.
struct GridPoint
{
    bool inside = false;              ///< within the grid's footprint (see the rules at the top)
    std::array<size_t, 4> corner{};   ///< cell indices: (row0, col0), (row0, col1), (row1, col0), (row1, col1)
    std::array<double, 4> weight{};   ///< bilinear weights of the corners (sum 1)
    size_t nearest = 0;               ///< the corner nearest the point (for categories such as the cloud type)
};

/// A regular latitude/longitude grid (degrees).
struct LatLonGrid
{
    double lat0Deg = 0;  ///< latitude of row 0 (degrees)
    double lon0Deg = 0;  ///< longitude of column 0 (degrees)
    double dLatDeg = 1;  ///< row spacing (degrees, may be negative)
    double dLonDeg = 1;  ///< column spacing (degrees, > 0)
    uint32_t nLat = 0;   ///< rows
    uint32_t nLon = 0;   ///< columns

    size_t cellCount() const { return size_t(nLat) * size_t(nLon); }
    size_t index(uint32_t iLat, uint32_t iLon) const { return size_t(iLat) * nLon + iLon; }

    /// True when the columns go all the way round (nLon * dLonDeg == 360 within kGlobalSpanToleranceDeg).
    bool wrapsInLongitude() const;

    /// Where (latDeg, lonDeg) falls on the grid (degrees; longitude in any convention); an empty grid
    /// (no cells) has nothing inside.
    GridPoint locate(double latDeg, double lonDeg) const;

    /// The field's value at a located point (the missing-value rule at the top).
    /// @param[in] values cellCount() values (row-major); of another size, the field is absent: `missing`.
    /// @param[in] missing the value where nothing is known.
    float sample(std::span<const float> values, const GridPoint& point, float missing = NAN) const;

    /// locate() then sample(); outside the grid's footprint (`inside` false) this too reads the edge.
    float sample(std::span<const float> values, double latDeg, double lonDeg, float missing = NAN) const
    {
        return sample(values, locate(latDeg, lonDeg), missing);
    }
};

/// The coverage of a cloud layer at a located point, bilinear, where a corner whose coverage, base or top
/// is missing counts as clear (a cloud without a known base or top is not drawn), each clamped to [0, 1].
/// Any vector without one value per cell gives 0. `cornerWeight` (cellCount() values, or empty for 1)
/// scales each corner's coverage (a snapshot's dataWeight folded in per cell). Outside the grid's
/// footprint the coverage is 0.
float sampleCoverage(const LatLonGrid& grid, std::span<const float> coverage, std::span<const float> base,
                     std::span<const float> top, const GridPoint& point, std::span<const float> cornerWeight = {});

}  // namespace sky
