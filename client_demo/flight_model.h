// SPDX-License-Identifier: MIT
// The demo's aircraft: a point that flies along its heading and pitch at a set speed, steered by keys and
// the mouse (window) or by a fixed script (headless capture). Not a flight dynamics model: a camera rig.
#pragma once

#include "skyservice/ipc/shm_layout.h"

namespace demo
{

/// Where the aircraft is and how it moves.
struct Aircraft
{
    double latDeg = 44.3;       ///< geodetic latitude (degrees)
    double lonDeg = 7.5;        ///< longitude (degrees, kept in [-180, 180))
    double altitudeM = 1500.0;  ///< height above the WGS84 ellipsoid (m)
    double headingDeg = 0.0;    ///< clockwise from true north (degrees, kept in [0, 360))
    double pitchDeg = 0.0;      ///< nose up (degrees, -89..89)
    double speedMps = 120.0;    ///< true airspeed (m/s, 0..1000)
};

/// What the pilot holds this frame (from keys and mouse); rates are per second.
struct FlightInput
{
    double turnDegPerS = 0.0;     ///< + right
    double pitchDegPerS = 0.0;    ///< + nose up
    double speedMpsPerS = 0.0;    ///< + faster
    double climbMps = 0.0;        ///< direct altitude change (m/s), on top of the pitch's climb
    double mouseHeadingDeg = 0.0; ///< one-off heading change this frame (mouse drag)
    double mousePitchDeg = 0.0;   ///< one-off pitch change this frame (mouse drag)
};

/// Lowest and highest altitudes the demo flies at (m): above the ground, below the service's limit.
inline constexpr double kMinAltitudeM = 20.0;
inline constexpr double kMaxAltitudeM = 60000.0;

/**
 * Moves the aircraft by dtS seconds: applies the input, then flies speed * dt along the heading with a climb
 * of speed * sin(pitch) (lat/lon advanced with the WGS84 radii of curvature at the current latitude).
 **********************************************************************/
void advanceAircraft(Aircraft& aircraft, const FlightInput& input, double dtS);

/**
 * The headless capture's scripted flight: a gentle right turn (3 degrees per frame) at the aircraft's speed,
 * so consecutive captures show the clouds moving across the frame.
 **********************************************************************/
FlightInput scriptedInput(unsigned frameIndex);

/// The frustum: symmetric (the vertical field of view) or off-centre, as one channel of a display wall
/// (half-angles from the view axis, PROTOCOL.md "Views").
struct ViewAngles
{
    double fovDeg = 60.0;     ///< vertical field of view (degrees) when not asymmetric
    bool asymmetric = false;  ///< true: the four half-angles below
    double leftDeg = 0.0;
    double rightDeg = 0.0;
    double upDeg = 0.0;
    double downDeg = 0.0;
};

/**
 * @param[in] aircraft the aircraft.
 * @param[in] angles the frustum.
 * @param[in] width, height image size (pixels).
 * @return the view to send to the service (roll 0).
 **********************************************************************/
SkyShmView viewOf(const Aircraft& aircraft, const ViewAngles& angles, unsigned width, unsigned height);

}  // namespace demo
