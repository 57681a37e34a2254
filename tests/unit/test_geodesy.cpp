// SPDX-License-Identifier: MIT
// Eye pose, camera frame and osculating-sphere error budget (skyservice/earth/geodesy.h).
#include "skyservice/earth/geodesy.h"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace
{

using sky::CameraFrame;
using sky::EyePose;

const double kA = GeographicLib::Constants::WGS84_a();
const double kF = GeographicLib::Constants::WGS84_f();
const double kE2 = kF * (2.0 - kF);

EyePose pose(double latDeg, double lonDeg, double altitudeM, double headingDeg = 0, double pitchDeg = 0,
             double rollDeg = 0)
{
    EyePose p;
    p.latDeg = latDeg;
    p.lonDeg = lonDeg;
    p.altitudeM = altitudeM;
    p.headingDeg = headingDeg;
    p.pitchDeg = pitchDeg;
    p.rollDeg = rollDeg;
    return p;
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(Geodesy, ValidatesEyePose)
{
    std::string error;
    EXPECT_TRUE(sky::validateEyePose(pose(45, 7, 3000, 270, -10, 5), error)) << error;
    EXPECT_TRUE(error.empty());
    EXPECT_TRUE(sky::validateEyePose(pose(-90, 725, -500), error)) << error;
    EXPECT_TRUE(sky::validateEyePose(pose(90, -3600, 100000), error)) << error;

    EXPECT_FALSE(sky::validateEyePose(pose(90.001, 0, 0), error));
    EXPECT_NE(error.find("latDeg"), std::string::npos) << error;
    EXPECT_FALSE(sky::validateEyePose(pose(std::nan(""), 0, 0), error));
    EXPECT_FALSE(sky::validateEyePose(pose(0, std::numeric_limits<double>::infinity(), 0), error));
    EXPECT_NE(error.find("lonDeg"), std::string::npos) << error;
    EXPECT_FALSE(sky::validateEyePose(pose(0, 0, -500.5), error));
    EXPECT_NE(error.find("altitudeM"), std::string::npos) << error;
    EXPECT_FALSE(sky::validateEyePose(pose(0, 0, 100000.5), error));
    EXPECT_FALSE(sky::validateEyePose(pose(0, 0, 0, std::nan("")), error));
    EXPECT_NE(error.find("headingDeg"), std::string::npos) << error;
    EXPECT_FALSE(sky::validateEyePose(pose(0, 0, 0, 0, std::nan("")), error));
    EXPECT_NE(error.find("pitchDeg"), std::string::npos) << error;
    EXPECT_FALSE(sky::validateEyePose(pose(0, 0, 0, 0, 0, -std::numeric_limits<double>::infinity()), error));
    EXPECT_NE(error.find("rollDeg"), std::string::npos) << error;
}

TEST(Geodesy, NormalizesLongitudeAndHeading)
{
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, 190, 0)).lonDeg, -170.0);
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, 180, 0)).lonDeg, -180.0);
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, -540, 0)).lonDeg, -180.0);
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, 725, 0)).lonDeg, 5.0);
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, 0, 0, -90)).headingDeg, 270.0);
    EXPECT_DOUBLE_EQ(sky::normalizeEyePose(pose(0, 0, 0, 720)).headingDeg, 0.0);
    // The frame keeps the normalised pose, and a wrapped longitude gives the same position.
    const CameraFrame wrapped = sky::computeCameraFrame(pose(10, 370, 500));
    const CameraFrame plain = sky::computeCameraFrame(pose(10, 10, 500));
    EXPECT_DOUBLE_EQ(wrapped.eye.lonDeg, 10.0);
    expectNear(wrapped.eyeEcefM, plain.eyeEcefM, 1e-6);
}

