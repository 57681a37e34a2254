// SPDX-License-Identifier: MIT
#include "skyservice/weather/window_lattice.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/Math.hpp>

#include <algorithm>
#include <cmath>

namespace sky
{

WindowCentre windowCentreForEye(double latDeg, double lonDeg)
{
    WindowCentre c;
    const int64_t maxRow = int64_t(std::llround(90.0 / kWindowLatticeDeg));
    c.row = std::clamp<int64_t>(std::llround(latDeg / kWindowLatticeDeg), -maxRow, maxRow);
    c.latDeg = double(c.row) * kWindowLatticeDeg;
    // Nodes per row: the row's circumference in units of kWindowLatticeDeg of arc, at least one.
    const double cosLat = std::cos(c.latDeg * M_PI / 180.0);
    const int64_t perRow = std::max<int64_t>(1, int64_t(std::floor(360.0 * cosLat / kWindowLatticeDeg)));
    const double stepDeg = 360.0 / double(perRow);
    double lon = std::fmod(lonDeg, 360.0);
    if (lon < 0.0)
        lon += 360.0;  // [0, 360)
    c.column = std::llround(lon / stepDeg) % perRow;
    c.lonDeg = GeographicLib::Math::AngNormalize(double(c.column) * stepDeg);
    if (c.lonDeg >= 180.0)
        c.lonDeg -= 360.0;
    return c;
}

EyeOnWindow placeEyeOnWindow(double centreLatDeg, double centreLonDeg, double eyeLatDeg, double eyeLonDeg)
{
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    const GeographicLib::AzimuthalEquidistant projection(geodesic);
    auto project = [&](double latDeg, double lonDeg) {
        double x = 0, y = 0, azi = 0, rk = 0;
        projection.Forward(centreLatDeg, centreLonDeg, latDeg, lonDeg, x, y, azi, rk);
        return glm::dvec2(x, y);
    };
    EyeOnWindow e;
    e.offsetM = project(eyeLatDeg, eyeLonDeg);
    // 50 m: short enough that the map is linear over it, long enough that double rounding (~1e-9 m
    // here) does not matter.
    const double stepM = 50.0;
    double lat = 0, lon = 0;
    geodesic.Direct(eyeLatDeg, eyeLonDeg, 90.0, stepM, lat, lon);
    e.eastAxis = (project(lat, lon) - e.offsetM) / stepM;
    geodesic.Direct(eyeLatDeg, eyeLonDeg, 0.0, stepM, lat, lon);
    e.northAxis = (project(lat, lon) - e.offsetM) / stepM;
    return e;
}

}  // namespace sky
