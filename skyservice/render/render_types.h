// SPDX-License-Identifier: MIT
// What a render is asked for and what it returns.
#pragma once

#include "skyservice/earth/geodesy.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sky
{

/// Knobs of the cloud model and the march that a user or a quality preset sets (the TOML config,
/// config/default.toml). Defaults are the published constants (docs/model.md), tuned. The knobs that exist
/// only for experiments are in RenderTuning (render_tuning.h).
struct QualitySettings
{
    uint32_t maxViewSteps = 160;     ///< view samples per ray at most
    uint32_t lightSamples = 6;       ///< cone samples toward the light (plus one long sample)
    /// Cone samples (nearest first) that may take the full, detail-eroded density; the rest are cheap,
    /// and near the eye they come from the light volume (shaders/shared/light_volume.h).
    uint32_t fullConeSamples = 2;
    /// Texel size of the light volume on the ground (m; LIGHT_VOLUME_SIZE texels a side); 0: no volume,
    /// every cone sample marched.
    double lightVolumeTexelM = 160.0;
    /// Frames that march fewer rays than this (pixels / march block^2) draw no light volume: its build
    /// (221 184 texels x 5 density lookups) then costs more than it saves: on a small reprojected frame
    /// the volume is slower, on a 1920x1080 one faster (BENCHMARKS.md). A setting: the device decides,
    /// not an experiment knob.
    uint32_t lightVolumeMinRays = 50000;
    uint32_t octaves = 3;            ///< multiple-scattering octaves (Wrenninge 2013)
    double extinctionPerM = 0.045;   ///< cloud extinction at density 1 (1/m); ~20 m mean free path
    double detailErosion = 0.35;     ///< strength of the detail-noise erosion
    double ambientStrength = 1.0;    ///< multiplier on sky and ground ambient light
    double octaveAttenuation = 0.5;  ///< a: extinction scale per octave
    /// b: energy per octave; the octaves beyond the last are kept as one diffuse term (cloud_lighting.glsl)
    double octaveContribution = 0.75;
    double octaveEccentricity = 0.5; ///< c: phase eccentricity scale per octave
    double powderStrength = 0.6;     ///< weight of Beer-powder darkening seen away from the light
    double phaseForwardG = 0.8;      ///< forward lobe of the two-lobe Henyey-Greenstein
    double phaseBackG = -0.3;        ///< back lobe
    double phaseForwardWeight = 0.7; ///< share of the forward lobe
    double coneStepM = 70.0;         ///< first light step (m); step i is (i+1) times this
    double baseNoisePeriodM = 8000.0;    ///< metres covered by one tile of the 128^3 base noise
    double detailNoisePeriodM = 1500.0;  ///< one tile of the 32^3 detail noise
    double curlNoisePeriodM = 6000.0;    ///< one tile of the curl noise
    double highNoisePeriodM = 24000.0;   ///< one tile of the high-cloud texture
    double windowHalfExtentM = 800000.0; ///< weather window half width (covers the horizon at 12 km)
    double windowWarpRadiusM = 150000.0; ///< radial warp r0: ~1 km texels at the eye, ~40 km at the edge
    double maxDistanceM = 700000.0;      ///< no cloud marched beyond this distance
    uint32_t noiseSeed = 1;              ///< seed of every noise texture, made when the renderer starts
    bool detail = true;                  ///< detail erosion on
    bool highCloud = true;               ///< cirrus layer on
    uint32_t accumulationFrames = 1;     ///< frames averaged, each with new march jitter and sub-pixel offset
    uint32_t shadowSteps = 48;           ///< density samples per shadow-map texel along the light ray
    /// Temporal reprojection (skyservice/render/reprojection.h): march one pixel of every 4x4 block and
    /// reproject the rest from the renderer's previous reprojected frame. accumulationFrames is ignored.
    bool reprojected = false;

    bool operator==(const QualitySettings&) const = default;
};

/// The images a frame copies back to the host (bits of ViewRequest::readback). What is not asked for
/// stays on the GPU (and is not even drawn, for the layers only a reader needs).
enum ReadbackBits : uint32_t
{
    kReadDisplay = 1u,     ///< RenderResult::displayRgba8: tone-mapped sRGB
    kReadCloud = 2u,       ///< cloudRgbaHalf: the clouds before aerial perspective (EXR files, statistics)
    kReadDepth = 4u,       ///< cloudDepthM: transmittance-weighted cloud distance
    kReadSky = 8u,         ///< skyRgbaHalf: linear sky radiance without clouds
    kReadCloudLayer = 16u, ///< cloudLayerRgbaHalf: premultiplied cloud radiance after aerial perspective + alpha
    kReadShadowDetail = 32u,  ///< shadowOpticalDepth as well as shadowTransmittance (files, tests)
    kReadDepthLayer = 64u, ///< depthLayerM: the cloud's front and weighted distance, two floats a pixel
    /// Layers drawn on the GPU without being copied back: the zero-copy export copies them from the
    /// renderer's images (skyservice/render/frame_export.h). A kRead* bit of the same layer draws it too.
    kDrawSky = 128u,
    kDrawCloudLayer = 256u,
    kDrawDepthLayer = 512u,
    ///< what one-shot renders want
    kReadEverything = kReadDisplay | kReadCloud | kReadDepth | kReadShadowDetail | kReadDepthLayer,
};

/// An off-centre frustum, as the channels of a display wall have (CIGI View Definition): the angles from
/// the view axis to the left, right, upper and lower edges (degrees, each in (-85, 85), left + right and
/// up + down > 1). When `asymmetric` is set it replaces ViewRequest::fovYDeg.
struct Frustum
{
    bool asymmetric = false;
    double leftDeg = 0, rightDeg = 0, upDeg = 0, downDeg = 0;
};

/// One view to render.
struct ViewRequest
{
    EyePose pose;
    double fovYDeg = 60.0;           ///< vertical field of view (degrees)
    Frustum frustum;                 ///< off-centre frustum (replaces fovYDeg when asymmetric)
    uint32_t width = 640;
    uint32_t height = 360;
    int64_t unixTimeS = 0;           ///< UTC time of the view (s since 1970)
    /// The part of a second after unixTimeS, [0, 1): the clouds' wind drift moves with it (a service frame
    /// at 60 Hz is not drawn where its second began); the sun and moon use whole seconds.
    double unixTimeFractionS = 0.0;
    /// Meteorological visibility near the ground (m): sets the haze (skyservice/sky/atmosphere.h
    /// setHazeVisibility); 0 = the clear atmosphere's own (~170 km).
    double visibilityM = 0.0;
    /// Ground fog (setGroundFog): a band from fogBaseM to fogTopM (m above the ellipsoid) with visibility
    /// fogVisibilityM (m) inside; none when that is 0.
    double fogBaseM = 0.0, fogTopM = 0.0, fogVisibilityM = 0.0;
    bool shadowMap = false;          ///< also render the cloud shadow map (skyservice/render/shadow_map.h)
    uint32_t shadowMapSize = 1024;   ///< shadow map texels per side
    double shadowMapExtentM = 150000.0;  ///< edge length of the shadow map's square on the ground (m)
    /// What to copy back (ReadbackBits); the linear frame follows linearOutput, and copyToHost = false
    /// copies nothing.
    uint32_t readback = kReadEverything;
    /// Copy the images `readback` asks for to RenderResult; false leaves them empty (sky-bench's timed
    /// frames), the layers of kDraw* bits are drawn all the same.
    bool copyToHost = true;
    /// Render the linear frame (RenderResult::linearRgbaHalf: EXR files, statistics). Without it the
    /// composite writes only the display image and the renderer holds no linear image (16.6 MB at
    /// 1080p); the service and sky-bench turn it off unless a caller reads it.
    bool linearOutput = true;
};

/// Where a shadow map lies on the earth, typed (RenderResult::shadowMap has the same as JSON with prose):
/// the azimuthal equidistant projection centred on the eye (skyservice/render/shadow_map.h).
struct ShadowMapReference
{
    double centreLatDeg = 0, centreLonDeg = 0;  ///< projection centre (degrees)
    double extentM = 0;                         ///< edge length of the square on the ground (m)
    double cornerLatDeg[4] = {}, cornerLonDeg[4] = {};  ///< outer corners NW, NE, SE, SW (degrees)
    double keyLightAzimuthDeg = 0, keyLightElevationDeg = 0;  ///< the sun, or the moon at night
    bool keyLightIsMoon = false;
};

/// Pixels and facts of a finished render. Images are row-major, top row first.
struct RenderResult
{
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint16_t> cloudRgbaHalf;  ///< premultiplied cloud radiance + alpha (1 - transmittance), half floats
    /// Transmittance-weighted cloud distance (m), 0 where alpha is 0. Reprojected frames: the pixels not
    /// marched this frame come from the history (shaders/lib/cloud_history.glsl): radiance to 2^-9 of
    /// the brightest channel, alpha to 1/131070, depth to 1.2e-4 relative.
    std::vector<float> cloudDepthM;
    std::vector<uint16_t> linearRgbaHalf; ///< final linear radiance (sky + clouds), half floats; empty without ViewRequest::linearOutput
    std::vector<uint8_t> displayRgba8;    ///< tone-mapped sRGB
    /// Compositing layers (kReadSky, kReadCloudLayer), half floats, pre-exposed like linearRgbaHalf: the sky
    /// without clouds, and the clouds as seen through the air in front of them, premultiplied, so that
    /// linear = sky * (1 - cloud.a) + cloud.rgb.
    std::vector<uint16_t> skyRgbaHalf;
    std::vector<uint16_t> cloudLayerRgbaHalf;
    /// The depth layer (kReadDepthLayer), two floats a pixel (m): the cloud's front, where the opacity
    /// accumulated from the eye first reaches 2 % (shaders/clouds/cloud_path.glsl kCloudFrontOpacity; the
    /// weighted distance where it never does; never beyond it), then the transmittance-weighted distance
    /// (cloudDepthM); both 0 where alpha is 0. Reprojected frames carry the front of the pixels not marched
    /// through a history of its own (float), the depth through the cloud history's.
    std::vector<float> depthLayerM;
    std::map<std::string, double> gpuMs;  ///< GPU time per pass (ms)
    double cpuSetupMs = 0;                ///< CPU time to prepare the frame (weather window etc.)
    double sunAzimuthDeg = 0, sunElevationDeg = 0;
    double moonAzimuthDeg = 0, moonElevationDeg = 0, moonIlluminatedFraction = 0;
    double exposure = 1;
    bool moonIsKeyLight = false;
    /// The weather this frame drew: the renderer's version of it (one per setWeather or staged weather
    /// swapped in: a staged weather shows from a frame that depends on timing) and its valid time.
    uint64_t weatherVersion = 0;
    int64_t weatherValidTimeUnixS = 0;
    /// Reprojected frames: one pixel of every marchBlockPx^2 was marched (4 normally; 2 near and 1
    /// inside a cloud layer, skyservice/render/reprojection.h), and why it was not 4 ("" when it was).
    /// Full-resolution frames: 1 and "".
    uint32_t marchBlockPx = 1;
    /// The march's workgroup rows (WORKGROUP_SIZE_2D rows of marched pixels each, top first): the order
    /// they were launched in (index: launch position, value: row), and per row the sum over its workgroups
    /// of their rays' largest density-lookup count (shaders/shared/march_order.h).
    std::vector<uint32_t> marchRowOrder;
    std::vector<uint32_t> marchRowLookups;
    std::string marchBlockReason;
    /// Cloud shadow map (when ViewRequest::shadowMap): shadowMapSize^2 texels, row-major, north row first,
    /// west column first (skyservice/render/shadow_map.h); gpuMs["shadowMap"] holds its GPU time.
    uint32_t shadowMapSize = 0;               ///< texels per side; 0 when no shadow map was rendered
    std::vector<float> shadowTransmittance;   ///< key-light transmittance through the clouds [0, 1]
    std::vector<float> shadowOpticalDepth;    ///< cloud optical depth along the light ray (capped at 12)
    nlohmann::json shadowMap;                 ///< metadata: projection, corners, sun, valid time
    ShadowMapReference shadowReference;       ///< the same geo-reference, typed (for the frame ring)
    /// Which drawing of the shadow map this frame carries: frames whose map would not differ by half a
    /// texel reuse the last drawing (shadow_map.h) with its metadata; equal ids hold equal texels.
    uint64_t shadowMapId = 0;
    bool shadowMapRedrawn = false;            ///< this frame drew its shadow map (false: reused)
};

}  // namespace sky
