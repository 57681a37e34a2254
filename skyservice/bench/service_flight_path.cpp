// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_flight_path.h"

#include "skyservice/sky/builtin_weather.h"

#include <GeographicLib/Geodesic.hpp>
#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

constexpr double kStandardGravityMps2 = 9.80665;
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
// The flight-path scene's time: the sun high over the cumulus, as in the scattered-cumulus scene.
constexpr const char* kFlightPathTimeIso = "2026-06-21T11:30:00Z";

double wrapDeg360(double deg)
{
    double d = std::fmod(deg, 360.0);
    return d < 0 ? d + 360.0 : d;
}

/// The nearest cell of `grid` to a point, false outside it.
bool nearestCell(const LatLonGrid& grid, double latDeg, double lonDeg, size_t& index)
{
    const long row = std::lround((latDeg - grid.lat0Deg) / grid.dLatDeg);
    const long column = std::lround((lonDeg - grid.lon0Deg) / grid.dLonDeg);
    if (row < 0 || column < 0 || row >= long(grid.nLat) || column >= long(grid.nLon))
        return false;
    index = grid.index(uint32_t(row), uint32_t(column));
    return true;
}

} // namespace

uint32_t FlightPathSpec::frames() const
{
    return uint32_t(std::max(1.0, std::round(seconds / stepS)));
}

std::vector<FlightPose> flightPathPoses(const FlightPathSpec& spec)
{
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    const double pitchDeg = std::atan2(spec.climbMps, spec.groundSpeedMps) * kDegPerRad;
    const double rollDeg =
        std::atan(spec.groundSpeedMps * spec.turnDegPerS / kDegPerRad / kStandardGravityMps2) * kDegPerRad;
    const uint32_t frames = spec.frames();
    std::vector<FlightPose> poses(frames);
    double lat = spec.startLatDeg, lon = spec.startLonDeg, heading = spec.startHeadingDeg;
    const double halfTurnDeg = 0.5 * spec.turnDegPerS * spec.stepS;
    for (uint32_t i = 0; i < frames; ++i)
    {
        FlightPose& p = poses[i];
        p.timeS = double(i) * spec.stepS;
        p.pose = {lat, lon, spec.startAltitudeM + spec.climbMps * p.timeS, wrapDeg360(heading), pitchDeg, rollDeg};
        // One step along the geodesic that leaves at the mid-step heading; its azimuth at the far end
        // carries the meridians' convergence into the next heading.
        double azimuthEndDeg = 0;
        geodesic.Direct(lat, lon, heading + halfTurnDeg, spec.groundSpeedMps * spec.stepS, lat, lon, azimuthEndDeg);
        heading = azimuthEndDeg + halfTurnDeg;
    }
    return poses;
}

BenchScene flightPathScene(const FlightPathSpec& spec)
{
    BenchScene scene;
    scene.name = "flight-path";
    scene.description = "Climbing turn from 300 m through the scattered cumulus";
    scene.timeIso = kFlightPathTimeIso;
    FlightPathSpec firstFrame = spec;
    firstFrame.seconds = spec.stepS;
    scene.pose = flightPathPoses(firstFrame).front().pose;
    scene.fovYDeg = 60.0;
    scene.builtinWeather = true;
    return scene;
}

std::vector<CloudLayerStretch> cloudLayerStretches(const std::vector<FlightPose>& poses,
                                                   std::vector<bool>& insideLayer)
{
    // The fields do not depend on the valid time (builtin_weather.h).
    const WeatherSnapshot weather = makeBuiltinWeather(0);
    std::vector<CloudLayerStretch> stretches;
    insideLayer.assign(poses.size(), false);
    for (const CloudLayerFields& layer : weather.layers)
    {
        bool inside = false;
        for (size_t i = 0; i < poses.size(); ++i)
        {
            const EyePose& eye = poses[i].pose;
            size_t cell = 0;
            const bool here = nearestCell(weather.grid, eye.latDeg, eye.lonDeg, cell) && layer.coverage[cell] > 0 &&
                              eye.altitudeM >= double(layer.baseAltitudeM[cell]) &&
                              eye.altitudeM <= double(layer.topAltitudeM[cell]);
            if (here && !inside)
                stretches.push_back({layer.name, poses[i].timeS, poses[i].timeS, 1.0f, 0.0f});
            if (here)
            {
                CloudLayerStretch& s = stretches.back();
                s.leaveS = poses[i].timeS;
                s.minCoverage = std::min(s.minCoverage, layer.coverage[cell]);
                s.maxCoverage = std::max(s.maxCoverage, layer.coverage[cell]);
                insideLayer[i] = true;
            }
            inside = here;
        }
    }
    std::sort(stretches.begin(), stretches.end(),
              [](const CloudLayerStretch& a, const CloudLayerStretch& b) { return a.enterS < b.enterS; });
    return stretches;
}

} // namespace sky
