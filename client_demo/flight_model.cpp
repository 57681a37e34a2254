// SPDX-License-Identifier: MIT
#include "client_demo/flight_model.h"

#include <GeographicLib/Constants.hpp>

#include <algorithm>
#include <cmath>

namespace demo
{
namespace
{

constexpr double kDegToRad = M_PI / 180.0;

double wrap(double value, double lo, double period)
{
    double v = std::fmod(value - lo, period);
    if (v < 0.0)
        v += period;
    return v + lo;
}

}  // namespace

void advanceAircraft(Aircraft& a, const FlightInput& in, double dtS)
{
    a.headingDeg = wrap(a.headingDeg + in.turnDegPerS * dtS + in.mouseHeadingDeg, 0.0, 360.0);
    a.pitchDeg = std::clamp(a.pitchDeg + in.pitchDegPerS * dtS + in.mousePitchDeg, -89.0, 89.0);
    a.speedMps = std::clamp(a.speedMps + in.speedMpsPerS * dtS, 0.0, 1000.0);

    const double along = a.speedMps * dtS * std::cos(a.pitchDeg * kDegToRad);
    const double climb = a.speedMps * dtS * std::sin(a.pitchDeg * kDegToRad) + in.climbMps * dtS;
    // WGS84 radii of curvature (textbook formulas; a and f from GeographicLib).
    const double ea = GeographicLib::Constants::WGS84_a<double>();
    const double f = GeographicLib::Constants::WGS84_f<double>();
    const double e2 = f * (2.0 - f);
    const double s = std::sin(a.latDeg * kDegToRad);
    const double w = 1.0 - e2 * s * s;
    const double primeVerticalM = ea / std::sqrt(w);
    const double meridionalM = ea * (1.0 - e2) / (w * std::sqrt(w));
    const double northM = along * std::cos(a.headingDeg * kDegToRad);
    const double eastM = along * std::sin(a.headingDeg * kDegToRad);
    a.latDeg = std::clamp(a.latDeg + northM / meridionalM / kDegToRad, -89.9, 89.9);
    a.lonDeg = wrap(a.lonDeg + eastM / (primeVerticalM * std::cos(a.latDeg * kDegToRad)) / kDegToRad, -180.0, 360.0);
    a.altitudeM = std::clamp(a.altitudeM + climb, kMinAltitudeM, kMaxAltitudeM);
}

FlightInput scriptedInput(unsigned /*frameIndex*/)
{
    FlightInput in;
    in.mouseHeadingDeg = 3.0;
    return in;
}

SkyShmView viewOf(const Aircraft& a, const ViewAngles& angles, unsigned width, unsigned height)
{
    SkyShmView v{};
    v.lat_deg = a.latDeg;
    v.lon_deg = a.lonDeg;
    v.alt_m = a.altitudeM;
    v.heading_deg = a.headingDeg;
    v.pitch_deg = a.pitchDeg;
    v.roll_deg = 0.0;
    v.fov_deg = angles.asymmetric ? angles.upDeg + angles.downDeg : angles.fovDeg;
    if (angles.asymmetric)
    {
        v.asymmetric = 1;
        v.left_deg = angles.leftDeg;
        v.right_deg = angles.rightDeg;
        v.up_deg = angles.upDeg;
        v.down_deg = angles.downDeg;
    }
    v.width = width;
    v.height = height;
    return v;
}

}  // namespace demo
