// SPDX-License-Identifier: MIT
#include "weather_ingest/pressure_altitude.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

// ICAO Doc 7488/3 (ISO 2533:1975) constants.
constexpr double kP0Pa = 101325.0;  // sea-level pressure
constexpr double kT0K = 288.15;     // sea-level temperature
constexpr double kG0 = 9.80665;     // standard gravity (m s^-2)
constexpr double kRAir = 287.05287; // specific gas constant of dry air (J kg^-1 K^-1)
constexpr double kLapse0 = 0.0065;  // 0-11 km lapse rate (K/m)
constexpr double kH11M = 11000.0;
constexpr double kT11K = 216.65;
constexpr double kP11Pa = 22632.06; // pressure at 11 km
constexpr double kH20M = 20000.0;
constexpr double kP20Pa = 5474.889; // pressure at 20 km
constexpr double kLapse20 = 0.001;  // 20-32 km: temperature rises 1 K/km (dT/dh, K/m)

} // namespace

double standardAtmosphereAltitudeM(double pressurePa)
{
    if (pressurePa >= kP11Pa)
        return kT0K / kLapse0 * (1.0 - std::pow(pressurePa / kP0Pa, kRAir * kLapse0 / kG0));
    if (pressurePa >= kP20Pa)
        return kH11M + kRAir * kT11K / kG0 * std::log(kP11Pa / pressurePa);
    return kH20M + kT11K / kLapse20 * (std::pow(pressurePa / kP20Pa, -kRAir * kLapse20 / kG0) - 1.0);
}

double standardAtmospherePressurePa(double altitudeM)
{
    if (altitudeM <= kH11M)
        return kP0Pa * std::pow(1.0 - kLapse0 * altitudeM / kT0K, kG0 / (kRAir * kLapse0));
    if (altitudeM <= kH20M)
        return kP11Pa * std::exp(-kG0 * (altitudeM - kH11M) / (kRAir * kT11K));
    return kP20Pa * std::pow(1.0 + kLapse20 * (altitudeM - kH20M) / kT11K, -kG0 / (kRAir * kLapse20));
}

void LevelStack::insert(double levelPressurePa, const float* values, size_t cellCount)
{
    if (cells_ == 0)
        cells_ = cellCount;
    auto it = std::find(pressurePa_.begin(), pressurePa_.end(), levelPressurePa);
    if (it != pressurePa_.end())
    {
        levels_[size_t(it - pressurePa_.begin())] = values;
        return;
    }
    it = std::find_if(pressurePa_.begin(), pressurePa_.end(), [&](double p) { return p < levelPressurePa; });
    const auto k = it - pressurePa_.begin();
    pressurePa_.insert(it, levelPressurePa);
    logPressure_.insert(logPressure_.begin() + k, std::log(levelPressurePa));
    levels_.insert(levels_.begin() + k, values);
}

void LevelStack::addLevelView(double levelPressurePa, const float* values, size_t cellCount)
{
    insert(levelPressurePa, values, cellCount);
}

void LevelStack::addLevel(double levelPressurePa, std::vector<float> values)
{
    owned_.push_back(std::move(values));
    insert(levelPressurePa, owned_.back().data(), owned_.back().size());
}

std::vector<float> LevelStack::concatenated() const
{
    std::vector<float> out;
    out.reserve(levels_.size() * cells_);
    for (const float* level : levels_)
        out.insert(out.end(), level, level + cells_);
    return out;
}

float LevelStack::at(size_t cell, double atPressurePa, bool extrapolate) const
{
    const size_t n = pressurePa_.size();
    // Levels are few (< 50): a linear walk that skips NaN levels is simpler than a search.
    long below = -1; // nearest level with p >= atPressurePa (higher pressure, lower altitude)
    long above = -1; // nearest level with p < atPressurePa
    long first = -1, second = -1, last = -1, beforeLast = -1;
    for (size_t k = 0; k < n; ++k)
    {
        if (std::isnan(levels_[k][cell]))
            continue;
        if (first < 0)
            first = long(k);
        else if (second < 0)
            second = long(k);
        beforeLast = last;
        last = long(k);
        if (pressurePa_[k] >= atPressurePa)
            below = long(k);
        else if (above < 0)
            above = long(k);
    }
    if (first < 0)
        return NAN;
    long k0 = below, k1 = above;
    if (below < 0 || above < 0)
    {
        if (!extrapolate)
            return levels_[size_t(below < 0 ? first : last)][cell];
        if (second < 0)
            return NAN;
        k0 = below < 0 ? first : beforeLast;
        k1 = below < 0 ? second : last;
    }
    const double v0 = levels_[size_t(k0)][cell];
    const double v1 = levels_[size_t(k1)][cell];
    const double l0 = logPressure_[size_t(k0)];
    const double l1 = logPressure_[size_t(k1)];
    const double t = (std::log(atPressurePa) - l0) / (l1 - l0);
    return static_cast<float>(v0 + (v1 - v0) * t);
}

LevelSampler::LevelSampler(const LevelStack& stack, double atPressurePa, bool extrapolate)
    : stack_(stack), atPressurePa_(atPressurePa), extrapolate_(extrapolate)
{
    // The levels at() picks in a cell where every level has a value; where one of these two is missing,
    // at() may pick others, so operator() falls back to it there.
    const size_t n = stack.levelCount();
    if (n == 0 || !(atPressurePa > 0))
        return;
    size_t above = 0; // first level with p < atPressurePa (n: none)
    while (above < n && stack.pressurePa(above) >= atPressurePa)
        ++above;
    size_t k0 = above - 1, k1 = above;
    if (above == 0 || above == n)
    {
        if (!extrapolate)
        {
            hold_ = true;
            k0_ = stack.level(above == 0 ? 0 : n - 1);
            return;
        }
        if (n < 2)
            return;
        k0 = above == 0 ? 0 : n - 2;
        k1 = above == 0 ? 1 : n - 1;
    }
    k0_ = stack.level(k0);
    k1_ = stack.level(k1);
    const double l0 = std::log(stack.pressurePa(k0)), l1 = std::log(stack.pressurePa(k1));
    t_ = (std::log(atPressurePa) - l0) / (l1 - l0);
}

float pressureToAltitudeM(const LevelStack& geopotentialHeightM, size_t cell, double pressurePa)
{
    if (!(pressurePa > 0))
        return NAN;
    if (!geopotentialHeightM.empty())
    {
        const float z = geopotentialHeightM.at(cell, pressurePa, true);
        if (std::isfinite(z))
            return z;
    }
    return static_cast<float>(standardAtmosphereAltitudeM(pressurePa));
}

AltitudeAtPressure::AltitudeAtPressure(const LevelStack& geopotentialHeightM, double pressurePa)
    : sampler_(geopotentialHeightM, pressurePa, true), valid_(pressurePa > 0),
      standardM_(valid_ ? static_cast<float>(standardAtmosphereAltitudeM(pressurePa)) : NAN)
{
}

} // namespace sky
