// SPDX-License-Identifier: MIT
// Atmosphere model shared by the atmosphere passes (GLSL) and the CPU (skyservice/sky/atmosphere.h):
// the uniform block, the LUT sizes, the descriptor slots and the sky-view push constants.
//
// Model: Bruneton 2017 ("Precomputed Atmospheric Scattering: a New Implementation", demo constants) and
// Hillaire 2020 ("A Scalable and Production Ready Sky and Atmosphere Rendering Technique", Table 1):
// Rayleigh and Mie densities fall off exponentially with altitude, ozone is a tent around 25 km.
// Units: metres, per-metre coefficients, radians. The earth is a sphere of radius radii.x (the local
// osculating radius at the eye, set per frame), the atmosphere ends 100 km above it.
#ifndef SKY_SHARED_ATMOSPHERE_PARAMS_H
#define SKY_SHARED_ATMOSPHERE_PARAMS_H
#include "shaders/shared/bindings.h"

// std140: vec4 members only, so the C++ layout is the GLSL layout (docs/style.md §7).
struct AtmosphereParams
{
    vec4 rayleighScattering;  // rgb: Rayleigh scattering at the bottom (1/m); w: Rayleigh scale height (m)
    vec4 mieScattering;       // rgb: Mie scattering at the bottom (1/m); w: Mie scale height (m)
    vec4 mieExtinction;       // rgb: Mie extinction at the bottom (1/m); w: Mie phase asymmetry g (Cornette-Shanks)
    vec4 ozoneAbsorption;     // rgb: ozone absorption at the peak of its tent profile (1/m); w: unused
    vec4 ozoneLayer;          // x: altitude of the ozone peak (m); y: half width of the tent (m); zw: unused
    vec4 radii;               // x: bottom (ground) radius (m); y: top radius (m); z: sun angular radius (rad); w: moon angular radius (rad)
    vec4 groundAlbedo;        // rgb: Lambertian ground albedo; w: unused
    vec4 solarIrradiance;     // rgb: solar irradiance at the top of the atmosphere (W m^-2 nm^-1 at 680, 550, 440 nm); w: unused
    // Ground fog, a band of extra extinction, all of it scattered (none when z is 0):
    vec4 groundFog;           // x: base, y: top altitude (m above the bottom); z: extinction inside (1/m); w: unused
};

// LUT sizes (Hillaire 2020 §4-5). Transmittance: x = view zenith, y = altitude (Bruneton mapping).
#define TRANSMITTANCE_LUT_WIDTH 256
#define TRANSMITTANCE_LUT_HEIGHT 64
// Multiple scattering: x = sun zenith cosine, y = altitude; 32^2 is what Hillaire found sufficient (§5.5).
#define MULTISCATTER_LUT_SIZE 32
// Directions integrated per multiple-scattering texel: 8 x 8 over the sphere (Hillaire uses 64).
#define MULTISCATTER_SQRT_DIRECTIONS 8
// Sky view: x = absolute azimuth in ENU over [0, 2 pi) (sample with REPEAT in u), y = view zenith with
// more rows near the horizon. 192x108 is Hillaire's size; the azimuth is absolute here so that one LUT
// holds both the sun and the moon.
#define SKY_VIEW_LUT_WIDTH 192
#define SKY_VIEW_LUT_HEIGHT 108

// Ray-march step counts. Transmittance: 40 steps on a quadratic grid stay within 0.7% (0.0011 absolute)
// of a 20000-step quadrature, the worst at the horizon. Sky view: Hillaire varies 30 to 60 steps with
// the path length; we do the same (within 0.5% of a 4000-step reference, tests/unit/test_atmosphere.cpp).
#define ATMOSPHERE_TRANSMITTANCE_STEPS 40
#define ATMOSPHERE_MULTISCATTER_STEPS 20
#define ATMOSPHERE_SKY_VIEW_MIN_STEPS 30
#define ATMOSPHERE_SKY_VIEW_MAX_STEPS 60
// Aerial perspective integrated along one ray (atmosphere_reference.h aerialPerspectiveCpu, in tests): 10 steps.
#define ATMOSPHERE_AERIAL_STEPS 10
// Aerial-perspective LUT (shaders/atmosphere/aerial_perspective_lut.comp.glsl): the in-scattered light
// and the transmittance between the eye and a distance along a direction, for the composite, which
// otherwise integrated 10 steps of 4 LUT fetches per cloudy pixel.
// Directions use the sky-view LUT's mapping (absolute azimuth, zenith rows crowded at the horizon), not
// screen froxels (Hillaire 2020 §5.4), so that channels at a seam read the same texels. 80 x 44
// directions (an even row count: no row lies exactly on the horizon, where the GPU and the CPU
// reference disagree on whether the ray grazes the ground) x 24 distances up to 700 km (the march's
// default reach; farther is read at 700 km; atmosphere.glsl aerialSliceDistanceM), 2 steps per slice:
// 1.35 MB for both LUTs (the 1080p budget is 64 MB in all); within 0.7 % of a 400-step integral.
#define AERIAL_LUT_WIDTH 80
#define AERIAL_LUT_HEIGHT 44
#define AERIAL_LUT_SLICES 24
#define AERIAL_LUT_MAX_DISTANCE_M 700000.0f
#define AERIAL_LUT_STEPS_PER_SLICE 2

// Descriptor slots of the atmosphere passes (set 0), contiguous per pass: the transmittance pass
// declares 0-1, the multiple-scattering pass 0-2, the sky-view pass 0-3, the aerial-perspective pass
// 0-4 (OUTPUT: the in-scattered light, OUTPUT_TRANSMITTANCE: the transmittance).
#define ATMOSPHERE_BINDING_PARAMS 0          // uniform AtmosphereParams
#define ATMOSPHERE_BINDING_OUTPUT 1          // storage image rgba16f (the LUT the pass writes)
#define ATMOSPHERE_BINDING_TRANSMITTANCE 2   // sampler2D, linear, clamp to edge
#define ATMOSPHERE_BINDING_MULTISCATTER 3    // sampler2D, linear, clamp to edge
#define ATMOSPHERE_BINDING_OUTPUT_TRANSMITTANCE 4  // storage image rgba16f (aerial-perspective pass)

// Flags of SkyViewPushConstants.flags.x
#define SKY_VIEW_FLAG_GROUND 1u  // add the lit ground (albedo) where view rays hit the earth

// Push constants of sky_view_lut.comp.glsl (80 bytes). Directions are unit vectors in the eye's
// east-north-up frame; irradiances are at the top of the atmosphere, in the renderer's units. The LUT is
// rgba16f: with irradiances in W m^-2 nm^-1 a moonlit sky (~1e-7) falls below half-float's normal
// range (6e-5), so pass exposure-scaled irradiances (or make the LUT rgba32f) for night scenes.
struct SkyViewPushConstants
{
    vec4 sunDirection;    // xyz: unit direction to the sun (ENU); w: camera distance from the earth centre (m)
    vec4 sunIrradiance;   // rgb: sun irradiance; w: unused
    vec4 moonDirection;   // xyz: unit direction to the moon (ENU); w: unused
    vec4 moonIrradiance;  // rgb: moon irradiance (phase already applied); w: unused
    uvec4 flags;          // x: SKY_VIEW_FLAG_*; yzw: unused
};

#endif