// Golden values from the closed-form geodetic-to-ECEF equations (e.g. Torge & Müller §4.2), written
// out independently of GeographicLib.
TEST(Geodesy, EyeEcefAndEnuBasisMatchClosedForm)
{
    struct Golden
    {
        double latDeg, lonDeg, hM;
    };
    for (const Golden g : {Golden{0, 0, 0}, Golden{45, 45, 1000}, Golden{-33.9, 151.2, 11000}, Golden{89.9, -120, 50},
                           Golden{-90, 0, 100}})
    {
        const CameraFrame frame = sky::computeCameraFrame(pose(g.latDeg, g.lonDeg, g.hM));
        const double phi = g.latDeg * M_PI / 180.0;
        const double lambda = g.lonDeg * M_PI / 180.0;
        const double n = kA / std::sqrt(1.0 - kE2 * std::sin(phi) * std::sin(phi));
        const glm::dvec3 expected((n + g.hM) * std::cos(phi) * std::cos(lambda),
                                  (n + g.hM) * std::cos(phi) * std::sin(lambda),
                                  (n * (1.0 - kE2) + g.hM) * std::sin(phi));
        expectNear(frame.eyeEcefM, expected, 1e-6);
        const glm::dvec3 east(-std::sin(lambda), std::cos(lambda), 0.0);
        const glm::dvec3 north(-std::sin(phi) * std::cos(lambda), -std::sin(phi) * std::sin(lambda), std::cos(phi));
        const glm::dvec3 up(std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi));
        expectNear(frame.enuToEcef[0], east, 1e-12);
        expectNear(frame.enuToEcef[1], north, 1e-12);
        expectNear(frame.enuToEcef[2], up, 1e-12);
    }
}

TEST(Geodesy, OsculatingSphereRadius)
{
    const double b = kA * (1.0 - kF);
    // Equator: M = a (1 - e^2), N = a.  Pole: M = N = a^2 / b.
    EXPECT_NEAR(sky::gaussianMeanRadiusM(0), kA * std::sqrt(1.0 - kE2), 1e-6);
    EXPECT_NEAR(sky::gaussianMeanRadiusM(90), kA * kA / b, 1e-6);
    EXPECT_NEAR(sky::gaussianMeanRadiusM(-90), kA * kA / b, 1e-6);
    const CameraFrame frame = sky::computeCameraFrame(pose(45, 7, 2500));
    EXPECT_DOUBLE_EQ(frame.localEarthRadiusM, sky::gaussianMeanRadiusM(45));
    expectNear(frame.earthCentreEnuM, glm::dvec3(0, 0, -(frame.localEarthRadiusM + 2500.0)), 1e-9);
    EXPECT_NEAR(sky::sphereAltitudeM(frame, glm::dvec3(0.0)), 2500.0, 1e-6);
    // One degree of latitude is about 111.1 km at 45 degrees; one of longitude about 78.8 km.
    EXPECT_NEAR(sky::metersPerDegreeLatitude(45), 111132.0, 2.0);
    EXPECT_NEAR(sky::metersPerDegreeLongitude(45), 78847.0, 2.0);
}

