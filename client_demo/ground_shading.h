// SPDX-License-Identifier: MIT
// The demo's ground: where a pixel's view ray meets the earth, what a simple flat terrain looks like
// there, and how much the service's cloud shadow map darkens it. Pure CPU maths (no Vulkan), shared by
// the window, the headless capture and the unit test.
#pragma once

#include "skyservice/ipc/shm_layout.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace demo
{

/// The service's camera for one view (same basis as skyservice/earth/geodesy.cpp computeCameraFrame and
/// shaders/clouds/view_ray.glsl, so the ground meets the frame's horizon where the frame's does).
struct GroundCamera
{
    glm::dvec3 forwardEnu{0.0, 1.0, 0.0};  ///< unit, east-north-up at the eye
    glm::dvec3 rightEnu{1.0, 0.0, 0.0};
    glm::dvec3 upEnu{0.0, 0.0, 1.0};
    double tanLeft = 1.0;       ///< tan of the frustum's half-angles from the view axis (symmetric or not)
    double tanRight = 1.0;
    double tanUp = 1.0;
    double tanDown = 1.0;
    double altitudeM = 0.0;     ///< eye height above the ellipsoid (m)
    double earthRadiusM = 0.0;  ///< local (Gaussian) radius of curvature at the eye, sqrt(M N) (m)
    double latDeg = 0.0;        ///< eye latitude (degrees)
    double lonDeg = 0.0;        ///< eye longitude (degrees)
    uint32_t width = 1;         ///< image size (pixels)
    uint32_t height = 1;
};

/**
 * @param[in] view the view a frame was rendered for (degrees, metres, pixels).
 * @return its camera (heading clockwise from north, pitch nose up, roll right wing down).
 **********************************************************************/
GroundCamera makeGroundCamera(const SkyShmView& view);

/**
 * @param[in] camera the camera.
 * @param[in] xPx, yPx a point of the image (pixels from the top-left corner; pixel centres at +0.5).
 * @return the unit view direction (ENU) through it.
 **********************************************************************/
glm::dvec3 viewRay(const GroundCamera& camera, double xPx, double yPx);

/// Where a view ray meets the ground.
struct GroundHit
{
    double distanceM = 0.0;  ///< along the ray (m)
    double eastM = 0.0;      ///< offset of the ground point from the point below the eye, east (m)
    double northM = 0.0;     ///< ... north (m)
};

/**
 * Intersects a view ray with the earth: a sphere of the camera's local radius (the renderer uses the same
 * osculating sphere, docs/datums.md).
 *
 * @param[in] camera the camera.
 * @param[in] dirEnu unit view direction (ENU).
 * @param[out] hit the ground point (valid when true is returned).
 * @return false when the ray misses the ground (sky) or the eye is below the ground.
 **********************************************************************/
bool intersectGround(const GroundCamera& camera, const glm::dvec3& dirEnu, GroundHit& hit);

/**
 * The eye's position in the shadow map's plane: east/north of the map's centre (m). A local tangent plane
 * at the centre (east = dLon * N cos(lat), north = dLat * M) stands in for the map's azimuthal
 * equidistant projection: within the ~100 km of a shadow map they differ by less than a texel (the
 * equidistant projection keeps distances from the centre exactly; the tangent plane errs by
 * ~d^3 / (6 R^2), 4 m at 75 km), which is fine for a demo's ground.
 *
 * @param[in] latDeg, lonDeg the eye (degrees).
 * @param[in] geo the shadow map's geo-reference.
 * @return (east, north) in metres.
 **********************************************************************/
std::array<double, 2> offsetFromShadowCentreM(double latDeg, double lonDeg, const SkyShmShadowGeoRef& geo);

/**
 * Bilinear lookup of the shadow map (texel layout of shm_layout.h: column c, row r at easting
 * (c + 0.5 - size/2) * extent/size, northing (size/2 - r - 0.5) * extent/size).
 *
 * @param[in] transmittance size^2 values (0 opaque, 1 clear), north row first, west column first.
 * @param[in] size texels per side.
 * @param[in] extentM edge of the square on the ground (m).
 * @param[in] eastM, northM the ground point relative to the map's centre (m).
 * @return the key-light transmittance there; 1 (clear) outside the map or when size is 0.
 **********************************************************************/
double shadowTransmittanceAt(const std::vector<float>& transmittance, uint32_t size, double extentM, double eastM,
                             double northM);

/// Lighting of the ground for one frame.
struct GroundLight
{
    double sunElevationDeg = 30.0;  ///< key light elevation (degrees); the frame's when it has a shadow map
    bool isMoon = false;            ///< the key light is the moon (much dimmer)
};

/**
 * The demo terrain's colour at a ground point: a checkerboard of fields (0.02 degree squares, fixed to
 * the earth so flying past them shows motion) lit by the key light times the cloud shadow.
 *
 * @param[in] groundLatDeg, groundLonDeg the ground point (degrees).
 * @param[in] light the key light.
 * @param[in] shadowTransmittance key-light transmittance of the clouds above the point (0..1).
 * @return sRGB-encoded colour (0..1 per channel).
 **********************************************************************/
glm::dvec3 shadeGround(double groundLatDeg, double groundLonDeg, const GroundLight& light, double shadowTransmittance);

/**
 * @param[in] camera the camera.
 * @param[in] hit a ground point of it.
 * @return the ground point's (latitude, longitude) in degrees (tangent-plane offset from the eye).
 **********************************************************************/
std::array<double, 2> groundLatLonDeg(const GroundCamera& camera, const GroundHit& hit);

}  // namespace demo
