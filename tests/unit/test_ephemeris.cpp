// SPDX-License-Identifier: MIT
// Sun and moon positions against published values (the ISO 8601 times they take: test_civil_time.cpp).
#include "skyservice/sky/ephemeris.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{

using namespace sky;

// Angle (degrees) between two unit vectors.
double separationDeg(const glm::dvec3& a, const glm::dvec3& b)
{
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / M_PI;
}

// Reda & Andreas, "Solar Position Algorithm for Solar Radiation Applications" (NREL/TP-560-34302,
// 2008), worked example: 2003-10-17 12:30:30 local (UTC-7), 39.742476 N, 105.1786 W, 1830.14 m,
// 820 mbar, 11 C: topocentric zenith 50.11162 deg (refracted), azimuth 194.34024 deg.
TEST(Ephemeris, SunMatchesSpaPaperExample)
{
    int64_t t = 0;
    std::string error;
    ASSERT_TRUE(parseIso8601Utc("2003-10-17T12:30:30-07:00", t, error)) << error;
    RefractionConditions air;
    air.pressureHPa = 820.0;
    air.temperatureC = 11.0;
    SunMoon sm = computeSunMoon(t, 39.742476, -105.1786, 1830.14, air);
    EXPECT_NEAR(90.0 - sm.sun.apparentElevationDeg, 50.11162, 0.05);
    EXPECT_NEAR(sm.sun.azimuthDeg, 194.34024, 0.05);
    // Measured: both within 0.01 deg; keep that margin visible.
    EXPECT_NEAR(90.0 - sm.sun.apparentElevationDeg, 50.11162, 0.01);
    EXPECT_NEAR(sm.sun.azimuthDeg, 194.34024, 0.01);
    // Geometric elevation is below the refracted one by the SPA refraction (~0.016 deg at 40 deg).
    EXPECT_NEAR(sm.sun.apparentElevationDeg - sm.sun.elevationDeg, 0.0166, 0.002);
    EXPECT_NEAR(sm.sun.distanceM / 149597870700.0, 0.9965, 0.001);
    EXPECT_NEAR(glm::length(sm.sun.directionEnu), 1.0, 1e-12);
}

// Meeus, Astronomical Algorithms, Example 25.a: 1992 October 13.0 TD, apparent alpha = 198.38083,
// delta = -7.78507 deg, R = 0.99766 AU.
TEST(Ephemeris, SunMatchesMeeusExample25a)
{
    EquatorialPosition sun = sunEquatorial(2448908.5);
    EXPECT_NEAR(sun.rightAscensionDeg, 198.38083, 0.005);
    EXPECT_NEAR(sun.declinationDeg, -7.78507, 0.005);
    EXPECT_NEAR(sun.distanceM / 149597870700.0, 0.99766, 0.00005);
}

// June solstice 2026 (08:24 UTC) at the Royal Observatory, Greenwich (51.4769 N, 0.0005 W): the noon
// elevation is 90 - lat + obliquity (23.438 deg in 2026, true obliquity of date) and solar noon falls at
// 12:01-12:02 UTC (equation of time about -1.7 min, as the NOAA solar calculator gives).
TEST(Ephemeris, SolsticeNoonAtGreenwich)
{
    int64_t start = 0;
    std::string error;
    ASSERT_TRUE(parseIso8601Utc("2026-06-21T11:30:00Z", start, error)) << error;
    double best = -90.0;
    int64_t bestT = start;
    for (int64_t t = start; t <= start + 3600; t += 10)
    {
        SunMoon sm = computeSunMoon(t, 51.4769, -0.0005, 46.0);
        if (sm.sun.elevationDeg > best)
        {
            best = sm.sun.elevationDeg;
            bestT = t;
        }
    }
    EXPECT_NEAR(best, 90.0 - 51.4769 + 23.438, 0.01);
    int64_t noon = 0;
    ASSERT_TRUE(parseIso8601Utc("2026-06-21T12:00:00Z", noon, error));
    EXPECT_GT(bestT, noon + 50);
    EXPECT_LT(bestT, noon + 170);
    // At solar noon the sun is due south.
    SunMoon atNoon = computeSunMoon(bestT, 51.4769, -0.0005, 46.0);
    EXPECT_NEAR(atNoon.sun.azimuthDeg, 180.0, 0.1);
}

