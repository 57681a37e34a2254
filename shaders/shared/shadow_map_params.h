// SPDX-License-Identifier: MIT
// Interface of the cloud shadow map pass (shaders/shadow/shadow_map.comp.glsl), shared by GLSL and C++
// (skyservice/render/shadow_map.h).
//
// The map is a square grid of size x size texels centred on the eye, on the ground (altitude 0). Its
// plane is the azimuthal equidistant projection of the weather window (shaders/shared/weather_window.h):
// texel (i, j), column i from the west edge and row j from the NORTH edge (image order, top row first),
// covers the ground point at easting x = (i + 0.5 - size/2) * texelSizeM and northing
// y = (size/2 - j - 0.5) * texelSizeM, i.e. at arc distance |(x, y)| from the eye along azimuth
// atan2(x, y). On the GPU that point lies on the eye's osculating sphere (frame.earth.radiusM); its latitude
// and longitude are GeographicLib::AzimuthalEquidistant(WGS84).Reverse(eye, x, y), as for the window.
//
// Output image (rgba16f): r = key-light transmittance through every cloud layer [0, 1] (0 also where
// the light is below the local horizon); g = the cloud optical depth along the light ray (volumetric
// layers + cirrus, capped at SHADOW_MAX_OPTICAL_DEPTH); b, a = 0.
#ifndef SKY_SHARED_SHADOW_MAP_PARAMS_H
#define SKY_SHARED_SHADOW_MAP_PARAMS_H
#include "shaders/shared/bindings.h"

#define SHADOW_BINDING_FRAME 0          // uniform FrameParams (the frame's, unchanged)
#define SHADOW_BINDING_WEATHER 1        // sampler2DArray weather window, linear, clamp
#define SHADOW_BINDING_BASE_NOISE 2     // sampler3D, linear, repeat
#define SHADOW_BINDING_DETAIL_NOISE 3   // sampler3D, linear, repeat
#define SHADOW_BINDING_CURL_NOISE 4     // sampler2D, linear, repeat
#define SHADOW_BINDING_OUTPUT 5         // storage image rgba16f

// Optical depth at which the march stops: e^-12 = 6e-6 is below half-float resolution near 0.
#define SHADOW_MAX_OPTICAL_DEPTH 12.0f
// Once the light path holds this optical depth (transmittance < 2%), samples skip detail erosion: the
// rest can only darken what is already dark (the light march of cloud_lighting.glsl does the same at 0.3).
#define SHADOW_CHEAP_OPTICAL_DEPTH 4.0f
// Fewest samples given to each separate altitude band of cloud (a thin deck under a tall shell).
#define SHADOW_MIN_STEPS_PER_BAND 4u

// 48 bytes of push constants (Vulkan guarantees 128).
struct ShadowMapPush
{
    vec4 lightDirection;  // xyz: unit direction to the key light (eye ENU); w: unused
    vec4 grid;            // x: texel size (m); y: half width of the map (m); zw: unused
    uvec4 params;         // x: texels per side; y: density samples per texel along the light ray; zw: unused
};

#endif