TEST(Geodesy, CameraAxesFollowHeadingPitchRoll)
{
    CameraFrame f = sky::computeCameraFrame(pose(45, 7, 1000, 0, 0, 0));
    expectNear(f.forwardEnu, {0, 1, 0}, 1e-15);
    expectNear(f.rightEnu, {1, 0, 0}, 1e-15);
    expectNear(f.upEnu, {0, 0, 1}, 1e-15);
    f = sky::computeCameraFrame(pose(45, 7, 1000, 90, 0, 0));
    expectNear(f.forwardEnu, {1, 0, 0}, 1e-15);
    expectNear(f.rightEnu, {0, -1, 0}, 1e-15);
    f = sky::computeCameraFrame(pose(45, 7, 1000, 0, 30, 0));
    expectNear(f.forwardEnu, {0, std::sqrt(3.0) / 2, 0.5}, 1e-15);
    expectNear(f.upEnu, {0, -0.5, std::sqrt(3.0) / 2}, 1e-15);
    // Right wing down: the right axis points below the horizon, the camera's up leans right.
    f = sky::computeCameraFrame(pose(45, 7, 1000, 0, 0, 20));
    EXPECT_LT(f.rightEnu.z, -0.3);
    EXPECT_GT(f.upEnu.x, 0.3);
    f = sky::computeCameraFrame(pose(45, 7, 1000, 0, 0, 90));
    expectNear(f.rightEnu, {0, 0, -1}, 1e-15);
    expectNear(f.upEnu, {1, 0, 0}, 1e-15);

    for (double heading = -180; heading <= 360; heading += 37)
        for (double pitch = -90; pitch <= 90; pitch += 22.5)
            for (double roll = -180; roll <= 180; roll += 45)
            {
                const CameraFrame g = sky::computeCameraFrame(pose(10, 20, 300, heading, pitch, roll));
                EXPECT_NEAR(glm::length(g.forwardEnu), 1.0, 1e-14);
                EXPECT_NEAR(glm::length(g.rightEnu), 1.0, 1e-14);
                EXPECT_NEAR(glm::dot(g.forwardEnu, g.rightEnu), 0.0, 1e-14);
                EXPECT_NEAR(glm::dot(g.forwardEnu, g.upEnu), 0.0, 1e-14);
                expectNear(glm::cross(g.rightEnu, g.forwardEnu), g.upEnu, 1e-14);
                double azimuth = 0;
                double elevation = 0;
                sky::enuDirectionToAzimuthElevation(g.forwardEnu, azimuth, elevation);
                EXPECT_NEAR(elevation, pitch, 1e-9);
            }
}

TEST(Geodesy, GeodeticToEnuRoundTrip)
{
    const CameraFrame f = sky::computeCameraFrame(pose(46, 8, 2000));
    expectNear(sky::geodeticToEnu(f, 46, 8, 2000), {0, 0, 0}, 1e-6);
    expectNear(sky::geodeticToEnu(f, 46, 8, 3500), {0, 0, 1500}, 1e-6);
    // 1 degree north: about 111 km north and, at the same height, below the tangent plane by about
    // d^2 / 2R = 970 m.
    const glm::dvec3 north = sky::geodeticToEnu(f, 47, 8, 2000);
    EXPECT_NEAR(north.x, 0.0, 1e-6);
    EXPECT_NEAR(north.y, 111170.0, 200.0);
    EXPECT_NEAR(north.z, -970.0, 10.0);
    double lat = 0;
    double lon = 0;
    double h = 0;
    sky::enuToGeodetic(f, glm::dvec3(-150000.0, 320000.0, 4000.0), lat, lon, h);
    expectNear(sky::geodeticToEnu(f, lat, lon, h), {-150000.0, 320000.0, 4000.0}, 1e-6);
}

TEST(Geodesy, AzimuthElevation)
{
    struct Case
    {
        glm::dvec3 direction;
        double azimuthDeg, elevationDeg;
    };
    for (const Case& c : {Case{{0, 1, 0}, 0, 0}, Case{{1, 0, 0}, 90, 0}, Case{{0, -2, 0}, 180, 0},
                          Case{{-1, 0, 0}, 270, 0}, Case{{1, 1, std::sqrt(2.0)}, 45, 45},
                          Case{{-1, -1, -std::sqrt(2.0)}, 225, -45}})
    {
        double azimuth = -1;
        double elevation = -1;
        sky::enuDirectionToAzimuthElevation(c.direction, azimuth, elevation);
        EXPECT_NEAR(azimuth, c.azimuthDeg, 1e-12);
        EXPECT_NEAR(elevation, c.elevationDeg, 1e-12);
        expectNear(sky::azimuthElevationToEnuDirection(azimuth, elevation), glm::normalize(c.direction), 1e-15);
    }
    double azimuth = -1;
    double elevation = -1;
    sky::enuDirectionToAzimuthElevation({0, 0, 5}, azimuth, elevation);
    EXPECT_DOUBLE_EQ(elevation, 90.0);
    EXPECT_GE(azimuth, 0.0);
    EXPECT_LT(azimuth, 360.0);
}

