// SPDX-License-Identifier: MIT
// Per-frame uniform block of the cloud and composite passes: named parts, each a struct of named members
// with their units. std140: every struct starts on 16 bytes; scalars pack, a vec2 takes an 8-byte slot,
// a vec3 starts a 16-byte slot whose last 4 bytes the next float may take. Every part is written so
// that it is a whole number of 16-byte slots with no hole (unused members fill them), so the C++ layout
// is the std140 one (static_asserts at the end) and no byte of the block is padding.
//
// Frames of reference: the GPU works in the eye's local east-north-up frame (metres, origin at the
// eye, z = ellipsoid normal at the eye). The earth around the eye is the osculating sphere of radius
// earth.radiusM whose centre is at (0, 0, -earth.centreToEyeM) (docs/datums.md: no raw ECEF in float).
// Noise is looked up in earth-fixed axes so that clouds do not swim when the camera moves: noisePos =
// enuToEcef * p + layer offset, where the offsets (eye ECEF minus wind drift, modulo the noise period)
// are computed in double on the CPU.
//
// Built in one place: skyservice/render/frame_setup.cpp makeFrameParams.
#ifndef SKY_SHARED_FRAME_PARAMS_H
#define SKY_SHARED_FRAME_PARAMS_H
#include "shaders/shared/bindings.h"

// The camera (skyservice/render/view_frustum.h ViewTangents): the ray of normalised device coordinates
// ndc (y down) is centreRayEnu + ndc.x * halfWidthTan * rightEnu - ndc.y * halfHeightTan * upEnu.
struct CameraParams
{
    vec3 rightEnu;        // unit right axis
    float halfWidthTan;   // half the image width in tangent units (tan(fovY/2) * aspect)
    vec3 upEnu;           // unit up axis
    float halfHeightTan;  // half the image height in tangent units (tan(fovY/2))
    // The ray through the image centre: the unit view axis, plus, for an off-centre frustum, the
    // centre's tangent offsets along the right and up axes (then not unit).
    vec3 centreRayEnu;
    float eyeAltitudeM;   // above the ellipsoid
};

// The osculating sphere at the eye.
struct EarthParams
{
    float radiusM;       // local earth radius R
    float centreToEyeM;  // R + eye altitude
    float unused0;
    float unused1;
};

// The weather window (skyservice/weather/window_lattice.h): it is centred on a lattice node near the eye,
// not on the eye; window-plane position = eyeOnPlaneM + the map position (m east, north of the eye)
// through eastAxis and northAxis.
struct WindowParams
{
    vec2 eyeOnPlaneM;    // the eye's position on the window plane
    float warpRadiusM;   // window warp radius r0 (window_warp.glsl)
    float halfExtentM;   // the window's half extent
    vec2 eastAxis;       // window-plane image of 1 m east of the eye
    vec2 northAxis;      // of 1 m north
};

// The altitudes the march looks between.
struct CloudShellParams
{
    float lowestBaseM;         // lowest cloud base in the window
    float highestTopM;         // highest volumetric top
    float maxMarchDistanceM;
    float highCloudAltitudeM;  // of the 2D high-cloud layer (0: none)
};

// The key lights.
struct SunMoonParams
{
    vec3 sunDirectionEnu;       // unit direction to the sun
    float sunAngularRadiusRad;
    vec3 sunIrradiance;         // at the top of the atmosphere (renderer units, pre-exposed)
    float unused0;
    vec3 moonDirectionEnu;      // unit direction to the moon
    float unused1;
    vec3 moonIrradiance;        // moonlight at the top of the atmosphere (phase applied, pre-exposed)
    float unused2;
};

// Rows of the ENU -> earth-fixed rotation, used for noise lookups and the march jitter.
struct EnuToEcefParams
{
    vec3 row0;
    float unused0;
    vec3 row1;
    float unused1;
    vec3 row2;
    float unused2;
};