// Meeus Example 47.a: 1992 April 12.0 TD, alpha = 134.688470, delta = 13.768368 deg,
// distance 368409.7 km (full series; we keep the largest terms).
TEST(Ephemeris, MoonMatchesMeeusExample47a)
{
    EquatorialPosition moon = moonEquatorial(2448724.5);
    EXPECT_NEAR(moon.rightAscensionDeg, 134.688470, 0.02);
    EXPECT_NEAR(moon.declinationDeg, 13.768368, 0.02);
    EXPECT_NEAR(moon.distanceM / 1000.0, 368409.7, 30.0);
}

// Meeus Example 48.a: at the same instant the illuminated fraction is 0.6786.
TEST(Ephemeris, MoonIlluminatedFractionMatchesMeeusExample48a)
{
    // 1992-04-12 00:00 TD is 58 s earlier in UTC; the fraction changes by 3e-4 per minute.
    SunMoon sm = computeSunMoon(703036800 - 58, 0.0, 0.0, 0.0);
    EXPECT_NEAR(sm.moonIlluminatedFraction, 0.6786, 0.003);
    EXPECT_NEAR(sm.moonPhaseAngleDeg, 69.0756, 0.3);
}

// At the point and time of greatest eclipse of a total solar eclipse the moon's topocentric centre
// covers the sun's (Espenak, NASA eclipse bulletins): a test of the moon's position including its
// 0.95-degree parallax, which on its own would move it by 0.3 degree here.
struct Eclipse
{
    const char* time;
    double latDeg;
    double lonDeg;
};

TEST(Ephemeris, MoonCoversSunAtGreatestEclipse)
{
    const Eclipse eclipses[] = {
        {"2024-04-08T18:17:16Z", 25.0 + 17.4 / 60.0, -(104.0 + 8.3 / 60.0)},  // NASA: 25 17.4'N 104 08.3'W
        {"2017-08-21T18:25:32Z", 36.0 + 58.0 / 60.0, -(87.0 + 40.0 / 60.0)},  // NASA: 36 58'N 87 40'W
    };
    for (const Eclipse& e : eclipses)
    {
        int64_t t = 0;
        std::string error;
        ASSERT_TRUE(parseIso8601Utc(e.time, t, error)) << error;
        SunMoon sm = computeSunMoon(t, e.latDeg, e.lonDeg, 0.0);
        EXPECT_LT(separationDeg(sm.sun.directionEnu, sm.moon.directionEnu), 0.1) << e.time;
        EXPECT_LT(sm.moonIlluminatedFraction, 0.001) << e.time;
        // Far from the path the same instant shows the two well apart (parallax matters).
        SunMoon south = computeSunMoon(t, e.latDeg - 60.0, e.lonDeg, 0.0);
        EXPECT_GT(separationDeg(south.sun.directionEnu, south.moon.directionEnu), 0.5) << e.time;
        EXPECT_NEAR(sm.moon.distanceM, 3.6e8, 0.3e8);
    }
}

TEST(Ephemeris, RefractionFollowsSaemundsson)
{
    RefractionConditions standard;
    // Meeus eq. 16.4 at a true altitude of 0: 1.02 / tan(10.3 / 5.11 deg) arcmin = 28.98'.
    EXPECT_NEAR(refractionDeg(0.0, standard), 28.98 / 60.0, 0.005);
    EXPECT_LT(refractionDeg(89.9, standard), 0.001);
    EXPECT_EQ(refractionDeg(-5.0, standard), 0.0);
}

}  // namespace
