// SPDX-License-Identifier: MIT
// Per-frame uniform block of the cloud and composite passes (std140: vec4/uvec4 members only).
//
// Frames of reference: the GPU works in the eye's local east-north-up frame (metres, origin at the
// eye, z = ellipsoid normal at the eye). The earth around the eye is the osculating sphere of radius
// earth.x whose centre is at (0, 0, -earth.y) (docs/datums.md: no raw ECEF in float). Noise is looked up in
// earth-fixed axes so that clouds do not swim when the camera moves: noisePos = enuToEcef * p + layer
// offset, where the offsets (eye ECEF minus wind drift, modulo the noise period) are computed in
// double on the CPU.
#ifndef SKY_SHARED_FRAME_PARAMS_H
#define SKY_SHARED_FRAME_PARAMS_H
#include "shaders/shared/bindings.h"

struct FrameParams
{
    // The camera (skyservice/render/view_frustum.h ViewTangents): the ray of normalised device
    // coordinates ndc (y down) is cameraForward.xyz + ndc.x * cameraRight.w * cameraRight.xyz
    // - ndc.y * cameraUp.w * cameraUp.xyz.
    vec4 cameraRight;    // xyz: unit right axis (ENU); w: half the image width, tangent units (tan(fovY/2) * aspect)
    vec4 cameraUp;       // xyz: unit up axis (ENU); w: half the image height in tangent units (tan(fovY/2))
    // xyz: the ray through the image centre: the unit view axis (ENU), plus, for an off-centre frustum,
    // the centre's tangent offsets along the right and up axes (then not unit); w: eye altitude above
    // the ellipsoid (m)
    vec4 cameraForward;
    vec4 earth;          // x: local earth radius R (m); y: R + eye altitude (m); z: window warp radius r0 (m, window_warp.glsl); w: window half extent (m)
    vec4 shell;          // x: lowest cloud base in the window (m); y: highest volumetric top (m); z: max march distance (m); w: high-cloud altitude (m)
    vec4 sunDirection;   // xyz: unit direction to the sun (ENU); w: sun angular radius (rad)
    vec4 sunIrradiance;  // rgb: solar irradiance at the top of the atmosphere (renderer units); w: unused
    vec4 moonDirection;  // xyz: unit direction to the moon (ENU); w: unused
    vec4 moonIrradiance; // rgb: moonlight irradiance at the top of the atmosphere (phase applied); w: unused
    vec4 enuToEcef0;     // rows of the ENU -> earth-fixed rotation, used for noise lookups and the march jitter
    vec4 enuToEcef1;
    vec4 enuToEcef2;
    vec4 layerNoiseOffsetM[MAX_CLOUD_LAYERS + 1];  // xyz: noise-space offset per volumetric layer, then the high layer (m)
    vec4 layerRangeM[MAX_CLOUD_LAYERS + 1];        // x: lowest base, y: highest top of the layer in the window (m); z: anvil amount [0,1]; w: unused
    vec4 layerShearM[MAX_CLOUD_LAYERS + 1];        // xy: downwind displacement of the layer top relative to its base (ENU m); zw: unused
    vec4 noiseScale;     // x: base noise period (m); y: detail noise period (m); z: curl noise period (m); w: high-cloud texture period (m)
    vec4 cloudLook;      // x: extinction per metre at density 1; y: detail erosion strength; z: ambient strength; w: multiple-scattering octaves
    vec4 lightingTerms;  // x: octave attenuation a; y: octave contribution b; z: octave eccentricity c; w: powder strength
    vec4 phaseTerms;     // x: forward g; y: back g; z: forward weight; w: cone light step (m)
    vec4 ambientSky;     // rgb: average sky radiance above the clouds; w: ground albedo
    vec4 ambientGround;  // rgb: irradiance on the ground (for light bounced up into cloud bases); w: unused
    vec4 exposure;       // x: display exposure multiplier; y: animation time (s); zw: sub-pixel jitter of the view rays (pixels)
    uvec4 image;         // x: width; y: height; z: frame index (decorrelates the march jitter); w: flags (FRAME_FLAG_*)
    uvec4 march;         // x: max view steps; y: light samples (cone); z: beyond this distance (m) the cone's
                         // detailed near samples are taken as one (0: never; coneNearMergeBeyondM); w: unused
    // Temporal reprojection (skyservice/render/reprojection.h). The previous camera is given in the
    // current eye's ENU frame, computed in double on the CPU (docs/datums.md).
    // reprojection x: block size (1: full resolution, 4: one pixel of each 4x4 block marched);
    // yz: marched position in the block; w: 1 when the history images hold the previous frame
    uvec4 reprojection;
    // The previous camera projects a direction v to ndc = (dot(v, previousRight.xyz) / (z * previousRight.w),
    // -dot(v, previousUp.xyz) / (z * previousUp.w)), z = dot(v, previousForward.xyz). For an off-centre
    // frustum the right and up axes are shifted to measure from the image centre: right - centreX * forward
    // (then not unit; skyservice/render/reprojection.cpp).
    vec4 previousRight;     // xyz: previous camera right axis; w: its half image width in tangent units
    vec4 previousUp;        // xyz: previous camera up axis; w: its half image height in tangent units
    vec4 previousForward;   // xyz: previous camera unit view axis; w: unused
    vec4 previousEye;       // xyz: previous eye position relative to the current eye (m); w: unused
    // The lines the previous frame did not see, marched in full (shaders/lib/new_lines.glsl): x: first
    // column, y: how many columns (0: none); z: first row, w: how many rows.
    uvec4 newLines;
    // The weather window is centred on a lattice node near the eye, not on the eye
    // (skyservice/earth/window_lattice.h): window-plane position = windowOffsetM.xy + the map position
    // (m east, north of the eye) through windowAxes.
    vec4 windowOffsetM;     // xy: the eye's position on the window plane (m); zw: unused
    vec4 windowAxes;        // xy: window-plane image of 1 m east of the eye; zw: of 1 m north
    // World-space march jitter (shaders/lib/world_jitter.glsl). x: angle of one jitter texel (rad), one
    // pixel's height at the view axis, so two channels of the same height and vertical extent share the
    // texels.
    vec4 worldJitter;
    // Level of detail of the march with distance (QualitySettings). x, y: the detail erosion fades out
    // between these distances (m); z: beyond this distance (m) the light cone takes 3 cheap samples (0:
    // never); w: cone samples that may take the full (detailed) density, nearest first.
    vec4 marchLod;
    // The light volume (light_volume.h): xy: window-plane position (m) of its corner texel's corner; z:
    // texel size (m), 0 when there is none this frame (its tail starts after marchLod.w samples); w: where
    // no volume reaches, a lit sample within this distance (m) of the last cone that marched its far
    // samples takes those (0: never; RenderTuning::coneTailReuseM, cloud_lighting.glsl ConeTail).
    vec4 lightVolume;
    // x: view samples behind a transmittance below this take the base shape without detail erosion (0:
    // never; RenderTuning::detailMinTransmittance); y: those samples step this many times further; z: a
    // step inside a cloud covers at most this optical depth (0: no limit; maxStepOpticalDepth); w: deep lit
    // samples within this distance (m) of the last cone marched take its light (0: never; deepLightReuseM).
    vec4 detailLod;
    // The light volume's far cascade (light_volume.h), as lightVolume: xy corner, z texel size (m; 0: none);
    // w: only lit samples farther than this from the eye (m) take an earlier cone's far samples
    // (RenderTuning::coneTailReuseBeyondM).
    vec4 lightVolumeFar;
};

