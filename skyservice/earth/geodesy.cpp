// SPDX-License-Identifier: MIT
#include "skyservice/earth/geodesy.h"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Math.hpp>

#include <cmath>
#include <sstream>
#include <vector>

namespace sky
{

namespace
{

using GeographicLib::Math;

// Eye altitudes accepted: from below the Dead Sea shore to the edge of the mesosphere's lower part,
// where our atmosphere model still holds (skyservice/ipc/PROTOCOL.md names no limits; these are ours).
constexpr double kMinEyeAltitudeM = -500.0;
constexpr double kMaxEyeAltitudeM = 100000.0;

double firstEccentricitySquared()
{
    const double f = GeographicLib::Constants::WGS84_f();
    return f * (2.0 - f);
}

// Meridional (M) and prime-vertical (N) radii of curvature, e.g. Torge & Müller, "Geodesy" §4.2.
void radiiOfCurvature(double latDeg, double& meridionalM, double& primeVerticalM)
{
    const double a = GeographicLib::Constants::WGS84_a();
    const double e2 = firstEccentricitySquared();
    double s = 0;
    double c = 0;
    Math::sincosd(latDeg, s, c);
    const double w2 = 1.0 - e2 * s * s;
    const double w = std::sqrt(w2);
    primeVerticalM = a / w;
    meridionalM = a * (1.0 - e2) / (w2 * w);
}

bool failField(std::string& error, const char* field, double value, const char* range)
{
    std::ostringstream message;
    message << "eye pose: " << field << " = " << value << " is out of range (" << range << ")";
    error = message.str();
    return false;
}

}  // namespace

bool validateEyePose(const EyePose& pose, std::string& error)
{
    if (!std::isfinite(pose.latDeg) || pose.latDeg < -90.0 || pose.latDeg > 90.0)
        return failField(error, "latDeg", pose.latDeg, "[-90, 90] degrees");
    if (!std::isfinite(pose.lonDeg))
        return failField(error, "lonDeg", pose.lonDeg, "finite degrees");
    if (!std::isfinite(pose.altitudeM) || pose.altitudeM < kMinEyeAltitudeM || pose.altitudeM > kMaxEyeAltitudeM)
        return failField(error, "altitudeM", pose.altitudeM, "[-500, 100000] meters above the WGS84 ellipsoid");
    if (!std::isfinite(pose.headingDeg))
        return failField(error, "headingDeg", pose.headingDeg, "finite degrees");
    if (!std::isfinite(pose.pitchDeg))
        return failField(error, "pitchDeg", pose.pitchDeg, "finite degrees");
    if (!std::isfinite(pose.rollDeg))
        return failField(error, "rollDeg", pose.rollDeg, "finite degrees");
    error.clear();
    return true;
}

EyePose normalizeEyePose(const EyePose& pose)
{
    EyePose out = pose;
    out.lonDeg = Math::AngNormalize(pose.lonDeg);
    if (out.lonDeg >= 180.0)
        out.lonDeg -= 360.0;
    out.headingDeg = std::fmod(pose.headingDeg, 360.0);
    if (out.headingDeg < 0.0)
        out.headingDeg += 360.0;
    if (out.headingDeg >= 360.0)  // fmod of a tiny negative number plus 360 rounds to 360
        out.headingDeg = 0.0;
    return out;
}

double gaussianMeanRadiusM(double latDeg)
{
    double m = 0;
    double n = 0;
    radiiOfCurvature(latDeg, m, n);
    return std::sqrt(m * n);
}

double metersPerDegreeLatitude(double latDeg)
{
    double m = 0;
    double n = 0;
    radiiOfCurvature(latDeg, m, n);
    return m * Math::pi() / 180.0;
}

double metersPerDegreeLongitude(double latDeg)
{
    double m = 0;
    double n = 0;
    radiiOfCurvature(latDeg, m, n);
    double s = 0;
    double c = 0;
    Math::sincosd(latDeg, s, c);
    return n * c * Math::pi() / 180.0;
}

CameraFrame computeCameraFrame(const EyePose& pose)
{
    CameraFrame frame;
    frame.eye = normalizeEyePose(pose);
    const EyePose& eye = frame.eye;

    std::vector<double> m(9);
    GeographicLib::Geocentric::WGS84().Forward(eye.latDeg, eye.lonDeg, eye.altitudeM, frame.eyeEcefM.x,
                                               frame.eyeEcefM.y, frame.eyeEcefM.z, m);
    // GeographicLib's M is row-major with v_ecef = M v_enu, so its columns are east, north, up.
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            frame.enuToEcef[column][row] = m[size_t(row * 3 + column)];
    frame.localCartesian.Reset(eye.latDeg, eye.lonDeg, eye.altitudeM);

    radiiOfCurvature(eye.latDeg, frame.meridionalRadiusM, frame.primeVerticalRadiusM);
    frame.localEarthRadiusM = std::sqrt(frame.meridionalRadiusM * frame.primeVerticalRadiusM);
    frame.earthCentreEnuM = glm::dvec3(0.0, 0.0, -(frame.localEarthRadiusM + eye.altitudeM));

    double sinHeading = 0;
    double cosHeading = 0;
    double sinPitch = 0;
    double cosPitch = 0;
    double sinRoll = 0;
    double cosRoll = 0;
    Math::sincosd(eye.headingDeg, sinHeading, cosHeading);
    Math::sincosd(eye.pitchDeg, sinPitch, cosPitch);
    Math::sincosd(eye.rollDeg, sinRoll, cosRoll);
    const glm::dvec3 forward(sinHeading * cosPitch, cosHeading * cosPitch, sinPitch);
    const glm::dvec3 right0(cosHeading, -sinHeading, 0.0);
    const glm::dvec3 up0 = glm::cross(right0, forward);
    frame.forwardEnu = forward;
    frame.rightEnu = cosRoll * right0 - sinRoll * up0;
    frame.upEnu = cosRoll * up0 + sinRoll * right0;
    return frame;
}

glm::dvec3 geodeticToEnu(const CameraFrame& frame, double latDeg, double lonDeg, double hM)
{
    glm::dvec3 enu(0.0);
    frame.localCartesian.Forward(latDeg, lonDeg, hM, enu.x, enu.y, enu.z);
    return enu;
}

void enuToGeodetic(const CameraFrame& frame, const glm::dvec3& enuM, double& latDeg, double& lonDeg, double& hM)
{
    frame.localCartesian.Reverse(enuM.x, enuM.y, enuM.z, latDeg, lonDeg, hM);
}

double sphereAltitudeM(const CameraFrame& frame, const glm::dvec3& enuM)
{
    return glm::length(enuM - frame.earthCentreEnuM) - frame.localEarthRadiusM;
}

double normalSectionRadiusM(const CameraFrame& frame, double azimuthDeg)
{
    double s = 0;
    double c = 0;
    Math::sincosd(azimuthDeg, s, c);
    return 1.0 / (c * c / frame.meridionalRadiusM + s * s / frame.primeVerticalRadiusM);
}

double normalSectionAltitudeM(const CameraFrame& frame, const glm::dvec3& enuM)
{
    if (enuM.x == 0.0 && enuM.y == 0.0)
        return sphereAltitudeM(frame, enuM);
    const double radiusM = normalSectionRadiusM(frame, Math::atan2d(enuM.x, enuM.y));
    const glm::dvec3 centre(0.0, 0.0, -(radiusM + frame.eye.altitudeM));
    return glm::length(enuM - centre) - radiusM;
}

void enuDirectionToAzimuthElevation(const glm::dvec3& directionEnu, double& azimuthDeg, double& elevationDeg)
{
    const double horizontal = std::hypot(directionEnu.x, directionEnu.y);
    azimuthDeg = Math::atan2d(directionEnu.x, directionEnu.y);
    if (azimuthDeg < 0.0)
        azimuthDeg += 360.0;
    if (azimuthDeg >= 360.0)
        azimuthDeg = 0.0;
    elevationDeg = Math::atan2d(directionEnu.z, horizontal);
}

glm::dvec3 azimuthElevationToEnuDirection(double azimuthDeg, double elevationDeg)
{
    double sinAzimuth = 0;
    double cosAzimuth = 0;
    double sinElevation = 0;
    double cosElevation = 0;
    Math::sincosd(azimuthDeg, sinAzimuth, cosAzimuth);
    Math::sincosd(elevationDeg, sinElevation, cosElevation);
    return glm::dvec3(sinAzimuth * cosElevation, cosAzimuth * cosElevation, sinElevation);
}

double distanceToHorizonM(double altitudeM, double radiusM)
{
    if (!(altitudeM > 0.0))
        return 0.0;
    return std::sqrt(altitudeM * (2.0 * radiusM + altitudeM));
}

}  // namespace sky
