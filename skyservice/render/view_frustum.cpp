// SPDX-License-Identifier: MIT
#include "skyservice/render/view_frustum.h"

#include "skyservice/render/view_limits.h"

#include <cmath>

namespace sky
{
namespace
{

// Degrees to radians as the symmetric path computes tan(fovY/2) (fovY * pi / 360): with up = fovY/2
// (a symmetric frustum given as angles) this gives the same double, so the same uniforms.
double tanDeg(double deg) { return std::tan(deg * M_PI / 180.0); }

}  // namespace

ViewTangents viewTangents(const ViewRequest& view)
{
    ViewTangents t;
    if (!view.frustum.asymmetric)
    {
        t.halfHeight = std::tan(view.fovYDeg * M_PI / 360.0);
        t.halfWidth = t.halfHeight * (double(view.width) / double(view.height));
        return t;
    }
    // The left and lower edges lie at -tan(left) and -tan(down) from the axis.
    const Frustum& f = view.frustum;
    const double left = tanDeg(f.leftDeg), right = tanDeg(f.rightDeg), up = tanDeg(f.upDeg), down = tanDeg(f.downDeg);
    t.halfWidth = 0.5 * (right + left);
    t.halfHeight = 0.5 * (up + down);
    t.centreX = 0.5 * (right - left);
    t.centreY = 0.5 * (up - down);
    return t;
}

bool validateFrustum(const Frustum& f, std::string& error)
{
    if (!f.asymmetric)
        return true;
    const struct
    {
        const char* name;
        double deg;
    } angles[] = {{"left", f.leftDeg}, {"right", f.rightDeg}, {"up", f.upDeg}, {"down", f.downDeg}};
    for (const auto& a : angles)
        if (!frustumHalfAngleInRange(a.deg))
        {
            error = std::string("frustum half-angle ") + a.name + " = " + std::to_string(a.deg) + " outside (-" +
                    std::to_string(int(kMaxFrustumHalfAngleDeg)) + ", " + std::to_string(int(kMaxFrustumHalfAngleDeg)) +
                    ") degrees";
            return false;
        }
    if (!(f.leftDeg + f.rightDeg > kMinFrustumSpanDeg))
    {
        error = "frustum left + right = " + std::to_string(f.leftDeg + f.rightDeg) +
                " degrees: the view must be more than 1 degree wide";
        return false;
    }
    if (!(f.upDeg + f.downDeg > kMinFrustumSpanDeg))
    {
        error = "frustum up + down = " + std::to_string(f.upDeg + f.downDeg) +
                " degrees: the view must be more than 1 degree high";
        return false;
    }
    return true;
}

bool sameProjection(const ViewRequest& a, const ViewRequest& b)
{
    if (a.width != b.width || a.height != b.height || a.frustum.asymmetric != b.frustum.asymmetric)
        return false;
    if (!a.frustum.asymmetric)
        return a.fovYDeg == b.fovYDeg;
    return a.frustum.leftDeg == b.frustum.leftDeg && a.frustum.rightDeg == b.frustum.rightDeg &&
           a.frustum.upDeg == b.frustum.upDeg && a.frustum.downDeg == b.frustum.downDeg;
}

double verticalExtentDeg(const ViewRequest& view)
{
    return view.frustum.asymmetric ? view.frustum.upDeg + view.frustum.downDeg : view.fovYDeg;
}

}  // namespace sky
