// SPDX-License-Identifier: MIT
#include "skyservice/sky/ephemeris.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Math.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace sky
{
namespace
{

using GeographicLib::Math;

constexpr double kJ2000 = 2451545.0;
constexpr double kUnixEpochJd = 2440587.5;
constexpr double kSecondsPerDay = 86400.0;
// IAU 2012 Resolution B2: the astronomical unit in metres, exactly.
constexpr double kAstronomicalUnitM = 149597870700.0;

double sind(double x)
{
    return Math::sind(x);
}
double cosd(double x)
{
    return Math::cosd(x);
}

double asind(double x)
{
    return std::asin(x) / Math::degree();
}
double acosd(double x)
{
    return std::acos(x) / Math::degree();
}

double normalizeDeg(double x)
{
    double y = std::fmod(x, 360.0);
    return y < 0 ? y + 360.0 : y;
}

// Nutation in longitude and obliquity (degrees), Meeus ch. 22 with its four largest terms (0.5"/0.1").
struct Nutation
{
    double longitudeDeg;
    double obliquityDeg;
};

Nutation nutation(double t)
{
    double omega = 125.04452 - 1934.136261 * t;
    double sunMeanLon = 280.4665 + 36000.7698 * t;
    double moonMeanLon = 218.3165 + 481267.8813 * t;
    double dpsiArcsec = -17.20 * sind(omega) - 1.32 * sind(2 * sunMeanLon) - 0.23 * sind(2 * moonMeanLon) +
                        0.21 * sind(2 * omega);
    double depsArcsec = 9.20 * cosd(omega) + 0.57 * cosd(2 * sunMeanLon) + 0.10 * cosd(2 * moonMeanLon) -
                        0.09 * cosd(2 * omega);
    return {dpsiArcsec / 3600.0, depsArcsec / 3600.0};
}

// Mean obliquity of the ecliptic (degrees), Meeus eq. 22.2.
double meanObliquityDeg(double t)
{
    return 23.0 + 26.0 / 60.0 + (21.448 - t * (46.8150 + t * (0.00059 - t * 0.001813))) / 3600.0;
}

EquatorialPosition eclipticToEquatorial(double lonDeg, double latDeg, double obliquityDeg, double distanceM)
{
    double sinLon, cosLon, sinLat, cosLat, sinEps, cosEps;
    Math::sincosd(lonDeg, sinLon, cosLon);
    Math::sincosd(latDeg, sinLat, cosLat);
    Math::sincosd(obliquityDeg, sinEps, cosEps);
    EquatorialPosition out;
    out.rightAscensionDeg = normalizeDeg(Math::atan2d(sinLon * cosLat * cosEps - sinLat * sinEps, cosLon * cosLat));
    out.declinationDeg = asind(sinLat * cosEps + cosLat * sinEps * sinLon);
    out.distanceM = distanceM;
    return out;
}

// Greenwich apparent sidereal time (degrees), Meeus eq. 12.4 plus the equation of the equinoxes.
double apparentSiderealTimeDeg(double julianDayUt, double t)
{
    double meanDeg = 280.46061837 + 360.98564736629 * (julianDayUt - kJ2000) + t * t * (0.000387933 - t / 38710000.0);
    Nutation n = nutation(t);
    return normalizeDeg(meanDeg + n.longitudeDeg * cosd(meanObliquityDeg(t) + n.obliquityDeg));
}

// One periodic term of Meeus tables 47.A / 47.B: multiples of D, M, M', F and the coefficient.
struct LunarTerm
{
    int8_t d, m, mp, f;
    int32_t coefficient;
};

// Table 47.A, longitude (1e-6 degree) and distance (1e-3 km): the first 32 of 60 rows (terms below
// 2e-3 degree and 10 km dropped).
constexpr std::array<LunarTerm, 32> kLunarLongitude = {{
    {0, 0, 1, 0, 6288774}, {2, 0, -1, 0, 1274027}, {2, 0, 0, 0, 658314}, {0, 0, 2, 0, 213618},
    {0, 1, 0, 0, -185116}, {0, 0, 0, 2, -114332}, {2, 0, -2, 0, 58793}, {2, -1, -1, 0, 57066},
    {2, 0, 1, 0, 53322},   {2, -1, 0, 0, 45758},  {0, 1, -1, 0, -40923}, {1, 0, 0, 0, -34720},
    {0, 1, 1, 0, -30383},  {2, 0, 0, -2, 15327},  {0, 0, 1, 2, -12528}, {0, 0, 1, -2, 10980},
    {4, 0, -1, 0, 10675},  {0, 0, 3, 0, 10034},   {4, 0, -2, 0, 8548},  {2, 1, -1, 0, -7888},
    {2, 1, 0, 0, -6766},   {1, 0, -1, 0, -5163},  {1, 1, 0, 0, 4987},   {2, -1, 1, 0, 4036},
    {2, 0, 2, 0, 3994},    {4, 0, 0, 0, 3861},    {2, 0, -3, 0, 3665},  {0, 1, -2, 0, -2689},
    {2, 0, -1, 2, -2602},  {2, -1, -2, 0, 2390},  {1, 0, 1, 0, -2348},  {2, -2, 0, 0, 2236},
}};
constexpr std::array<LunarTerm, 30> kLunarDistance = {{
    {0, 0, 1, 0, -20905355}, {2, 0, -1, 0, -3699111}, {2, 0, 0, 0, -2955968}, {0, 0, 2, 0, -569925},
    {0, 1, 0, 0, 48888},     {0, 0, 0, 2, -3149},     {2, 0, -2, 0, 246158},  {2, -1, -1, 0, -152138},
    {2, 0, 1, 0, -170733},   {2, -1, 0, 0, -204586},  {0, 1, -1, 0, -129620}, {1, 0, 0, 0, 108743},
    {0, 1, 1, 0, 104755},    {2, 0, 0, -2, 10321},    {0, 0, 1, -2, 79661},   {4, 0, -1, 0, -34782},
    {0, 0, 3, 0, -23210},    {4, 0, -2, 0, -21636},   {2, 1, -1, 0, 24208},   {2, 1, 0, 0, 30824},
    {1, 0, -1, 0, -8379},    {1, 1, 0, 0, -16675},    {2, -1, 1, 0, -12831},  {2, 0, 2, 0, -10445},
    {4, 0, 0, 0, -11650},    {2, 0, -3, 0, 14403},    {0, 1, -2, 0, -7003},   {2, -1, -2, 0, 10056},
    {1, 0, 1, 0, 6322},      {2, -2, 0, 0, -9884},
}};
// Table 47.B, latitude (1e-6 degree): the 28 largest of 60 terms.
constexpr std::array<LunarTerm, 28> kLunarLatitude = {{
    {0, 0, 0, 1, 5128122}, {0, 0, 1, 1, 280602}, {0, 0, 1, -1, 277693}, {2, 0, 0, -1, 173237},
    {2, 0, -1, 1, 55413},  {2, 0, -1, -1, 46271}, {2, 0, 0, 1, 32573},  {0, 0, 2, 1, 17198},
    {2, 0, 1, -1, 9266},   {0, 0, 2, -1, 8822},  {2, -1, 0, -1, 8216},  {2, 0, -2, -1, 4324},
    {2, 0, 1, 1, 4200},    {2, 1, 0, -1, -3359}, {2, -1, -1, 1, 2463},  {2, -1, 0, 1, 2211},
    {2, -1, -1, -1, 2065}, {0, 1, -1, -1, -1870}, {4, 0, -1, -1, 1828}, {0, 1, 0, 1, -1794},
    {0, 0, 0, 3, -1749},   {0, 1, -1, 1, -1565}, {1, 0, 0, 1, -1491},   {0, 1, 1, 1, -1475},
    {0, 1, 1, -1, -1410},  {0, 1, 0, -1, -1344}, {1, 0, 0, -1, -1335},  {0, 0, 3, 1, 1107},
}};

// Sum of a table's sine (or cosine) terms; terms in M are scaled by E^|m| (Meeus eq. 47.6).
template <size_t N>
double lunarSeries(const std::array<LunarTerm, N>& table, double d, double m, double mp, double f, double e,
                   bool useCosine)
{
    double sum = 0;
    for (const LunarTerm& term : table)
    {
        double arg = term.d * d + term.m * m + term.mp * mp + term.f * f;
        double scale = term.m == 0 ? 1.0 : (std::abs(term.m) == 1 ? e : e * e);
        sum += scale * term.coefficient * (useCosine ? cosd(arg) : sind(arg));
    }
    return sum;
}

// ENU direction, distance, azimuth and elevation of a body at geocentric equatorial `eq`.
CelestialPosition topocentric(const EquatorialPosition& eq, double siderealDeg, const glm::dvec3& observerEcef,
                              const glm::dmat3& ecefToEnu, const RefractionConditions& air)
{
    double sinDec, cosDec, sinLon, cosLon;
    Math::sincosd(eq.declinationDeg, sinDec, cosDec);
    // Earth-fixed longitude of the point below the body (polar motion, < 0.5", ignored).
    Math::sincosd(eq.rightAscensionDeg - siderealDeg, sinLon, cosLon);
    glm::dvec3 bodyEcef = eq.distanceM * glm::dvec3(cosDec * cosLon, cosDec * sinLon, sinDec);
    glm::dvec3 enu = ecefToEnu * (bodyEcef - observerEcef);
    CelestialPosition out;
    out.distanceM = glm::length(enu);
    out.directionEnu = enu / out.distanceM;
    out.azimuthDeg = normalizeDeg(Math::atan2d(out.directionEnu.x, out.directionEnu.y));
    out.elevationDeg = asind(std::clamp(out.directionEnu.z, -1.0, 1.0));
    out.apparentElevationDeg = out.elevationDeg + refractionDeg(out.elevationDeg, air);
    return out;
}

}  // namespace

double julianDayFromUnix(double unixTimeS)
{
    return kUnixEpochJd + unixTimeS / kSecondsPerDay;
}

double deltaTSeconds(double y)
{
    // Espenak & Meeus, "Five Millennium Canon of Solar Eclipses" (NASA/TP-2006-214141), polynomials.
    if (y < 1900.0 || y >= 2150.0)
    {
        double u = (y - 1820.0) / 100.0;
        return -20.0 + 32.0 * u * u;
    }
    if (y < 1920.0)
    {
        double t = y - 1900.0;
        return -2.79 + t * (1.494119 + t * (-0.0598939 + t * (0.0061966 - t * 0.000197)));
    }
    if (y < 1941.0)
    {
        double t = y - 1920.0;
        return 21.20 + t * (0.84493 + t * (-0.076100 + t * 0.0020936));
    }
    if (y < 1961.0)
    {
        double t = y - 1950.0;
        return 29.07 + 0.407 * t - t * t / 233.0 + t * t * t / 2547.0;
    }
    if (y < 1986.0)
    {
        double t = y - 1975.0;
        return 45.45 + 1.067 * t - t * t / 260.0 - t * t * t / 718.0;
    }
    if (y < 2005.0)
    {
        double t = y - 2000.0;
        return 63.86 + t * (0.3345 + t * (-0.060374 + t * (0.0017275 + t * (0.000651814 + t * 0.00002373599))));
    }
    if (y < 2050.0)
    {
        double t = y - 2000.0;
        return 62.92 + t * (0.32217 + t * 0.005589);
    }
    double u = (y - 1820.0) / 100.0;
    return -20.0 + 32.0 * u * u - 0.5628 * (2150.0 - y);
}

EquatorialPosition sunEquatorial(double jde)
{
    double t = (jde - kJ2000) / 36525.0;
    double meanLon = 280.46646 + t * (36000.76983 + t * 0.0003032);
    double meanAnomaly = 357.52911 + t * (35999.05029 - t * 0.0001537);
    double eccentricity = 0.016708634 - t * (0.000042037 + t * 0.0000001267);
    double centre = (1.914602 - t * (0.004817 + t * 0.000014)) * sind(meanAnomaly) +
                    (0.019993 - t * 0.000101) * sind(2 * meanAnomaly) + 0.000289 * sind(3 * meanAnomaly);
    double trueLon = meanLon + centre;
    double trueAnomaly = meanAnomaly + centre;
    double radiusAu = 1.000001018 * (1 - eccentricity * eccentricity) / (1 + eccentricity * cosd(trueAnomaly));
    Nutation n = nutation(t);
    // Apparent longitude: nutation plus annual aberration (-20.4898" / R, Meeus eq. 25.10).
    double apparentLon = trueLon + n.longitudeDeg - 20.4898 / 3600.0 / radiusAu;
    return eclipticToEquatorial(apparentLon, 0.0, meanObliquityDeg(t) + n.obliquityDeg, radiusAu * kAstronomicalUnitM);
}

EquatorialPosition moonEquatorial(double jde)
{
    double t = (jde - kJ2000) / 36525.0;
    // Fundamental arguments, Meeus eqs. 47.1-47.5, and the additive arguments A1-A3.
    double lp = 218.3164477 + t * (481267.88123421 + t * (-0.0015786 + t * (1.0 / 538841.0 - t / 65194000.0)));
    double d = 297.8501921 + t * (445267.1114034 + t * (-0.0018819 + t * (1.0 / 545868.0 - t / 113065000.0)));
    double m = 357.5291092 + t * (35999.0502909 + t * (-0.0001536 + t / 24490000.0));
    double mp = 134.9633964 + t * (477198.8675055 + t * (0.0087414 + t * (1.0 / 69699.0 - t / 14712000.0)));
    double f = 93.2720950 + t * (483202.0175233 + t * (-0.0036539 + t * (-1.0 / 3526000.0 + t / 863310000.0)));
    double a1 = 119.75 + 131.849 * t;
    double a2 = 53.09 + 479264.290 * t;
    double a3 = 313.45 + 481266.484 * t;
    double e = 1.0 - t * (0.002516 + t * 0.0000074);

    double sumL = lunarSeries(kLunarLongitude, d, m, mp, f, e, false) + 3958 * sind(a1) + 1962 * sind(lp - f) +
                  318 * sind(a2);
    double sumR = lunarSeries(kLunarDistance, d, m, mp, f, e, true);
    double sumB = lunarSeries(kLunarLatitude, d, m, mp, f, e, false) - 2235 * sind(lp) + 382 * sind(a3) +
                  175 * sind(a1 - f) + 175 * sind(a1 + f) + 127 * sind(lp - mp) - 115 * sind(lp + mp);
    Nutation n = nutation(t);
    double lonDeg = lp + sumL / 1e6 + n.longitudeDeg;
    double latDeg = sumB / 1e6;
    double distanceM = (385000.56 + sumR / 1000.0) * 1000.0;
    return eclipticToEquatorial(lonDeg, latDeg, meanObliquityDeg(t) + n.obliquityDeg, distanceM);
}

double refractionDeg(double elevationDeg, const RefractionConditions& air)
{
    // NREL SPA (Reda & Andreas 2008, eq. 42): no refraction once the sun's upper limb has set.
    if (elevationDeg < -0.8333)
        return 0.0;
    double arcmin = 1.02 / std::tan(Math::degree() * (elevationDeg + 10.3 / (elevationDeg + 5.11)));
    return arcmin / 60.0 * (air.pressureHPa / 1010.0) * (283.0 / (273.0 + air.temperatureC));
}

SunMoon computeSunMoon(int64_t unixTimeS, double latDeg, double lonDeg, double heightM,
                       const RefractionConditions& air)
{
    double jd = julianDayFromUnix(double(unixTimeS));
    double decimalYear = 2000.0 + (jd - kJ2000) / 365.25;
    double jde = jd + deltaTSeconds(decimalYear) / kSecondsPerDay;
    double tUt = (jd - kJ2000) / 36525.0;
    double sidereal = apparentSiderealTimeDeg(jd, tUt);

    const GeographicLib::Geocentric& earth = GeographicLib::Geocentric::WGS84();
    glm::dvec3 observer;
    std::vector<double> rotation(9);  // ENU -> ECEF, row-major: ecef_i = sum_j M[3 i + j] enu_j
    earth.Forward(latDeg, lonDeg, heightM, observer.x, observer.y, observer.z, rotation);
    glm::dmat3 ecefToEnu;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            ecefToEnu[i][j] = rotation[size_t(3 * i + j)];  // column i of the inverse = row i of M^T

    EquatorialPosition sunEq = sunEquatorial(jde);
    EquatorialPosition moonEq = moonEquatorial(jde);
    SunMoon out;
    out.sun = topocentric(sunEq, sidereal, observer, ecefToEnu, air);
    out.moon = topocentric(moonEq, sidereal, observer, ecefToEnu, air);

    // Phase angle from the geocentric elongation (Meeus eqs. 48.2-48.3).
    double sinDs, cosDs, sinDm, cosDm;
    Math::sincosd(sunEq.declinationDeg, sinDs, cosDs);
    Math::sincosd(moonEq.declinationDeg, sinDm, cosDm);
    double cosElong = sinDs * sinDm + cosDs * cosDm * cosd(sunEq.rightAscensionDeg - moonEq.rightAscensionDeg);
    double elongDeg = acosd(std::clamp(cosElong, -1.0, 1.0));
    out.moonPhaseAngleDeg = Math::atan2d(sunEq.distanceM * sind(elongDeg),
                                         moonEq.distanceM - sunEq.distanceM * cosd(elongDeg));
    out.moonIlluminatedFraction = 0.5 * (1.0 + cosd(out.moonPhaseAngleDeg));
    return out;
}

}  // namespace sky
