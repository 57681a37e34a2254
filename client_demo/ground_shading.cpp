// SPDX-License-Identifier: MIT
#include "client_demo/ground_shading.h"

#include <GeographicLib/Constants.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace demo
{
namespace
{

constexpr double kDegToRad = M_PI / 180.0;

// Meridional (M) and prime-vertical (N) radii of curvature of the WGS84 ellipsoid at a latitude
// (textbook formulas; a and f from GeographicLib).
void radiiOfCurvatureM(double latDeg, double& meridionalM, double& primeVerticalM)
{
    const double a = GeographicLib::Constants::WGS84_a<double>();
    const double f = GeographicLib::Constants::WGS84_f<double>();
    const double e2 = f * (2.0 - f);
    const double s = std::sin(latDeg * kDegToRad);
    const double w = 1.0 - e2 * s * s;
    primeVerticalM = a / std::sqrt(w);
    meridionalM = a * (1.0 - e2) / (w * std::sqrt(w));
}

double wrapDeg180(double deg)
{
    double d = std::fmod(deg + 180.0, 360.0);
    if (d < 0.0)
        d += 360.0;
    return d - 180.0;
}

}  // namespace

GroundCamera makeGroundCamera(const SkyShmView& view)
{
    GroundCamera c;
    const double heading = view.heading_deg * kDegToRad;
    const double pitch = view.pitch_deg * kDegToRad;
    const double roll = view.roll_deg * kDegToRad;
    const glm::dvec3 forward(std::sin(heading) * std::cos(pitch), std::cos(heading) * std::cos(pitch), std::sin(pitch));
    const glm::dvec3 right0(std::cos(heading), -std::sin(heading), 0.0);
    const glm::dvec3 up0 = glm::cross(right0, forward);
    c.forwardEnu = forward;
    c.rightEnu = std::cos(roll) * right0 - std::sin(roll) * up0;
    c.upEnu = std::cos(roll) * up0 + std::sin(roll) * right0;
    c.width = std::max(view.width, 1u);
    c.height = std::max(view.height, 1u);
    if (view.asymmetric == 1)
    {
        c.tanLeft = std::tan(view.left_deg * kDegToRad);
        c.tanRight = std::tan(view.right_deg * kDegToRad);
        c.tanUp = std::tan(view.up_deg * kDegToRad);
        c.tanDown = std::tan(view.down_deg * kDegToRad);
    }
    else
    {
        c.tanUp = c.tanDown = std::tan(view.fov_deg * kDegToRad * 0.5);
        c.tanLeft = c.tanRight = c.tanUp * double(c.width) / double(c.height);
    }
    c.altitudeM = view.alt_m;
    c.latDeg = view.lat_deg;
    c.lonDeg = view.lon_deg;
    double m = 0.0;
    double n = 0.0;
    radiiOfCurvatureM(view.lat_deg, m, n);
    c.earthRadiusM = std::sqrt(m * n);
    return c;
}

glm::dvec3 viewRay(const GroundCamera& camera, double xPx, double yPx)
{
    // Left edge -tanLeft to right edge +tanRight; top edge +tanUp to bottom edge -tanDown (view_ray.glsl).
    const double u = xPx / double(camera.width);
    const double v = yPx / double(camera.height);
    const double x = -camera.tanLeft + u * (camera.tanLeft + camera.tanRight);
    const double y = camera.tanUp - v * (camera.tanUp + camera.tanDown);
    return glm::normalize(camera.forwardEnu + x * camera.rightEnu + y * camera.upEnu);
}

bool intersectGround(const GroundCamera& camera, const glm::dvec3& dirEnu, GroundHit& hit)
{
    if (camera.altitudeM <= 0.0 || dirEnu.z >= 0.0)
        return false;
    // |e + t d - c| = R with the centre c straight below the eye: t^2 + 2 t (R + h) mu + (h^2 + 2 h R) = 0.
    // The constant term is written without cancellation (docs/datums.md).
    const double h = camera.altitudeM;
    const double rPlusH = camera.earthRadiusM + h;
    const double mu = dirEnu.z;
    const double b = rPlusH * mu;
    const double c = h * (2.0 * camera.earthRadiusM + h);
    const double disc = b * b - c;
    if (disc < 0.0)
        return false;
    // Near root as c / (-b + sqrt(disc)) (b < 0 here): stable for grazing rays.
    const double t = c / (-b + std::sqrt(disc));
    hit.distanceM = t;
    hit.eastM = t * dirEnu.x;
    hit.northM = t * dirEnu.y;
    return true;
}

std::array<double, 2> offsetFromShadowCentreM(double latDeg, double lonDeg, const SkyShmShadowGeoRef& geo)
{
    double m = 0.0;
    double n = 0.0;
    radiiOfCurvatureM(geo.centre_lat_deg, m, n);
    const double east = wrapDeg180(lonDeg - geo.centre_lon_deg) * kDegToRad * n * std::cos(geo.centre_lat_deg * kDegToRad);
    const double north = (latDeg - geo.centre_lat_deg) * kDegToRad * m;
    return {east, north};
}

double shadowTransmittanceAt(const std::vector<float>& transmittance, uint32_t size, double extentM, double eastM,
                             double northM)
{
    if (size == 0 || extentM <= 0.0 || transmittance.size() < size_t(size) * size)
        return 1.0;
    const double texelM = extentM / double(size);
    // Continuous texel coordinates whose integer points are texel centres.
    const double u = eastM / texelM + double(size) * 0.5 - 0.5;
    const double v = double(size) * 0.5 - 0.5 - northM / texelM;
    if (u < -0.5 || v < -0.5 || u > double(size) - 0.5 || v > double(size) - 0.5)
        return 1.0;
    const double last = double(size - 1);
    const double uc = std::clamp(u, 0.0, last);
    const double vc = std::clamp(v, 0.0, last);
    const auto c0 = uint32_t(uc);
    const auto r0 = uint32_t(vc);
    const uint32_t c1 = std::min(c0 + 1, size - 1);
    const uint32_t r1 = std::min(r0 + 1, size - 1);
    const double fu = uc - double(c0);
    const double fv = vc - double(r0);
    auto at = [&](uint32_t c, uint32_t r) { return double(transmittance[size_t(r) * size + c]); };
    const double top = at(c0, r0) * (1.0 - fu) + at(c1, r0) * fu;
    const double bottom = at(c0, r1) * (1.0 - fu) + at(c1, r1) * fu;
    return std::clamp(top * (1.0 - fv) + bottom * fv, 0.0, 1.0);
}

glm::dvec3 shadeGround(double groundLatDeg, double groundLonDeg, const GroundLight& light, double shadowTransmittance)
{
    // Fields of 0.02 degrees (~2 km): big enough to read at cruise altitude, small enough to show motion.
    const auto i = int64_t(std::floor(groundLatDeg / 0.02));
    const auto j = int64_t(std::floor(groundLonDeg / 0.02));
    const bool dark = ((i + j) & 1) != 0;
    // sRGB albedo-ish colours of meadow and ploughed field; a per-field hash varies them a little.
    const uint64_t hash = uint64_t(i * 73856093) ^ uint64_t(j * 19349663);
    const double vary = 0.9 + 0.2 * double(hash % 101) / 100.0;
    const glm::dvec3 albedo = dark ? glm::dvec3(0.36, 0.30, 0.20) : glm::dvec3(0.30, 0.42, 0.20);
    // Direct light grows with the sine of the elevation, saturating at ~20 degrees; the sky's ambient light
    // keeps shadowed ground at about a third of sunlit ground (a display-space approximation, not physics).
    const double sinElev = std::sin(std::clamp(light.sunElevationDeg, -90.0, 90.0) * kDegToRad);
    const double direct = std::clamp(sinElev * 3.0, 0.0, 1.0);
    const double ambient = 0.35 * std::clamp(sinElev * 5.0 + 0.3, 0.05, 1.0);
    double lit = ambient + (1.0 - 0.35) * direct * std::clamp(shadowTransmittance, 0.0, 1.0);
    if (light.isMoon)
        lit *= 0.12;
    return albedo * vary * lit;
}

std::array<double, 2> groundLatLonDeg(const GroundCamera& camera, const GroundHit& hit)
{
    double m = 0.0;
    double n = 0.0;
    radiiOfCurvatureM(camera.latDeg, m, n);
    const double lat = camera.latDeg + hit.northM / m / kDegToRad;
    const double lon = camera.lonDeg + hit.eastM / (n * std::max(std::cos(camera.latDeg * kDegToRad), 1e-6)) / kDegToRad;
    return {lat, lon};
}

}  // namespace demo
