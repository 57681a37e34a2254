// SPDX-License-Identifier: MIT
// Compositing by depth with the service's layers (skyservice/ipc/PROTOCOL.md "Compositing layers"): per
// pixel the demo's terrain with relief (terrain.h) is put in front of the clouds where it is nearer than the
// cloud's depth and behind them elsewhere, over the linear sky where it draws nothing; then the demo's own
// tone mapping and sRGB encoding, as an image generator compositing its scene with the sky would do.
#pragma once

#include "client_demo/compositor.h"
#include "client_demo/terrain.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace demo
{

/// The scene as one pixel sees it: nothing, or a surface at distanceM with its linear radiance.
struct SceneSample
{
    bool hit = false;
    double distanceM = 0.0;           ///< along the pixel's ray (m)
    glm::dvec3 radiance{0.0};         ///< linear, pre-exposed (haze included)
};

/**
 * One pixel's linear colour from the layers and the scene:
 *   no scene:                                   sky * (1 - a) + clouds.rgb
 *   scene nearer than the cloud's front,
 *   or no cloud:                                scene
 *   scene behind the cloud, or a cloud (a > 0)
 *   whose depth is unknown (0):                 scene * (1 - a) + clouds.rgb
 *
 * @param[in] sky the sky layer (linear).
 * @param[in] clouds the clouds layer (premultiplied linear rgb, alpha).
 * @param[in] cloudFrontM the depth layer's front distance (R; m; 0 where there is no cloud).
 * @param[in] scene what the demo draws in this pixel.
 * @return linear, pre-exposed colour.
 **********************************************************************/
glm::dvec3 compositeOverScene(const glm::dvec3& sky, const glm::dvec4& clouds, double cloudFrontM,
                              const SceneSample& scene);

/**
 * Simple haze: the terrain fades into the sky layer's colour of its own pixel (what the eye would see
 * with no terrain there) as exp(-distance / hazeM).
 **********************************************************************/
glm::dvec3 hazeTerrain(const glm::dvec3& terrain, const glm::dvec3& sky, double distanceM, double hazeM);

/// The ACES filmic curve (Narkowicz 2015 fit), the service's display curve too (shaders/lib/tonemap.glsl).
glm::dvec3 tonemapAces(const glm::dvec3& linear);

/// The sRGB transfer function (IEC 61966-2-1) of a value in 0..1.
double encodeSrgb(double linear);

/// Linear pre-exposed colour to the 8-bit sRGB display value: ACES, sRGB, rounded (the service's pipeline).
void toDisplayRgb8(const glm::dvec3& linear, uint8_t* rgb);

/// The key light for the terrain: the shadow map's (sun or moon) when the frame has one, else mid-morning.
TerrainLight terrainLightOf(const LatestFrame& frame);

/// The heights the frame's clouds occupy, estimated from the depth layer (cloudLayerOf).
struct CloudLayerEstimate
{
    bool valid = false;   ///< false: too few clouds in view to say
    double baseM = 0.0;   ///< above the flat ground (m)
    double topM = 0.0;
};

/**
 * Where the clouds in view lie in height: the heights of the points at the depth layer's distance along
 * the rays of pixels with alpha >= 0.5, their 5th and 95th percentiles (at least 200 m apart). The
 * transmittance-weighted depth lies inside the clouds, so this is the cloud layer as seen, a little
 * inside its true base and top.
 *
 * @param[in] frame a frame with layers.
 * @param[in] camera its camera.
 * @return the estimate (invalid with fewer than 16 such pixels).
 **********************************************************************/
CloudLayerEstimate cloudLayerOf(const LatestFrame& frame, const GroundCamera& camera);

/**
 * The key light's transmittance above a terrain point at heightM. The shadow map holds it from the flat
 * ground up; the part of its optical depth (-ln T) that lies below the point is taken away, the optical
 * depth spread evenly over the cloud layer's heights: T^f, f the fraction of the layer above the point.
 * A peak above a deck is then in sunlight, a valley under it in the deck's shadow.
 *
 * @param[in] groundTransmittance the shadow map's value at the light ray's ground footprint (0..1).
 * @param[in] heightM the terrain point's height (m).
 * @param[in] layer the cloud layer (invalid: the map's value as it is).
 **********************************************************************/
double keyTransmittanceAt(double groundTransmittance, double heightM, const CloudLayerEstimate& layer);

/**
 * Composites a frame that carries the sky, clouds and depth layers (frame.hasLayers()): the terrain of
 * options.terrain (flat ground when it has no peaks; nothing when options.ground is off), lit by the key
 * light, darkened by the cloud shadow map and hazed, put in front of or behind the clouds by depth.
 *
 * @param[in] frame the frame with its layers.
 * @param[in] options terrain and haze.
 * @param[out] out the displayable image (alpha 255), the frame's size.
 * @param[out] stats what was drawn (may be null).
 **********************************************************************/
void compositeLayers(const LatestFrame& frame, const CompositeOptions& options, sky::ImageRgba8& out,
                     CompositeStats* stats);

}  // namespace demo
