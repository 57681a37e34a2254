// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_view.h"

#include "skyservice/earth/geodesy.h"
#include "skyservice/render/view_frustum.h"
#include "skyservice/render/view_limits.h"

#include <GeographicLib/LocalCartesian.hpp>

#include <array>
#include <cmath>

namespace sky
{
namespace
{

using Mat3 = std::array<std::array<double, 3>, 3>;

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kRadToDeg = 180.0 / M_PI;

/// Body -> north-east-down rotation of yaw, then pitch, then roll (the aerospace sequence CIGI uses).
Mat3 bodyToNed(double yawDeg, double pitchDeg, double rollDeg)
{
    const double cy = std::cos(yawDeg * kDegToRad), sy = std::sin(yawDeg * kDegToRad);
    const double cp = std::cos(pitchDeg * kDegToRad), sp = std::sin(pitchDeg * kDegToRad);
    const double cr = std::cos(rollDeg * kDegToRad), sr = std::sin(rollDeg * kDegToRad);
    return {{{cp * cy, sr * sp * cy - cr * sy, cr * sp * cy + sr * sy},
             {cp * sy, sr * sp * sy + cr * cy, cr * sp * sy - sr * cy},
             {-sp, sr * cp, cr * cp}}};
}

Mat3 multiply(const Mat3& a, const Mat3& b)
{
    Mat3 m{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                m[size_t(i)][size_t(j)] += a[size_t(i)][size_t(k)] * b[size_t(k)][size_t(j)];
    return m;
}

} // namespace

bool cigiEyePose(const cigi::OwnshipPose& ownship, const cigi::ViewState* view, const cigi::GeoidGrid& geoid,
                 EyePose& out, std::string& error)
{
    if (!ownship.valid)
    {
        error = "no Entity Control for the ownship yet";
        return false;
    }
    double undulationM = geoid.undulationM(ownship.latDeg, ownship.lonDeg);
    if (!std::isfinite(undulationM))
        undulationM = 0; // no geoid grid: mean sea level taken as the ellipsoid (at most ~100 m off)
    const double heightM = ownship.altitudeMslM + undulationM;
    const Mat3 own = bodyToNed(ownship.yawDeg, ownship.pitchDeg, ownship.rollDeg);
    EyePose pose;
    pose.latDeg = ownship.latDeg;
    pose.lonDeg = ownship.lonDeg;
    pose.altitudeM = heightM;
    Mat3 eye = own;
    if (view)
    {
        eye = multiply(own, bodyToNed(view->yawDeg, view->pitchDeg, view->rollDeg));
        // The offset in the ownship's body axes, turned into north-east-down, then east-north-up.
        const double body[3] = {view->xOffsetM, view->yOffsetM, view->zOffsetM};
        double ned[3] = {0, 0, 0};
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                ned[i] += own[size_t(i)][size_t(k)] * body[k];
        if (ned[0] != 0 || ned[1] != 0 || ned[2] != 0)
        {
            const GeographicLib::LocalCartesian enu(ownship.latDeg, ownship.lonDeg, heightM);
            enu.Reverse(ned[1], ned[0], -ned[2], pose.latDeg, pose.lonDeg, pose.altitudeM);
        }
    }
    pose.headingDeg = std::atan2(eye[1][0], eye[0][0]) * kRadToDeg;
    pose.pitchDeg = std::asin(std::clamp(-eye[2][0], -1.0, 1.0)) * kRadToDeg;
    pose.rollDeg = std::atan2(eye[2][1], eye[2][2]) * kRadToDeg;
    if (!validateEyePose(pose, error))
        return false;
    out = normalizeEyePose(pose);
    return true;
}

bool cigiFrustum(const cigi::ViewState& view, Frustum& out, double& fovYDeg, std::string& error)
{
    Frustum f;
    f.asymmetric = true;
    f.leftDeg = -double(view.leftDeg);
    f.rightDeg = double(view.rightDeg);
    f.upDeg = double(view.topDeg);
    f.downDeg = -double(view.bottomDeg);
    // The renderer's own rule (view_limits.h), checked here where the host's view enters: a View
    // Definition it would refuse is not applied, so no frame meets it.
    std::string why;
    if (!validateFrustum(f, why))
    {
        error = "View Definition " + std::to_string(view.viewId) + ": " + why;
        return false;
    }
    out = f;
    fovYDeg = f.upDeg + f.downDeg; // within [kMinFovYDeg, kMaxFovYDeg]: each half-angle is under 85
    return true;
}

} // namespace sky