TEST(Geodesy, HorizonDistanceIsTangent)
{
    EXPECT_EQ(sky::distanceToHorizonM(0, 6371000), 0.0);
    EXPECT_EQ(sky::distanceToHorizonM(-20, 6371000), 0.0);
    EXPECT_NEAR(sky::distanceToHorizonM(10000, 6371000), std::sqrt(10000.0 * 12752000.0), 1e-6);
    // The straight line to the horizon grazes the osculating sphere: zero altitude at its end.
    const CameraFrame f = sky::computeCameraFrame(pose(45, 7, 11000));
    const double d = sky::distanceToHorizonM(11000, f.localEarthRadiusM);
    const double dipDeg = -std::acos(f.localEarthRadiusM / (f.localEarthRadiusM + 11000.0)) * 180.0 / M_PI;
    const glm::dvec3 end = d * sky::azimuthElevationToEnuDirection(123, dipDeg);
    EXPECT_NEAR(sky::sphereAltitudeM(f, end), 0.0, 1e-3);
    EXPECT_GT(d, 370000.0);  // about 374 km at 11 km: DESIGN's ~700 km needs cloud tops, not ground
}

// The error budget of docs/datums.md: layer shells are spheres around the eye, the truth is the height
// above the ellipsoid. For points at a given geodesic distance from the eye (every 15 degrees of
// azimuth), at cloud heights, this measures the worst |sphere altitude - ellipsoidal height| for the
// Gaussian sphere (one radius for all directions) and for the normal-section sphere (one radius per
// azimuth), and checks them against the numbers documented in skyservice/earth/geodesy.h.
TEST(Geodesy, OsculatingSphereErrorBudget)
{
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    const double distancesKm[] = {25, 50, 100, 200, 300, 400, 700};
    // Documented bounds (meters), about 1.2 x the worst measured value (at the equator).
    const double gaussianBoundsM[] = {0.2, 0.8, 3.2, 13.0, 29.0, 51.0, 155.0};
    const double sectionBoundsM[] = {0.01, 0.01, 0.06, 0.4, 1.4, 3.2, 17.0};
    for (const double eyeLat : {0.0, 30.0, 45.0, 60.0, 80.0, -89.0})
    {
        std::printf("eye lat %4.0f  gaussian / normal section:", eyeLat);
        for (size_t n = 0; n < std::size(distancesKm); ++n)
        {
            double worstGaussian = 0;
            double worstSection = 0;
            for (const double eyeAlt : {100.0, 11000.0})
            {
                const CameraFrame f = sky::computeCameraFrame(pose(eyeLat, 10, eyeAlt));
                for (double azimuth = 0; azimuth < 360; azimuth += 15)
                    for (const double h : {1000.0, 5000.0, 12000.0})
                    {
                        double lat = 0;
                        double lon = 0;
                        geodesic.Direct(eyeLat, 10, azimuth, distancesKm[n] * 1000.0, lat, lon);
                        const glm::dvec3 enu = sky::geodeticToEnu(f, lat, lon, h);
                        worstGaussian = std::max(worstGaussian, std::abs(sky::sphereAltitudeM(f, enu) - h));
                        worstSection = std::max(worstSection, std::abs(sky::normalSectionAltitudeM(f, enu) - h));
                    }
            }
            std::printf("  %3.0f km: %.3f / %.3f m", distancesKm[n], worstGaussian, worstSection);
            EXPECT_LT(worstGaussian, gaussianBoundsM[n]) << "eye lat " << eyeLat << ", " << distancesKm[n] << " km";
            EXPECT_LT(worstSection, sectionBoundsM[n]) << "eye lat " << eyeLat << ", " << distancesKm[n] << " km";
        }
        std::printf("\n");
    }
}

}  // namespace
