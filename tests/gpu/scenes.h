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
