// SPDX-License-Identifier: MIT
// Where the weather window is centred for a given eye, and where the eye lies on that window.
//
// Resampling the 256^2 x 11 window costs tens of milliseconds of CPU (weather_window.h), far too much for every
// frame of a moving eye. So the window is not centred on the eye exactly but on the node of a fixed
// lattice nearest to it (about 2.2 km between nodes): it is resampled only when the eye crosses into
// another lattice cell (every ~9 s at 250 m/s), and the renderer prepares the next cell's window
// ahead of time on a worker thread (weather/window_provider.h). The centre depends only on the eye
// position, never on timing, so every machine of a multi-channel simulator and every one-shot render
// use the same window for the same eye: the same clouds.
//
// The shaders then look the weather up at the eye's offset from the window centre (FrameParams
// window.eyeOnPlaneM, eastAxis, northAxis), computed here in double with GeographicLib: the eye's position in the
// centre's azimuthal equidistant plane and the images there of the eye's east and north unit vectors
// (a first-order map from the eye's local plane to the window plane; its error grows as
// offset x distance / earth radius: < 300 m at 700 km, where texels are 40 km).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace sky
{

/// Latitude spacing of the lattice (degrees): 0.02 deg is 2.2 km, about two window texels at the eye.
inline constexpr double kWindowLatticeDeg = 0.02;

/// A lattice node: the centre of a weather window.
struct WindowCentre
{
    int64_t row = 0;        ///< latitude index: latDeg = row * kWindowLatticeDeg
    int64_t column = 0;     ///< longitude index within the row
    double latDeg = 0;      ///< node latitude (degrees, [-90, 90])
    double lonDeg = 0;      ///< node longitude (degrees, [-180, 180))
    bool operator==(const WindowCentre& o) const { return row == o.row && column == o.column; }
};

/// The lattice node that serves an eye at (latDeg, lonDeg) (degrees; any longitude convention). Rows are
/// kWindowLatticeDeg apart; each row holds a whole number of nodes, as close to kWindowLatticeDeg of
/// arc apart as that allows (so nodes get sparser in longitude toward the poles, and a row at a pole
/// has one node). The eye is at most ~1.6 km from its node.
WindowCentre windowCentreForEye(double latDeg, double lonDeg);

/// Where the eye lies on a window centred at `centre`.
struct EyeOnWindow
{
    glm::dvec2 offsetM{0.0};    ///< the eye's easting, northing on the window plane (m)
    glm::dvec2 eastAxis{1, 0};  ///< window-plane image of 1 m toward the eye's east
    glm::dvec2 northAxis{0, 1}; ///< ... and of 1 m toward the eye's north
};

/// The eye's place on the window centred at (centreLatDeg, centreLonDeg): WGS84 azimuthal equidistant
/// (GeographicLib), with the axes measured by projecting points 50 m east and north of the eye.
EyeOnWindow placeEyeOnWindow(double centreLatDeg, double centreLonDeg, double eyeLatDeg, double eyeLonDeg);

}  // namespace sky
