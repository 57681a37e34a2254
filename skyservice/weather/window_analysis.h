// SPDX-License-Identifier: MIT
// Facts about a resampled weather window that the frame needs: the altitude range of each layer (so
// the march skips what is empty), the mean wind per layer (animation and shear), and the anvils.
#pragma once

#include "skyservice/weather/weather_window.h"

#include <array>
#include <glm/glm.hpp>

namespace sky
{

struct LayerSummary
{
    float minBaseM = 0;         ///< lowest base where coverage > 0 (m); > maxTopM when the layer is empty
    float maxTopM = -1;         ///< highest top (m)
    glm::dvec2 meanWindEnuMS{0.0};  ///< coverage-weighted mean wind (m/s, east, north)
    float anvilAmount = 0;      ///< Häggström anvil term for cumulonimbus in this layer [0,1]
    bool empty() const { return maxTopM <= minBaseM; }
};

struct WindowSummary
{
    std::array<LayerSummary, 4> layers;  ///< volumetric layers (MAX_CLOUD_LAYERS)
    LayerSummary anvil;                  ///< the anvil slab
    glm::dvec2 upperWindEnuMS{0.0};      ///< mean high-level wind (m/s)
    float highAltitudeM = 0;             ///< coverage-weighted high-cloud altitude (m); 0 when none
};

/// Fills the anvil slice of `window` (WEATHER_WINDOW_ANVIL_SLICE) from its cumulonimbus cells: each
/// tower top spreads into a slab whose radius grows with CAPE (8 km + 12 km per 3000 J/kg) and whose
/// centre is pushed downwind by the upper-level wind over 5 minutes, at 72-100% of the tower height.
void computeAnvils(WeatherWindow& window);

/// Summarises `window` (after computeAnvils).
WindowSummary summarizeWindow(const WeatherWindow& window);

}  // namespace sky
