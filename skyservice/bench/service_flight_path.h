// SPDX-License-Identifier: MIT
// The flight path of sky-service-bench --flight-path: an eye that climbs and turns through the built-in
// weather's scattered cumulus, one pose per delivered frame, and where along it the eye is inside a
// cloud layer.
//
// The eye starts at 44.3 N 7.5 E, 300 m, heading north, and flies at 250 m/s over the ground, climbing
// at 15 m/s and turning right at 3 degrees per second: four minutes climb it to 3900 m through the
// cumulus layer (1200..3200 m there) on a circle of about 4.8 km radius, twice round. The view looks
// along the flight path (pitch = the climb angle) and banks as a coordinated turn does
// (tan(roll) = speed * turn rate / g), as a pilot's eye would.
#pragma once

#include "skyservice/bench/bench_scenes.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sky
{

struct FlightPathSpec
{
    double startLatDeg = 44.3, startLonDeg = 7.5, startAltitudeM = 300.0;
    double startHeadingDeg = 0.0;
    double groundSpeedMps = 250.0;
    double climbMps = 15.0;
    double turnDegPerS = 3.0;  ///< + to the right (heading increases)
    double seconds = 240.0;    ///< simulated length of the path
    double stepS = 1.0 / 60.0; ///< simulated time per delivered frame

    /// Frames along the path: seconds / stepS, rounded, at least 1.
    uint32_t frames() const;
};

/// The eye at one frame: simulated time since the start and the pose drawn.
struct FlightPose
{
    double timeS = 0;
    EyePose pose;
};

/**
 * The poses of every frame: frame i at time i * stepS. Integrated in double on the WGS84 ellipsoid
 * (GeographicLib geodesics, the heading at mid-step), so the ground track is the same whatever the step.
 **********************************************************************/
std::vector<FlightPose> flightPathPoses(const FlightPathSpec& spec);

/// The scene the daemon starts with: the path's first pose in the built-in weather, at midday.
BenchScene flightPathScene(const FlightPathSpec& spec);

/// A stretch of the path with the eye between a cloud layer's base and top where the layer has cloud.
struct CloudLayerStretch
{
    std::string layer;        ///< the built-in weather's layer name ("low", ...)
    double enterS = 0, leaveS = 0; ///< simulated time of the first and last frame inside
    float minCoverage = 1, maxCoverage = 0; ///< the layer's coverage under the eye meanwhile
};

/**
 * Where the eye is inside a layer of the built-in weather (nearest grid cell under the eye, coverage
 * above 0, base <= altitude <= top). Inside the layer the eye still flies through clear air between the
 * cumulus: the cloud itself is the renderer's density field.
 *
 * @param[in] poses the path.
 * @param[out] insideLayer per pose, whether the eye is inside some layer.
 * @return the stretches, in time order.
 **********************************************************************/
std::vector<CloudLayerStretch> cloudLayerStretches(const std::vector<FlightPose>& poses,
                                                   std::vector<bool>& insideLayer);

} // namespace sky
