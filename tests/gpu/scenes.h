// SPDX-License-Identifier: MIT
// Weather scenes, views and image statistics shared by the GPU tests.
#pragma once

#include "skyservice/render/renderer.h"

#include <string>
#include <vector>

namespace sky::testscenes
{

QualitySettings testQuality();

int64_t parseTime(const std::string& iso);
/// First time after `startIso` (searching forward, 1-minute steps, up to 12 h) when the sun's elevation
/// at the place falls to `elevationDeg`.
int64_t timeOfSunElevation(double latDeg, double lonDeg, const std::string& startIso, double elevationDeg);

WeatherSnapshot clearSky();
/// One layer of uniform coverage, type and altitudes over a global 1-degree grid.
WeatherSnapshot uniformLayer(float coverage, CloudType type, float baseM, float topM);

/// One round cell of full coverage (radius in metres) on a 0.01-degree regional grid, clear elsewhere.
WeatherSnapshot isolatedCell(double latDeg, double lonDeg, double radiusM, CloudType type, float baseM, float topM);

ViewRequest lookUp(double latDeg, double lonDeg, double altM, double pitchDeg, const std::string& timeIso);
ViewRequest lookDown(double latDeg, double lonDeg, double altM, int64_t unixTimeS);
/// 40 km west of the built-in cumulonimbus at 4500 m (above the cumulus field), looking east.
ViewRequest cumulonimbusView(const std::string& timeIso);
/// Gives `r` the built-in weather and returns cumulonimbusView at 2026-06-21 15:00 UTC, 320x180: the
/// tower and the cumulus field beyond the light volume, cloudy rows and clear ones.
ViewRequest builtinCumulonimbus320(Renderer& r);

struct ImageStats
{
    uint32_t skyPixels = 0;      ///< pixels whose view ray does not hit the ground
    uint32_t cloudPixels = 0;    ///< pixels with alpha > 0.5
    float maxAlpha = 0;
    bool allFinite = true;
    double meanCloudLuminance = 0;  ///< mean of cloud radiance / alpha over cloud pixels
    double meanCloudRed = 0, meanCloudBlue = 0;
    double meanDisplayLuminance = 0;  ///< mean of the tone-mapped image (0..1)
    uint32_t opaquePixels = 0;        ///< pixels with alpha > 0.95 (thick cloud, no silver lining)
    double meanOpaqueLuminance = 0;   ///< mean cloud radiance over opaque pixels
};
/// Statistics over rows [0, rowEnd) (all rows by default).
ImageStats cloudStats(const RenderResult& r, uint32_t rowEnd = 0xffffffffu);

struct SkyProbe
{
    int x = 0, y = 0;
    glm::vec3 radiance{0.0f};
};
/// CPU sky radiance (skyservice/sky/atmosphere_reference) at `count` pixels of a clear view, away from
/// the sun and the moon.
std::vector<SkyProbe> cpuSkyProbes(Renderer& r, const ViewRequest& view, int count);

}  // namespace sky::testscenes

namespace sky::testscenes
{

// --- Geo-referencing (tests/gpu/test_georef.cpp) ---

/// Unit view direction (ENU) through a point of the image given in pixels (x right, y down; pixel
/// (i, j) covers [i, i+1) x [j, j+1)): the mapping of shaders/clouds/view_ray.glsl without jitter.
glm::dvec3 pixelRayEnu(const CameraFrame& cam, const ViewRequest& view, double xPx, double yPx);

struct CloudCentroid
{
    double weight = 0;    ///< sum of alpha over the pixels counted
    double xPx = 0, yPx = 0;  ///< alpha-weighted centroid of pixel centres (pixels, y down)
    uint32_t pixels = 0;  ///< pixels with alpha above the threshold
};
/// Alpha-weighted centroid of the pixels whose cloud alpha exceeds `minAlpha`.
CloudCentroid cloudCentroid(const RenderResult& r, float minAlpha);

/// Largest angle (degrees) between `directionEnu` and the ray of any pixel whose cloud alpha exceeds
/// `minAlpha`; also counts those beyond `limitDeg`.
double maxCloudAngleDeg(const RenderResult& r, const CameraFrame& cam, const ViewRequest& view,
                        const glm::dvec3& directionEnu, float minAlpha, double limitDeg, uint32_t& beyondLimit);

}  // namespace sky::testscenes

namespace sky::testscenes
{

// --- Cloud shadow map (tests/gpu/test_shadow_map.cpp) ---

/// Only a high (2D) layer of uniform coverage, type and altitude over a global 1-degree grid.
WeatherSnapshot highLayer(float coverage, CloudType type, float altitudeM);

}  // namespace sky::testscenes

namespace sky::testscenes
{

// --- Temporal reprojection (tests/gpu/test_reprojection.cpp and its siblings) ---

/// testQuality() with reprojection on.
QualitySettings reprojectedQuality();
/// Scattered cumulus (coverage 0.4, 1200-3000 m) seen from 200 m, 12 degrees above the horizon,
/// looking north at 128x72: cloud edges, sky gaps and depth from ~1 km to the horizon.
WeatherSnapshot reprojectionWeather();
ViewRequest reprojectionView();

// --- March lighting (tests/gpu/test_light_volume.cpp, test_render.cpp) ---

/// A stratocumulus deck (coverage 0.8, 900-1900 m) seen from 4000 m, 45 degrees down, at 160x90 with
/// the sun at 30 degrees: thick cloud filling the image, lit from above.
WeatherSnapshot deckBelowWeather();
ViewRequest deckFromAboveView();

}  // namespace sky::testscenes
