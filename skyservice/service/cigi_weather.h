// SPDX-License-Identifier: MIT
// The weather a CIGI host sets (Weather Control, Environmental Region Control) as the renderer's weather:
// the cloud layers at any point, and a WeatherSnapshot of them that the daemon swaps in like a loaded
// file.
//
// At a point: the global cloud layers (1-3), then each active region over them in region-id order. A
// region is a rectangle sizeX x sizeY (X along its rotation from north) with rounded corners around its
// centre; inside it its layers replace the global ones, over its transition perimeter outside the
// rectangle they fade back to them (smoothstep of the distance to the rounded rectangle). A region with
// Merge Weather set is averaged with the regions before it where they overlap (half weight), one
// without it wins ("use last"). A region's layer that is disabled clears that layer inside the region; a
// layer the region does not mention stays global. A change drawn while it fades in is composed the same way
// (cigi_weather_fade.h).
//
// Cloud types follow the CIGI enumeration, which is the snapshot's CloudType numbering. Cirrocumulus,
// cirrostratus and cirrus go to the snapshot's high (2D) cloud layer; None, the IG-defined types 11-15, a
// zero thickness or coverage draw nothing. Altitudes from the host are above mean sea level; the snapshot
// holds ellipsoid heights (+ the EGM96 undulation per cell).
#pragma once

#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/geoid_undulation.h"
#include "weather_ingest/weather_snapshot.h"

#include <array>

namespace sky
{

/// One cloud layer (CIGI layer 1-3) at a point.
struct CigiCloudAt
{
    uint8_t layerId = 0;
    bool set = false;   ///< a global or regional Weather Control names this layer here
    float coverage = 0; ///< fraction [0, 1]; 0 = no cloud here
    float baseMslM = 0, topMslM = 0;
    uint8_t cloudType = 0; ///< CIGI = snapshot CloudType numbering
    float windEastMps = 0, windNorthMps = 0, verticalWindMps = 0;
    float humidityPct = 0, aerosolGPerM3 = 0;
};
using CigiCloudsAt = std::array<CigiCloudAt, 3>; ///< layers 1, 2, 3

class CigiWeatherFade;

/// True once the host has set any cloud layer (global or regional): from then on its weather is drawn.
bool cigiHasCloudWeather(const cigi::CigiState& state);

/// The cloud layers at a point as the host set them (see the top of this file; what is drawn while a change
/// fades in is CigiWeatherFade::cloudsAt).
CigiCloudsAt cigiCloudsAt(const cigi::CigiState& state, double latDeg, double lonDeg);

/// Cirrocumulus, cirrostratus, cirrus: drawn in the snapshot's high (2D) cloud layer.
bool cigiHighCloudType(uint8_t type);

/// A host's Weather Control layer at a point where it applies (coverage 0 when it draws nothing).
CigiCloudAt cigiLayerFromHost(const cigi::WeatherLayer& layer);

/// Blends `layer` over `current` with weight t [0, 1]: coverage, altitudes and winds interpolate; over a
/// layer with no cloud the blended one keeps its own altitudes and type (a cloud fades in where it will be),
/// and a layer with no cloud blended over one keeps that one's (it fades out where it was).
void cigiBlendLayer(CigiCloudAt& current, const CigiCloudAt& layer, float t);

/// a and b draw the same cloud (coverage, altitudes, type, horizontal wind; humidity, aerosol and vertical
/// wind are answered in responses, not drawn).
bool cigiSameDrawnLayer(const CigiCloudAt& a, const CigiCloudAt& b);

/// A region draws its layers: defined, Active, with at least one layer.
bool cigiRegionDrawn(const cigi::EnvironmentalRegion& region);

/// Weight [0, 1] of a region at a point: 1 inside the rounded rectangle, fading to 0 over its transition
/// perimeter (0 at once outside when the perimeter is 0).
double cigiRegionWeight(const cigi::EnvironmentalRegion& region, double latDeg, double lonDeg);

/// Wind towards east and north (m/s) of a speed and the direction it blows from (degrees from north).
void cigiWindComponents(float speedMps, float fromDeg, float& eastMps, float& northMps);

/// Where the snapshot's grid lies. Global layers only: the whole earth at 1 degree (uniform layers need
/// no more). With active regions: a grid around the ownship fine enough for the smallest region.
struct CigiWeatherGrid
{
    LatLonGrid grid;
    bool regional = false;
    double centreLatDeg = 0, centreLonDeg = 0; ///< regional: the ownship when it was made
    double halfExtentM = 0;                    ///< regional: distance from the centre to the grid's edge
};
/// ... for the regions a fade still draws (fading out ones included). `overGridded`: laid over a gridded
/// weather (cigi_weather_merge.h), whose clouds must still reach the renderer's whole weather window: the
/// regional grid then spans that window (800 km from the ownship), its cells no finer than 4 km.
CigiWeatherGrid cigiWeatherGrid(const CigiWeatherFade& fade, double ownLatDeg, double ownLonDeg,
                                bool overGridded = false);
CigiWeatherGrid cigiWeatherGrid(const cigi::CigiState& state, double ownLatDeg, double ownLonDeg);

/// The snapshot of the host's weather drawn at IG time nowS on `grid`, valid at `validTimeUnixS`.
WeatherSnapshot cigiWeatherSnapshot(const CigiWeatherFade& fade, double nowS, const CigiWeatherGrid& grid,
                                    const cigi::GeoidGrid& geoid, int64_t validTimeUnixS);
/// ... of the host's weather as set (no fade under way).
WeatherSnapshot cigiWeatherSnapshot(const cigi::CigiState& state, const CigiWeatherGrid& grid,
                                    const cigi::GeoidGrid& geoid, int64_t validTimeUnixS);

} // namespace sky
