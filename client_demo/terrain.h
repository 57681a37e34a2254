// SPDX-License-Identifier: MIT
// The demo's terrain with relief: an analytic heightfield (a mountain of two Gaussian peaks with a valley
// between them, on the flat ground of the earth's sphere), where a pixel's view ray first meets it, and how
// it is lit in the service's pre-exposed linear light. Pure CPU maths, shared by the layer compositor and
// its unit tests.
#pragma once

#include "client_demo/ground_shading.h"

#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace demo
{

/// One Gaussian peak: height * exp(-r^2 / (2 sigma^2)), r the horizontal distance from its centre.
struct TerrainPeak
{
    double latDeg = 0.0;     ///< centre (degrees)
    double lonDeg = 0.0;
    double heightM = 0.0;    ///< above the flat ground (m)
    double sigmaM = 1000.0;  ///< horizontal scale (m)
};

/// The heightfield: the flat ground (height 0, the sphere ground_shading.h meets) plus some peaks.
struct DemoTerrain
{
    std::vector<TerrainPeak> peaks;  ///< empty = flat ground only
};

/**
 * The demo's mountain, fixed to the earth where a flight from (latDeg, lonDeg) along headingDeg meets it:
 * a main peak of 3000 m (sigma 2.2 km) 12 km ahead, and a shoulder of 2200 m (sigma 2.2 km) 8 km to the
 * right of it. Between them lies a valley whose floor (the saddle) is ~1000 m high, with the flat ground
 * all around at 0 m.
 *
 * @param[in] latDeg, lonDeg where the flight starts (degrees).
 * @param[in] headingDeg its heading (degrees clockwise from north).
 * @return the terrain.
 **********************************************************************/
DemoTerrain demoMountainAhead(double latDeg, double lonDeg, double headingDeg);

/// A terrain in the eye's local frame (east/north of the point below the eye, metres): made once per frame.
struct LocalTerrain
{
    struct Peak
    {
        double eastM = 0.0;
        double northM = 0.0;
        double heightM = 0.0;
        double sigmaM = 1.0;
        double inverseTwoSigma2 = 0.0;  ///< 1 / (2 sigma^2) (m^-2)
        double reachM = 0.0;            ///< beyond this distance the peak is below 0.1 m: taken as 0
    };
    std::vector<Peak> peaks;
    double maxSlope = 0.0;  ///< bound on |grad h| over the whole field (for safe ray-march steps)
};

/**
 * @param[in] terrain the terrain.
 * @param[in] camera the eye (its lat/lon are the local frame's origin; tangent plane at the eye).
 * @return the terrain in the eye's frame.
 **********************************************************************/
LocalTerrain localTerrain(const DemoTerrain& terrain, const GroundCamera& camera);

/**
 * @param[in] t the terrain in the eye's frame.
 * @param[in] eastM, northM a point (m, relative to the point below the eye).
 * @param[out] gradient dh/deast, dh/dnorth there (may be null).
 * @return the terrain's height there (m above the flat ground).
 **********************************************************************/
double terrainHeightM(const LocalTerrain& t, double eastM, double northM, std::array<double, 2>* gradient = nullptr);

/// Where a view ray meets the terrain.
struct TerrainHit
{
    double distanceM = 0.0;           ///< along the ray (m)
    double eastM = 0.0;               ///< offset of the point from the point below the eye (m)
    double northM = 0.0;
    double heightM = 0.0;             ///< the terrain's height there (m above the flat ground)
    glm::dvec3 normalEnu{0.0, 0.0, 1.0};  ///< unit surface normal
};

/**
 * @param[in] t the terrain in the eye's frame.
 * @param[in] eastM, northM the centre of a horizontal disc (m).
 * @param[in] radiusM its radius (m).
 * @return a bound on |grad h| within the disc: per peak the Gaussian's slope at the disc's nearest point to
 *   the peak's centre when that is beyond sigma (where the slope falls with distance), else its steepest.
 **********************************************************************/
double slopeBoundNear(const LocalTerrain& t, double eastM, double northM, double radiusM);

/**
 * Ray-marches the heightfield: steps of (ray height - terrain height) / (slope bound + descent rate), which
 * cannot pass under the surface, the slope bound taken over the disc the step can reach (slopeBoundNear,
 * so that far from the peaks the steps are long), then bisection where the ray went under. The flat ground
 * beyond the peaks is met analytically (intersectGround). The eye's height is the camera's altitude
 * above the sphere; the ray's height along it includes the earth's curvature.
 *
 * @param[in] camera the camera.
 * @param[in] terrain the terrain in the eye's frame.
 * @param[in] dirEnu unit view direction (ENU).
 * @param[out] hit the nearest terrain point (valid when true is returned).
 * @return false when the ray meets no terrain (sky), or the eye is under the terrain's surface.
 **********************************************************************/
bool intersectTerrain(const GroundCamera& camera, const LocalTerrain& terrain, const glm::dvec3& dirEnu,
                      TerrainHit& hit);

/**
 * @param[in] camera the camera.
 * @param[in] dirEnu unit view direction (ENU).
 * @param[in] distanceM distance along it (m).
 * @return the height of that point above the flat ground (the sphere of intersectGround), in metres.
 **********************************************************************/
double rayHeightM(const GroundCamera& camera, const glm::dvec3& dirEnu, double distanceM);

/// The key light for the terrain: direction (from the shadow map's metadata, else a mid-morning sun).
struct TerrainLight
{
    double elevationDeg = 30.0;  ///< above the horizon (degrees)
    double azimuthDeg = 120.0;   ///< clockwise from north (degrees)
    bool isMoon = false;
};

/**
 * The terrain's radiance in the service's pre-exposed linear units (what the `sky` and `clouds` layers
 * hold). The service picks its exposure so that a white cloud facing the key light maps to ~1.2 (0.6 of the
 * key light's irradiance plus the sky's, divided by pi); on that scale a white Lambertian surface facing a
 * daylight key light has ~1.4 from the key light and ~0.35 from the sky, the sky's share rising to ~1.2 in
 * twilight when the key light is gone. These are approximations of a demo, not the service's physics.
 * Albedo: fields (a checkerboard of 0.02 degrees, fixed to the earth) on the flat ground and the lower
 * slopes, forest and rock higher and on steep slopes, snow above ~2600 m.
 *
 * @param[in] hit the terrain point.
 * @param[in] latDeg, lonDeg where it lies (degrees; for the fields).
 * @param[in] light the key light.
 * @param[in] keyTransmittance the clouds' key-light transmittance above the point (0..1, shadow map).
 * @return linear RGB radiance, pre-exposed.
 **********************************************************************/
glm::dvec3 shadeTerrainLinear(const TerrainHit& hit, double latDeg, double lonDeg, const TerrainLight& light,
                              double keyTransmittance);

/**
 * Where the key light's ray through a terrain point at heightM meets the flat ground (the plane of the
 * shadow map, which holds the transmittance of light rays from the ground up): the point's offset moved
 * away from the light by heightM / tan(elevation). The map's value there is the transmittance above the
 * terrain point as long as no cloud lies below the point (a peak above a deck is still darkened by it).
 *
 * @return (east, north) offset of that ground point (m), in the same frame as the hit.
 **********************************************************************/
std::array<double, 2> shadowFootprintM(const TerrainHit& hit, const TerrainLight& light);

}  // namespace demo