// Per volumetric layer k < MAX_CLOUD_LAYERS; at MAX_CLOUD_LAYERS the anvil slab, which moves with the
// upper wind (its noise offset is also the high cloud's).
struct CloudLayerParams
{
    vec3 noiseOffsetM;   // noise-space offset of the layer
    float anvilAmount;   // [0,1] (0 for the anvil slab itself)
    float lowestBaseM;   // lowest base of the layer in the window (1e9: no layer)
    float highestTopM;   // highest top of the layer in the window (-1e9: no layer)
    vec2 topShearM;      // downwind displacement of the layer top relative to its base (ENU m)
};

// Noise periods.
struct NoisePeriodParams
{
    float baseM;
    float detailM;
    float curlM;
    float highCloudM;    // high-cloud texture period
};

// The cloud model's scattering terms (QualitySettings).
struct CloudLookParams
{
    float extinctionPerM;      // at density 1
    float detailErosion;       // detail erosion strength
    float ambientStrength;
    uint octaves;              // multiple-scattering octaves
    float octaveAttenuation;   // a
    float octaveContribution;  // b
    float octaveEccentricity;  // c
    float powderStrength;
    float phaseForwardG;
    float phaseBackG;
    float phaseForwardWeight;
    float coneStepM;           // light cone step
};

// Light from the sky and the ground.
struct AmbientParams
{
    vec3 skyRadiance;       // average sky radiance above the clouds
    float groundAlbedo;
    vec3 groundIrradiance;  // on the ground (for light bounced up into cloud bases)
    float unused0;
};

// The image this frame makes.
struct ImageParams
{
    uint widthPx;
    uint heightPx;
    uint flags;      // FRAME_FLAG_*
    float exposure;  // display exposure multiplier
};

// Where this frame lies in time and in an accumulation of frames.
struct SequenceParams
{
    vec2 rayJitterPx;      // sub-pixel offset of the view rays
    uint frameIndex;       // decorrelates the march jitter
    float animationTimeS;  // seconds since the weather's valid time (its wind drift is in the noise offsets)
};

// The march's budget, jitter and level of detail with distance (QualitySettings, RenderTuning).
struct MarchParams
{
    uint maxViewSteps;
    uint coneSamples;            // light samples per cone
    // Beyond this distance the cone's detailed near samples are taken as one (0: never;
    // RenderTuning::coneNearMergeBeyondM).
    uint coneNearMergeBeyondM;
    // World-space march jitter (shaders/lib/world_jitter.glsl): the angle of one jitter texel, one
    // pixel's height at the view axis, so two channels of the same height and vertical extent share
    // the texels.
    float jitterTexelRad;
    // The detail erosion fades out between these distances.
    float detailFadeStartM;
    float detailFadeEndM;
    float coneCheapBeyondM;      // beyond this distance the light cone takes 3 cheap samples (0: never)
    uint fullConeSamples;        // cone samples that may take the full (detailed) density, nearest first
    // View samples behind a transmittance below this take the base shape without detail erosion (0:
    // never; detailMinTransmittance); those samples step deepStepFactor times further.
    float detailMinTransmittance;
    float deepStepFactor;
    float maxStepOpticalDepth;   // a step inside a cloud covers at most this optical depth (0: no limit)
    float unused0;
};

// Reuse of earlier light cones (RenderTuning; cloud_lighting.glsl ConeTail).
struct LightReuseParams
{
    // Where no light volume reaches, a lit sample within this distance of the last cone that marched
    // its far samples takes those (0: never; coneTailReuseM) ...
    float coneTailReuseM;
    // ... but only lit samples farther than this from the eye (coneTailReuseBeyondM).
    float coneTailReuseBeyondM;
    float deepLightReuseM;       // deep lit samples this close to the last cone marched take its light (0: never)
    float unused0;
};

// A light volume (skyservice/render/light_volume.h) on the window plane.
struct LightVolumeCascadeParams
{
    vec2 cornerM;   // window-plane position of its corner texel's corner
    float texelM;   // texel size; 0 when there is none this frame
    float unused0;
};

// The light volume and its far cascade (LIGHT_VOLUME_FAR_SCALE times wider texels). The volume's
// tail starts after march.fullConeSamples samples.
struct LightVolumeParams
{
    LightVolumeCascadeParams nearCascade;
    LightVolumeCascadeParams farCascade;
};

