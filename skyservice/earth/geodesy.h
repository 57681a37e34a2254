// SPDX-License-Identifier: MIT
// The eye on the WGS84 ellipsoid: its pose, its local east-north-up frame, and the osculating sphere
// that the shaders use in place of the ellipsoid near the eye (docs/datums.md).
//
// Everything here is double and goes through GeographicLib (Geocentric, LocalCartesian); WGS84
// constants come only from GeographicLib::Constants (docs/style.md §10).
//
// Why an osculating sphere: the shaders intersect rays with layer shells written in a
// cancellation-free form that needs a sphere. The sphere is centred on the eye's normal and tangent
// to the ellipsoid below the eye. Its altitude error against the true ellipsoidal height grows with
// the square of the distance from the eye. Worst case over all azimuths, eye latitudes 0..89 and
// heights 0..12 km (tests/unit/test_geodesy.cpp, OsculatingSphereErrorBudget):
//
//   distance from the eye                      50 km    200 km    400 km    700 km
//   Gaussian sphere, R = sqrt(M N)             0.66 m   10.6 m    42 m      129 m    (worst at the equator)
//   normal-section sphere, R(azimuth)          0.005 m  0.33 m    2.6 m     14 m     (worst near 45 N/S)
//
// docs/datums.md allows 1% of a layer's thickness: 8 m for an 800 m stratocumulus deck. The Gaussian
// sphere meets that to about 170 km; the normal-section sphere (one radius per ray, since a ray's
// azimuth is fixed: normalSectionRadiusM) meets it to about 550 km, and for layers thicker than
// 1.4 km to the 700 km horizon of a cruising aircraft.
#pragma once

#include <GeographicLib/LocalCartesian.hpp>
#include <glm/glm.hpp>

#include <string>

