// SPDX-License-Identifier: MIT
// The camera-centred weather window: a WeatherSnapshot resampled onto the eye's azimuthal equidistant
// grid, in the texel layout of shaders/shared/weather_window.h (uploaded as one RGBA16F 2D array texture: weather/window_provider.h).
//
// Sampling rules (OVERVIEW.md); wrap, edges and missing values are LatLonGrid's (weather_ingest/lat_lon_grid.h):
//  - continuous fields bilinear on the lat/lon grid; cloud type from the nearest cell;
//  - a grid whose nLon * dLonDeg is 360 wraps in longitude (any longitude convention) and is clamped
//    at the poles; outside a regional grid (beyond half a cell from its outer nodes) the coverage is 0
//    and the other fields take the value at the nearest edge of the grid (so that the GPU's bilinear
//    filter does not pull base and top altitudes towards zero at the edge);
//  - a corner whose coverage, base or top is missing counts as coverage 0; other missing values are left
//    out of the interpolation (the remaining corners are re-weighted) and, when all four are missing,
//    take a default (0, or 11000 m for the tropopause);
//  - a layer that is absent, or whose coverage, base or top vector does not have one value per cell,
//    gives coverage 0; other missing vectors give their defaults;
//  - every coverage is multiplied by the snapshot's dataWeight (bilinear; absent = 1), so outside a
//    regional model's domain the sky is clear and its edge fades in over the domain's outer 5 %.
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
    double texelSizeM = 0;    ///< texel edge length in the (warped) window plane (meters)
    double halfExtentM = 0;   ///< half width of the window (meters): points up to this far are inside
    double warpRadiusM = 0;   ///< radial warp r0 (meters, 0 = none): see windowWarpM() below
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
    /// Window-plane easting (meters) of the centre of column i; the true easting when warpRadiusM = 0.
    double texelEastingM(uint32_t i) const { return (double(i) + 0.5 - 0.5 * double(sizeTexels)) * texelSizeM; }
    /// Window-plane northing (meters) of the centre of row j; the true northing when warpRadiusM = 0.
    double texelNorthingM(uint32_t j) const { return (double(j) + 0.5 - 0.5 * double(sizeTexels)) * texelSizeM; }
    /// True position (easting, northing in the azimuthal equidistant projection, meters) of texel (i, j).
    glm::dvec2 texelPositionM(uint32_t i, uint32_t j) const;
};

/**
 * The radial warp of the window (shaders/lib/window_warp.glsl is the same formula in float):
 * q = p (E + r0) / (|p| + r0) for a point p at distance |p| from the eye, with E the half extent and r0
 * the warp radius. It keeps q = p at |p| = E and magnifies the centre by (E + r0) / r0, so texels are
 * fine near the eye (0.99 km at E = 800 km, r0 = 150 km, 256 texels) and coarse at the horizon (40 km).
 * With r0 = 0 there is no warp.
 */
glm::dvec2 windowWarpM(const glm::dvec2& pM, double halfExtentM, double warpRadiusM);
/// The inverse of windowWarpM; plane points at or beyond E + r0 (the window's corners) map far away.
glm::dvec2 windowUnwarpM(const glm::dvec2& qM, double halfExtentM, double warpRadiusM);

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
 * @param[in] warpRadiusM radial warp r0 (meters; 0 = uniform texels), see windowWarpM().
 *
 * Each texel centre is projected back to latitude and longitude exactly, with GeographicLib's
 * AzimuthalEquidistant::Reverse on WGS84 (a geodesic direct problem per texel). Rows are shared out
 * to up to 8 threads (std::thread, joined before returning; the result does not depend on their
 * number). A whole window takes tens of milliseconds of CPU even so, which is why it is made off the
 * frame path (window_lattice.h). Not thread-safe on the same `out`.
 **********************************************************************/
void resampleWeatherWindow(const WeatherSnapshot& snapshot, double centreLatDeg, double centreLonDeg,
                           double halfExtentM, WeatherWindow& out, uint32_t sizeTexels = WEATHER_WINDOW_SIZE,
                           double warpRadiusM = 0.0);

}  // namespace sky