// The previous camera (given in the current eye's ENU frame, computed in double on the CPU,
// docs/datums.md) projects a direction v to ndc = (dot(v, rightEnu) / (z * halfWidthTan),
// -dot(v, upEnu) / (z * halfHeightTan)), z = dot(v, forwardEnu). For an off-centre frustum the right and
// up axes are shifted to measure from the image centre: right - centreX * forward (then not unit;
// skyservice/render/reprojection.cpp).
struct PreviousCameraParams
{
    vec3 rightEnu;
    float halfWidthTan;
    vec3 upEnu;
    float halfHeightTan;
    vec3 forwardEnu;     // unit view axis
    float unused0;
    vec3 eyeEnuM;        // the previous eye relative to the current eye
    float unused1;
};

// The lines the previous frame did not see, marched in full (shaders/lib/new_lines.glsl).
struct NewLinesParams
{
    uint firstColumn;
    uint columnCount;  // 0: none
    uint firstRow;
    uint rowCount;     // 0: none
};

// Temporal reprojection (skyservice/render/reprojection.h).
struct ReprojectionParams
{
    uvec2 phasePx;        // the marched position in the block
    uint blockPx;         // 1: full resolution, 4: one pixel of each 4x4 block marched
    uint historyValid;    // 1 when the history images hold the previous frame
    PreviousCameraParams previous;
    NewLinesParams newLines;
};

struct FrameParams
{
    CameraParams camera;
    EarthParams earth;
    WindowParams window;
    CloudShellParams shell;
    SunMoonParams light;
    EnuToEcefParams enuToEcef;
    CloudLayerParams layers[MAX_CLOUD_LAYERS + 1];
    NoisePeriodParams noisePeriod;
    CloudLookParams look;
    AmbientParams ambient;
    ImageParams image;
    SequenceParams sequence;
    MarchParams march;
    LightReuseParams lightReuse;
    LightVolumeParams lightVolume;
    ReprojectionParams reprojection;
};

#ifdef __cplusplus
#include <cstddef>
// The std140 layout, written out: a part that gained a hole would move these.
static_assert(sizeof(CameraParams) == 48 && sizeof(EarthParams) == 16 && sizeof(WindowParams) == 32 &&
                  sizeof(CloudShellParams) == 16 && sizeof(SunMoonParams) == 64 && sizeof(EnuToEcefParams) == 48 &&
                  sizeof(CloudLayerParams) == 32 && sizeof(NoisePeriodParams) == 16 && sizeof(CloudLookParams) == 48 &&
                  sizeof(AmbientParams) == 32 && sizeof(ImageParams) == 16 && sizeof(SequenceParams) == 16 &&
                  sizeof(MarchParams) == 48 && sizeof(LightReuseParams) == 16 && sizeof(LightVolumeParams) == 32 &&
                  sizeof(PreviousCameraParams) == 64 && sizeof(NewLinesParams) == 16 &&
                  sizeof(ReprojectionParams) == 96,
              "frame_params.h: a part is no longer whole 16-byte slots");
static_assert(offsetof(WindowParams, eastAxis) == 16 && offsetof(CloudLayerParams, topShearM) == 24 &&
                  offsetof(SequenceParams, frameIndex) == 8 && offsetof(ReprojectionParams, previous) == 16,
              "frame_params.h: a member left its std140 offset");
static_assert(offsetof(FrameParams, earth) == 48 && offsetof(FrameParams, layers) == 224 &&
                  offsetof(FrameParams, noisePeriod) == 384 && offsetof(FrameParams, image) == 480 &&
                  offsetof(FrameParams, march) == 512 && offsetof(FrameParams, lightVolume) == 576 &&
                  offsetof(FrameParams, reprojection) == 608 && sizeof(FrameParams) == 704,
              "frame_params.h: a part left its std140 offset");
#endif

// frame flags
// The noise offsets (CloudLayerParams::noiseOffsetM) wrap at this many high-cloud periods
// (noisePeriod.highCloudM: 384 km by default; skyservice/render/frame_setup.cpp): whatever the cloud
// shaders make periodic repeats with it.
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