// frame flags
// The noise offsets (layerNoiseOffsetM) wrap at this many high-cloud periods (noiseScale.w: 384 km by
// default; skyservice/render/frame_setup.cpp): whatever the cloud shaders make periodic repeats with it.
#define NOISE_OFFSET_MODULUS_HIGH_PERIODS 16
#define FRAME_FLAG_NO_DETAIL 1u      // skip detail erosion (tests of the base shape)
#define FRAME_FLAG_NO_HIGH_CLOUD 2u  // skip the 2D cirrus layer
#define FRAME_FLAG_NO_LINEAR_OUTPUT 4u  // the composite writes no linear frame (none was asked for: 1x1 stand-in bound)
#define FRAME_FLAG_REPROJECTED 8u    // the composite takes fresh pixels from the block-resolution image, the rest from the cloud history
#define FRAME_FLAG_NO_SKIPPING 16u   // the march's search samples every step (no empty-space skipping: tests, A/B)
// The composite's optional outputs, each written only while a reader asks for it (1x1 stand-ins otherwise):
#define FRAME_FLAG_SKY_LAYER 32u     // the sky without clouds (linear, pre-exposed)
#define FRAME_FLAG_CLOUD_LAYER 64u   // the clouds after aerial perspective, premultiplied, + alpha
#define FRAME_FLAG_WRITE_CLOUD 128u  // reprojected frames: the full-resolution cloud image and depth it composited
// The depth layer (front and weighted cloud distance, RG32F): the march stores each ray's front distance, the
// reconstruct pass carries it through its own history, the composite writes the layer.
#define FRAME_FLAG_DEPTH_LAYER 256u
// The march's row counts (march_order.h rowLookups) sum the lookups of every ray instead of taking the
// slowest ray of each workgroup: the work a frame does, for counting (RenderTuning::marchLookupTotals).
#define FRAME_FLAG_LOOKUP_TOTALS 512u

#endif
