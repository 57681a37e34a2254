// SPDX-License-Identifier: MIT
// Layout of the camera-centred weather window, shared by the CPU resampler and the shaders.
//
// The window is an azimuthal equidistant projection centred on the eye (GeographicLib
// AzimuthalEquidistant on WGS84): texel (i, j) of a WEATHER_WINDOW_SIZE^2 grid covers the point at
// easting x = (i + 0.5 - N/2) * texelSizeM and northing y = (j + 0.5 - N/2) * texelSizeM from the eye.
// It is stored as a 2D array texture, RGBA16F (half floats: altitudes in 8 m steps up to 16 km), with
// WEATHER_WINDOW_SLICES slices:
//
//   slice 2k   (k < MAX_CLOUD_LAYERS): coverage [0,1], base altitude (m), top altitude (m), cloud type (0..10, CIGI)
//   slice 2k+1                         : wind east (m/s), wind north (m/s), precipitation rate (mm/h), CAPE (J/kg)
//   slice HIGH_SLICE                  : high-cloud coverage [0,1], altitude (m), type (3,4,5), unused
//   slice HIGH_SLICE+1                : high-level wind east (m/s), wind north (m/s), tropopause altitude (m), unused
//   slice ANVIL_SLICE                 : anvil coverage [0,1], unused x3 -- NOT filled by the resampler: the
//                                       renderer derives it from cumulonimbus cells, CAPE and the upper wind
//
// Altitudes are metres above the WGS84 ellipsoid, the same datum as the eye altitude (the model's
// mean-sea-level heights are taken as ellipsoid heights; README "Datums" says why).
// A coverage of 0 means "no cloud" whatever the other channels hold. Types are categorical: shaders
// read them with the nearest texel, everything else with bilinear filtering.
#ifndef SKY_SHARED_WEATHER_WINDOW_H
#define SKY_SHARED_WEATHER_WINDOW_H
#include "shaders/shared/bindings.h"
#include "shaders/shared/cloud_type.h"

#define WEATHER_WINDOW_HIGH_SLICE (2 * MAX_CLOUD_LAYERS)
#define WEATHER_WINDOW_ANVIL_SLICE (2 * MAX_CLOUD_LAYERS + 2)
#define WEATHER_WINDOW_SLICES (2 * MAX_CLOUD_LAYERS + 3)

// The GPU copy of the window holds only what the shaders read (the layers' winds and CAPE serve the CPU:
// anvils, wind drift), in WEATHER_GPU_SLICES slices of the same texels (skyservice/render/
// window_provider.cpp packs it; 3 slices, 1.6 MB, fewer than the window's):
//   slice k (k < MAX_CLOUD_LAYERS): the window's slice 2k (coverage, base, top, type)
//   WEATHER_GPU_PRECIP_SLICE:       precipitation rate (mm/h) of layers 0..3 in x, y, z, w
//   WEATHER_GPU_HIGH_SLICE, WEATHER_GPU_HIGH_WIND_SLICE, WEATHER_GPU_ANVIL_SLICE: the window's high,
//                                   high + 1 and anvil slices
#define WEATHER_GPU_PRECIP_SLICE MAX_CLOUD_LAYERS
#define WEATHER_GPU_HIGH_SLICE (MAX_CLOUD_LAYERS + 1)
#define WEATHER_GPU_HIGH_WIND_SLICE (MAX_CLOUD_LAYERS + 2)
#define WEATHER_GPU_ANVIL_SLICE (MAX_CLOUD_LAYERS + 3)
#define WEATHER_GPU_SLICES (MAX_CLOUD_LAYERS + 4)

// Coverage below which a layer draws nothing (cloudDensity skips it; column_bounds.h counts from it).
#define CLOUD_COVERAGE_MIN 0.01f

#endif
