// SPDX-License-Identifier: MIT
// From pressure to altitude: the ICAO standard atmosphere, and fields on isobaric levels interpolated
// linearly in log-pressure (geopotential height, wind, mixing ratio).
#pragma once

#include <cmath>
#include <cstddef>
#include <deque>
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

/// A field given on isobaric levels over a grid. A level is either a view of values that outlive the stack
/// (a decoded message's field: no copy of a whole field per level) or values the stack owns.
class LevelStack
{
  public:
    bool empty() const { return pressurePa_.empty(); }
    size_t levelCount() const { return pressurePa_.size(); }
    size_t cells() const { return cells_; }
    /// Levels sorted by decreasing pressure (surface first).
    double pressurePa(size_t k) const { return pressurePa_[k]; }
    const float* level(size_t k) const { return levels_[k]; }

    /// Adds a level viewing `values` (cells() floats, kept alive by the caller while the stack is used),
    /// keeping the levels sorted; a repeated pressure replaces the old level. NaN = missing at that level.
    void addLevelView(double levelPressurePa, const float* values, size_t cellCount);
    /// The same with values the stack keeps.
    void addLevel(double levelPressurePa, std::vector<float> values);

    /// Every level, level-major (values[k * cells() + cell]), e.g. for a snapshot's pressure-level field.
    std::vector<float> concatenated() const;

    /// Value at a pressure, linear in ln(p) between the two bracketing levels that have values.
    ///
    /// @param[in] cell grid cell.
    /// @param[in] atPressurePa pressure (Pa), > 0.
    /// @param[in] extrapolate outside the levels: true extends the line through the two nearest levels
    ///   (for heights), false holds the nearest level (for winds).
    /// @return NaN when fewer than one (hold) or two (extrapolate) levels have a value in this cell.
    float at(size_t cell, double atPressurePa, bool extrapolate) const;

  private:
    void insert(double levelPressurePa, const float* values, size_t cellCount);

    std::vector<double> pressurePa_;
    std::vector<double> logPressure_; ///< ln(pressurePa_), for at()
    std::vector<const float*> levels_;
    std::deque<std::vector<float>> owned_; ///< levels added by value (a deque: their data never moves)
    size_t cells_ = 0;
};

/// LevelStack::at() for many cells at one pressure, with the same results: the bracketing levels are found
/// once, and a cell falls back to at() only where one of them is missing.
class LevelSampler
{
  public:
    LevelSampler(const LevelStack& stack, double atPressurePa, bool extrapolate);
    float operator()(size_t cell) const
    {
        if (k0_ != nullptr)
        {
            const float v0 = k0_[cell];
            if (hold_)
            {
                if (!std::isnan(v0))
                    return v0;
            }
            else if (const float v1 = k1_[cell]; !std::isnan(v0) && !std::isnan(v1))
            {
                return static_cast<float>(double(v0) + (double(v1) - double(v0)) * t_);
            }
        }
        return stack_.empty() ? NAN : stack_.at(cell, atPressurePa_, extrapolate_);
    }

  private:
    const LevelStack& stack_;
    double atPressurePa_;
    bool extrapolate_;
    const float* k0_ = nullptr; ///< the level values come from when every level has one (nullptr: none)
    const float* k1_ = nullptr;
    bool hold_ = false; ///< outside the levels without extrapolation: k0's value
    double t_ = 0;
};

/// Altitude (m) of a pressure in one cell: from geopotential height on isobaric levels when given
/// (log-pressure interpolation; geopotential metres are taken as metres, < 0.3 % off below 20 km),
/// else, or where those are missing, the ICAO standard atmosphere.
float pressureToAltitudeM(const LevelStack& geopotentialHeightM, size_t cell, double pressurePa);

/// pressureToAltitudeM() for many cells at one pressure (same results, faster).
class AltitudeAtPressure
{
  public:
    AltitudeAtPressure(const LevelStack& geopotentialHeightM, double pressurePa);
    float operator()(size_t cell) const
    {
        if (!valid_)
            return NAN;
        const float z = sampler_(cell);
        return std::isfinite(z) ? z : standardM_;
    }

  private:
    LevelSampler sampler_;
    bool valid_;
    float standardM_;
};

} // namespace sky
