// SPDX-License-Identifier: MIT
// From pressure to altitude: the ICAO standard atmosphere, and fields on isobaric levels interpolated
// linearly in log-pressure (geopotential height, wind, mixing ratio).
#pragma once

#include <cstddef>
#include <vector>

namespace sky
{

/// Altitude of a pressure in the ICAO standard atmosphere (ICAO Doc 7488/3, = ISO 2533:1975), valid
/// from below sea level to 32 km (layers 0-11 km lapse 6.5 K/km, 11-20 km isothermal 216.65 K,
/// 20-32 km lapse -1 K/km).
///
/// @param[in] pressurePa pressure (Pa), > 0; below 868 Pa (32 km) the 20-32 km law is extended.
/// @return geopotential altitude (m), which the snapshot takes as height above the ellipsoid.
double standardAtmosphereAltitudeM(double pressurePa);

/// Inverse of standardAtmosphereAltitudeM(): pressure (Pa) at an altitude (m).
double standardAtmospherePressurePa(double altitudeM);

/// A field given on isobaric levels over a grid.
struct LevelStack
{
    std::vector<double> pressurePa;  ///< one per level, sorted decreasing (surface first)
    std::vector<float> values;       ///< level-major: values[k * cells + cell]; NaN = missing at that level
    size_t cells = 0;

    bool empty() const { return pressurePa.empty(); }

    /// Adds a level, keeping the levels sorted (a repeated pressure replaces the old level).
    void addLevel(double levelPressurePa, const std::vector<float>& levelValues);

    /// Value at a pressure, linear in ln(p) between the two bracketing levels that have values.
    ///
    /// @param[in] cell grid cell.
    /// @param[in] atPressurePa pressure (Pa), > 0.
    /// @param[in] extrapolate outside the levels: true extends the line through the two nearest levels
    ///   (for heights), false holds the nearest level (for winds).
    /// @return NaN when fewer than one (hold) or two (extrapolate) levels have a value in this cell.
    float at(size_t cell, double atPressurePa, bool extrapolate) const;
};

/// Altitude (m) of a pressure in one cell: from geopotential height on isobaric levels when given
/// (log-pressure interpolation; geopotential metres are taken as metres, < 0.3 % off below 20 km),
/// else, or where those are missing, the ICAO standard atmosphere.
float pressureToAltitudeM(const LevelStack& geopotentialHeightM, size_t cell, double pressurePa);

}  // namespace sky
