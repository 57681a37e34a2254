// SPDX-License-Identifier: MIT
// The camera-centred weather window: a WeatherSnapshot resampled onto the eye's azimuthal equidistant
// grid, in the texel layout of shaders/shared/weather_window.h (one RGBA32F 2D array texture).
//
// Sampling rules (DESIGN §1 "LocalWeather"):
//  - continuous fields bilinear on the lat/lon grid; cloud type from the nearest cell;
//  - a grid whose nLon * dLonDeg is 360 wraps in longitude (any longitude convention) and is clamped
//    at the poles; outside a regional grid the coverage is 0 and the other fields take the value at
//    the nearest edge of the grid (so that the GPU's bilinear filter does not pull base and top
//    altitudes towards zero at the edge);
//  - a corner whose coverage, base or top is NaN counts as coverage 0; other NaN values are left out
//    of the interpolation (the remaining corners are re-weighted) and, when all four are NaN, take a
//    default (0, or 11000 m for the tropopause);
//  - a layer that is absent, or whose coverage, base or top vector does not have one value per cell,
//    gives coverage 0; other missing vectors give their defaults.
#pragma once

#include "shaders/shared/weather_window.h"
#include "weather_ingest/weather_snapshot.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sky
{

/// A resampled weather window, ready for upload as a 2D array texture.
struct WeatherWindow
{
    double centreLatDeg = 0;  ///< latitude of the projection centre (degrees)
    double centreLonDeg = 0;  ///< longitude of the projection centre (degrees)
    double texelSizeM = 0;    ///< texel edge length in the projection plane (meters)
    uint32_t sizeTexels = 0;  ///< texels per side (WEATHER_WINDOW_SIZE unless a test asks otherwise)
    /// WEATHER_WINDOW_SLICES slices of sizeTexels^2 texels: slice-major, then row (northing j), then
    /// column (easting i). Channel meaning per slice: shaders/shared/weather_window.h. The resampler
    /// leaves WEATHER_WINDOW_ANVIL_SLICE at zero (the renderer derives it).
    std::vector<glm::vec4> texels;

    size_t index(uint32_t slice, uint32_t i, uint32_t j) const
    {
        return (size_t(slice) * sizeTexels + j) * sizeTexels + i;
    }
    const glm::vec4& at(uint32_t slice, uint32_t i, uint32_t j) const { return texels[index(slice, i, j)]; }
    /// Easting (meters) of the centre of column i, from the projection centre.
    double texelEastingM(uint32_t i) const { return (double(i) + 0.5 - 0.5 * double(sizeTexels)) * texelSizeM; }
    /// Northing (meters) of the centre of row j, from the projection centre.
    double texelNorthingM(uint32_t j) const { return (double(j) + 0.5 - 0.5 * double(sizeTexels)) * texelSizeM; }
};

/// Tropopause altitude used where the snapshot has none: the ICAO standard atmosphere's 11 km
/// (ISO 2533:1975).
inline constexpr float kDefaultTropopauseAltitudeM = 11000.0f;

/**
 * Resample a snapshot onto the window centred on a point.
 *
 * @param[in] snapshot the weather; its grid must have nLat, nLon >= 1 and dLonDeg > 0.
 * @param[in] centreLatDeg latitude of the window centre, normally the eye (degrees, [-90, 90]).
 * @param[in] centreLonDeg longitude of the window centre (degrees, any convention).
 * @param[in] halfExtentM distance from the centre to an edge of the window (meters, > 0); the texel
 *   size is 2 halfExtentM / sizeTexels.
 * @param[out] out the window; its texels vector is resized (and reused when it has the right size).
 * @param[in] sizeTexels texels per side (default WEATHER_WINDOW_SIZE; smaller sizes are for tests).
 *
 * Each texel centre is projected back to latitude and longitude exactly, with GeographicLib's
 * AzimuthalEquidistant::Reverse on WGS84 (a geodesic direct problem, ~1.3 us). Rows are shared out
 * to up to 8 threads (std::thread, joined before returning; the result does not depend on their
 * number). Measured for 256^2 texels of the built-in weather: 85 ms on one core, 17 ms with 8
 * threads (H100 host, 16 cores). Not thread-safe on the same `out`.
 **********************************************************************/
void resampleWeatherWindow(const WeatherSnapshot& snapshot, double centreLatDeg, double centreLonDeg,
                           double halfExtentM, WeatherWindow& out, uint32_t sizeTexels = WEATHER_WINDOW_SIZE);

}  // namespace sky
