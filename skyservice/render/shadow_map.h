// SPDX-License-Identifier: MIT
// The geo-referenced cloud shadow map (docs/model.md): key-light transmittance through every cloud layer
// (volumetric and cirrus) on a square grid of ground points centred on the eye, plus the metadata an
// image generator needs to drape it on its terrain.
//
// Projection: the weather window's (shaders/shared/shadow_map_params.h has the texel convention).
// The map plane is the azimuthal equidistant projection centred on the eye: the point at easting x,
// northing y lies at distance sqrt(x^2 + y^2) from the eye along azimuth atan2(x, y). Its latitude and
// longitude are GeographicLib::AzimuthalEquidistant(Geodesic::WGS84()).Reverse (geodesics on WGS84),
// which is how the weather window places the model's cells; the GPU puts the same point on the eye's
// osculating sphere (error < 1 m within 50 km, 10 m at 200 km: skyservice/earth/geodesy.h).
//
// Usage (inside a frame): validateShadowMapRequest, ensureShadowMapImages, reserveShadowMapReadback,
// recordShadowMap, then collectShadowMap.
#pragma once

#include "shaders/shared/shadow_map_params.h"
#include "skyservice/render/frame_context.h"
#include "skyservice/render/noise_textures.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/pass_images.h"
#include "skyservice/render/render_tuning.h"
#include "skyservice/render/render_types.h"
#include "skyservice/sky/ephemeris.h"
#include "skyservice/vk/programs.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace sky
{

/// Where the texels of a shadow map lie on the earth.
struct ShadowMapGeometry
{
    double centreLatDeg = 0;  ///< latitude of the projection centre, the eye (degrees)
    double centreLonDeg = 0;  ///< longitude of the projection centre (degrees)
    uint32_t sizeTexels = 0;  ///< texels per side
    double extentM = 0;       ///< edge length of the square (meters)

    /// Edge length of one texel (meters).
    double texelSizeM() const { return extentM / double(sizeTexels); }
    /**
     * @param[in] column texel column from the west edge (0.5 = centre of the first column).
     * @param[in] row texel row from the north edge (0.5 = centre of the first row).
     * @return easting and northing on the projection plane (meters from the centre).
     **********************************************************************/
    glm::dvec2 planePositionM(double column, double row) const;
    /**
     * @param[in] eastNorthM easting and northing on the projection plane (meters).
     * @param[out] latDeg latitude (degrees).
     * @param[out] lonDeg longitude (degrees, [-180, 180]).
     **********************************************************************/
    void toLatLon(const glm::dvec2& eastNorthM, double& latDeg, double& lonDeg) const;
    /**
     * @param[in] latDeg latitude (degrees).
     * @param[in] lonDeg longitude (degrees).
     * @return easting and northing on the projection plane (meters).
     **********************************************************************/
    glm::dvec2 fromLatLon(double latDeg, double lonDeg) const;
};

/// The key light of the clouds, as the cloud shaders pick it (cloud_lighting.glsl, moonIsKeyLight):
/// the sun down to 4 degrees below the horizon (z > -0.07), else the moon.
bool moonIsKeyLight(const SunMoon& sunMoon);

/**
 * Check the shadow-map part of a request.
 *
 * @param[in,out] pass the pass (what it drew last).
 * @param[in] in the weather window and noise the frame draws.
 * @param[in] request the view; shadowMapSize must be in [8, 8192], shadowMapExtentM in [100 m, 2 x the
 *   weather window's half extent] (the weather window must cover the map).
 * @param[in] quality the settings; shadowSteps must be in [1, 1024].
 * @param[out] error a message naming the field when the request is invalid.
 * @return true when the request is valid or asks for no shadow map.
 **********************************************************************/
bool validateShadowMapRequest(const ViewRequest& request, const QualitySettings& quality, std::string& error);

/**
 * The metadata of a shadow map, as written under "shadowMap" in the render's JSON sidecar.
 *
 * @param[in] geometry where the map lies.
 * @param[in] sunMoon the sun and moon at the eye.
 * @param[in] earthRadiusM radius of the osculating sphere the GPU used (meters).
 * @param[in] unixTimeS the view's UTC time, the map's valid time (s since 1970).
 * @param[in] weatherValidTimeUnixS the weather snapshot's valid time (s since 1970).
 * @return projection, centre, extent, texel size, corners (outer edges of the grid, lat/lon by
 *   AzimuthalEquidistant::Reverse on WGS84), sun and key-light direction (ENU unit vector, azimuth,
 *   elevation), valid times, and what the pixels hold.
 **********************************************************************/
nlohmann::json shadowMapMetadata(const ShadowMapGeometry& geometry, const SunMoon& sunMoon, double earthRadiusM,
                                 int64_t unixTimeS, int64_t weatherValidTimeUnixS);

/// What the map in ShadowMapPass's images was drawn for, and what was published with it. A later frame
/// reuses it (no dispatch, the same metadata and id) while a new drawing would not differ: the same size,
/// extent, quality, weather and window, the same second (the clouds drift with the wind within it: a map is
/// at most a second behind them), the key light's shadows moved less
/// than half a texel, and the eye (the map's centre) moved less than 1/64 of the extent. The map is
/// geo-referenced by its own centre, so a reused map is exact where it lies (within the second).
struct ShadowMapDrawing
{
    bool valid = false;
    uint64_t id = 0;                  ///< counts drawings (RenderResult::shadowMapId)
    uint32_t sizeTexels = 0;
    double extentM = 0;
    QualitySettings quality;
    RenderTuning tuning;
    uint64_t weatherVersion = 0;      ///< and valid time: the snapshot drawn from (WindowKey)
    int64_t weatherValidTimeUnixS = 0;
    const void* window = nullptr;     ///< the weather window drawn from (ShadowMapInputs::window)
    int64_t unixTimeS = 0;            ///< the view's whole second: a map is at most a second behind the wind
    glm::dvec3 eyeEcefM{0.0};
    glm::dvec3 lightEnu{0.0};
    bool lightIsMoon = false;
    nlohmann::json metadata;          ///< RenderResult::shadowMap of the drawing
    ShadowMapReference reference;     ///< RenderResult::shadowReference of the drawing
};

/// The pass's program, its images and what they hold.
struct ShadowMapPass
{
    Program program;
    Image image;  ///< rgba16f (transmittance, optical depth), sizeTexels^2, GENERAL; (re)made with the size
    Image transmittance;  ///< r32f: the transmittance as readers take it (blitted from `image`)
    ShadowMapDrawing drawn;  ///< what `image` and `transmittance` hold
    uint64_t transmittanceCopies = 0;  ///< copies of `transmittance` to a readback buffer (tests)
};

/// Where a frame's shadow map lies in its readback buffer.
struct ShadowMapReadback
{
    bool recorded = false;             ///< the frame has a shadow map (drawn or reused)
    bool redrawn = false;              ///< it drew it (its timestamps are written)
    ReadbackRegion transmittance;      ///< float texels
    ReadbackRegion detail;             ///< the RGBA16F image (kReadShadowDetail)
};

/// Loads the shadow_map program (the image is made on first use).
SkyStatus createShadowMapPass(const Context& ctx, ShadowMapPass& pass);
void destroyShadowMapPass(const Context& ctx, MemoryTracker& memory, ShadowMapPass& pass);

/// Makes the shadow-map images of `sizeTexels` (before the frame's commands begin; pass_images.h: a resize
/// idles nothing).
SkyStatus ensureShadowMapImages(ShadowMapPass& pass, ImageChanges& changes, uint32_t sizeTexels);

/// What the shadow map reads: the frame's weather window and the noise.
struct ShadowMapInputs
{
    const Image& weatherWindow;
    const NoiseTextures& noise;
    const void* window = nullptr;  ///< identity of the window drawn (a new one redraws the map)
    uint64_t weatherVersion = 0;
    int64_t weatherValidTimeUnixS = 0;
    const RenderTuning& tuning;
};

/// Room for the transmittance in the frame's readback buffer, reserved before any other readback of the
/// frame (so it lies at the same offset every frame and a reused map need not be copied again); goes into
/// recordShadowMap's `readback.transmittance`. Empty without readback.
ReadbackRegion reserveShadowMapReadback(const ShadowMapPass& pass, FrameContext& frame, const ViewRequest& request);

/**
 * Record the shadow map of the frame into its command buffer, and the copies of its texels.
 *
 * @param[in] f the frame being recorded (its uniforms hold the frame).
 * @param[in,out] frame its frame context (timestamps; its readback buffer must have room:
 *   frameReadbackBytes counts the shadow map).
 * @param[in,out] pass the pass (what it drew last).
 * @param[in] in the weather window and noise the frame draws.
 * @param[in] request the view (shadowMapSize, shadowMapExtentM; validated; readback bits).
 * @param[in] quality the settings (shadowSteps, readback).
 * @param[in] camera the eye's frame (centre of the map, osculating radius).
 * @param[in] sunMoon the sun and moon at the eye.
 * @param[in,out] readback in: `transmittance` from reserveShadowMapReadback; out: where the texels lie
 *   (copied only when this frame context's buffer does not hold this drawing already).
 * @param[out] facts shadowMapSize and shadowMap (metadata).
 **********************************************************************/
void recordShadowMap(const PassFrame& f, FrameContext& frame, ShadowMapPass& pass, const ShadowMapInputs& in,
                     const ViewRequest& request, const QualitySettings& quality, const CameraFrame& camera,
                     const SunMoon& sunMoon, ShadowMapReadback& readback, RenderResult& facts);

/// After the frame's fence: shadowTransmittance, shadowOpticalDepth (when read back) and gpuMs["shadowMap"]
/// (0 when the frame reused the last drawing).
void collectShadowMap(const Context& ctx, const FrameContext& frame, const ShadowMapReadback& readback,
                      RenderResult& result);

}  // namespace sky