namespace sky
{

/// Where the eye is and where it looks.
struct EyePose
{
    double latDeg = 0;      ///< geodetic latitude (degrees, [-90, 90])
    double lonDeg = 0;      ///< longitude (degrees, any finite value; normalised to [-180, 180))
    double altitudeM = 0;   ///< height above the WGS84 ellipsoid (meters, [-500, 100000])
    double headingDeg = 0;  ///< azimuth of the view, clockwise from true north (degrees; 0 north, 90 east)
    double pitchDeg = 0;    ///< elevation of the view above the local horizontal (degrees; + nose up)
    double rollDeg = 0;     ///< bank about the view axis (degrees; + right wing down)
};

/// Everything about the eye that the renderer needs, computed in double.
struct CameraFrame
{
    EyePose eye;                  ///< the pose this frame was computed from, longitude normalised
    glm::dvec3 eyeEcefM{0.0};     ///< eye position, earth-centred earth-fixed (meters)
    glm::dmat3 enuToEcef{1.0};    ///< rotation, columns: east, north, up at the eye, in ECEF
    double localEarthRadiusM = 0; ///< radius of the osculating sphere: Gaussian mean radius sqrt(M N) (meters)
    double meridionalRadiusM = 0;     ///< M, radius of curvature of the meridian at the eye (meters)
    double primeVerticalRadiusM = 0;  ///< N, radius of curvature of the prime vertical at the eye (meters)
    glm::dvec3 earthCentreEnuM{0.0};  ///< centre of that sphere relative to the eye, ENU: (0, 0, -(R + h)) (meters)
    glm::dvec3 forwardEnu{0.0, 1.0, 0.0};  ///< unit view direction in ENU
    glm::dvec3 rightEnu{1.0, 0.0, 0.0};    ///< unit camera right axis in ENU
    glm::dvec3 upEnu{0.0, 0.0, 1.0};       ///< unit camera up axis in ENU (right x forward)
    GeographicLib::LocalCartesian localCartesian;  ///< ENU converter with its origin at the eye
};

/**
 * Check an eye pose.
 *
 * @param[in] pose the pose to check.
 * @param[out] error set to a message naming the field and its value when the pose is invalid.
 * @return true if latitude is in [-90, 90] degrees, longitude, heading, pitch and roll are finite,
 *   and altitude is in [-500, 100000] meters.
 **********************************************************************/
bool validateEyePose(const EyePose& pose, std::string& error);

/**
 * @param[in] pose any pose (validate it first).
 * @return the same pose with longitude in [-180, 180) and heading in [0, 360) degrees.
 **********************************************************************/
EyePose normalizeEyePose(const EyePose& pose);

/**
 * Compute the camera frame of a (valid) eye pose.
 *
 * @param[in] pose the eye pose; its longitude is normalised.
 * @return the frame: ECEF position, ENU basis, osculating sphere and camera axes.
 *
 * Camera axes: heading rotates the view clockwise from north about up, pitch raises it, and roll
 * turns right and up about the view axis so that a positive roll lowers the right axis.
 **********************************************************************/
CameraFrame computeCameraFrame(const EyePose& pose);

/**
 * @param[in] latDeg geodetic latitude (degrees).
 * @return the Gaussian mean radius of curvature sqrt(M N) of WGS84 at that latitude (meters), where
 *   M is the meridional and N the prime-vertical radius of curvature.
 **********************************************************************/
double gaussianMeanRadiusM(double latDeg);

/**
 * @param[in] latDeg geodetic latitude (degrees).
 * @return the length of one degree of latitude along the meridian there (meters), M * pi / 180.
 **********************************************************************/
double metersPerDegreeLatitude(double latDeg);

/**
 * @param[in] latDeg geodetic latitude (degrees).
 * @return the length of one degree of longitude along the parallel there (meters), N cos(lat) pi / 180.
 **********************************************************************/
double metersPerDegreeLongitude(double latDeg);

/**
 * Position of a geodetic point in the eye's east-north-up frame (through LocalCartesian).
 *
 * @param[in] frame the camera frame.
 * @param[in] latDeg latitude of the point (degrees).
 * @param[in] lonDeg longitude of the point (degrees).
 * @param[in] hM height of the point above the ellipsoid (meters).
 * @return east, north, up offsets from the eye (meters).
 **********************************************************************/
glm::dvec3 geodeticToEnu(const CameraFrame& frame, double latDeg, double lonDeg, double hM);

/**
 * Geodetic position of a point given in the eye's east-north-up frame (the inverse of geodeticToEnu).
 *
 * @param[in] frame the camera frame.
 * @param[in] enuM east, north, up offsets from the eye (meters).
 * @param[out] latDeg latitude (degrees).
 * @param[out] lonDeg longitude (degrees, [-180, 180]).
 * @param[out] hM height above the ellipsoid (meters).
 **********************************************************************/
void enuToGeodetic(const CameraFrame& frame, const glm::dvec3& enuM, double& latDeg, double& lonDeg, double& hM);

/**
 * Height of a point above the eye's osculating sphere: what the shaders compute for a sample.
 *
 * @param[in] frame the camera frame.
 * @param[in] enuM east, north, up offsets from the eye (meters).
 * @return |p - centre| - R (meters).
 **********************************************************************/
double sphereAltitudeM(const CameraFrame& frame, const glm::dvec3& enuM);

/**
 * Radius of curvature of the ellipsoid's normal section through the eye in one azimuth (Euler's
 * theorem: 1/R = cos^2(az)/M + sin^2(az)/N). A sphere of this radius, centred on the eye's normal,
 * follows the ellipsoid along that azimuth much more closely than the Gaussian sphere (see the error
 * budget above); a shader can use it per ray, since a ray's azimuth is constant.
 *
 * @param[in] frame the camera frame.
 * @param[in] azimuthDeg clockwise from north (degrees).
 * @return the radius (meters), between M and N.
 **********************************************************************/
double normalSectionRadiusM(const CameraFrame& frame, double azimuthDeg);

/**
 * Height of a point above the eye's normal-section sphere for the point's azimuth (see
 * normalSectionRadiusM); for a point straight above or below the eye, the Gaussian sphere's height.
 *
 * @param[in] frame the camera frame.
 * @param[in] enuM east, north, up offsets from the eye (meters).
 * @return |p - centre(az)| - R(az) (meters).
 **********************************************************************/
double normalSectionAltitudeM(const CameraFrame& frame, const glm::dvec3& enuM);

/**
 * Azimuth and elevation of a direction given in ENU.
 *
 * @param[in] directionEnu a direction (need not be unit length, must not be zero).
 * @param[out] azimuthDeg clockwise from north (degrees, [0, 360)).
 * @param[out] elevationDeg above the local horizontal (degrees, [-90, 90]).
 **********************************************************************/
void enuDirectionToAzimuthElevation(const glm::dvec3& directionEnu, double& azimuthDeg, double& elevationDeg);

/**
 * The unit ENU direction of an azimuth and elevation (the inverse of enuDirectionToAzimuthElevation).
 *
 * @param[in] azimuthDeg clockwise from north (degrees).
 * @param[in] elevationDeg above the local horizontal (degrees).
 * @return unit direction in ENU.
 **********************************************************************/
glm::dvec3 azimuthElevationToEnuDirection(double azimuthDeg, double elevationDeg);

/**
 * Distance along a straight line from an eye to its geometric horizon on a sphere.
 *
 * @param[in] altitudeM eye height above the sphere (meters); heights <= 0 give 0.
 * @param[in] radiusM sphere radius (meters).
 * @return sqrt(h (2R + h)) (meters).
 **********************************************************************/
double distanceToHorizonM(double altitudeM, double radiusM);

}  // namespace sky
