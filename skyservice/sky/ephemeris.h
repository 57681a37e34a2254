// SPDX-License-Identifier: MIT
// Where the sun and the moon are, seen from a point on the WGS84 ellipsoid at a UTC time.
//
// Sun: Meeus, "Astronomical Algorithms" (2nd ed. 1998) ch. 25 low-accuracy theory (about 0.01 degree),
// with nutation in longitude (ch. 22) and apparent sidereal time (ch. 12). Moon: Meeus ch. 47 with the
// larger terms of tables 47.A/47.B (about 0.02 degree geocentric), illuminated fraction from ch. 48.
// Both are turned into earth-fixed vectors and made topocentric by subtracting the observer's ECEF
// position (GeographicLib), which applies the parallax exactly (0.95 degree for the moon).
// Accuracy: checked against the NREL SPA paper example (0.01 degree), Meeus' worked examples and two
// total solar eclipses (tests/unit/test_ephemeris.cpp); valid for years 1900-2100.
#pragma once

#include "weather_ingest/civil_time.h"  // the times it takes: Unix seconds, ISO 8601

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace sky
{

/// A body's direction and distance from the observer.
struct CelestialPosition
{
    double azimuthDeg = 0;           ///< clockwise from true north (degrees, [0, 360))
    double elevationDeg = 0;         ///< geometric (airless) elevation above the local horizontal (degrees)
    double apparentElevationDeg = 0; ///< elevationDeg plus atmospheric refraction (degrees); see RefractionConditions
    glm::dvec3 directionEnu{0.0, 0.0, 1.0};  ///< unit vector (east, north, up) of the geometric direction
    double distanceM = 0;            ///< topocentric distance (meters)
};

/// The sun and the moon at one time and place.
struct SunMoon
{
    CelestialPosition sun;
    CelestialPosition moon;
    double moonIlluminatedFraction = 0;  ///< lit fraction of the moon's disk, [0, 1] (0 new, 1 full)
    double moonPhaseAngleDeg = 0;        ///< sun-moon-earth angle (degrees, [0, 180]; 0 full, 180 new)
};

/// Air at the observer, for the refraction correction (Meeus eq. 16.4, Saemundsson's formula).
struct RefractionConditions
{
    double pressureHPa = 1010;  ///< surface pressure (hPa)
    double temperatureC = 10;   ///< surface temperature (degrees Celsius)
};

/**
 * Sun and moon positions seen from an observer.
 *
 * @param[in] unixTimeS UTC time (seconds since 1970-01-01T00:00:00Z, leap seconds not counted).
 * @param[in] latDeg geodetic latitude (degrees, [-90, 90]).
 * @param[in] lonDeg longitude (degrees, east positive).
 * @param[in] heightM height above the WGS84 ellipsoid (meters).
 * @param[in] air conditions for apparentElevationDeg only; the geometric values do not depend on them.
 * @return both bodies. Refraction is applied as in NREL's SPA: only while the geometric elevation is
 *   above -0.8333 degrees (a body below that is set whatever the refraction).
 **********************************************************************/
SunMoon computeSunMoon(int64_t unixTimeS, double latDeg, double lonDeg, double heightM,
                       const RefractionConditions& air = RefractionConditions());

/// Geocentric apparent equatorial coordinates of date.
struct EquatorialPosition
{
    double rightAscensionDeg = 0;  ///< [0, 360)
    double declinationDeg = 0;
    double distanceM = 0;          ///< from the earth's centre (meters)
};

/**
 * Geocentric apparent position of the sun (Meeus ch. 25, low accuracy, with nutation).
 *
 * @param[in] julianEphemerisDay Julian day in Terrestrial Time.
 **********************************************************************/
EquatorialPosition sunEquatorial(double julianEphemerisDay);

/**
 * Geocentric apparent position of the moon (Meeus ch. 47, truncated series, with nutation).
 *
 * @param[in] julianEphemerisDay Julian day in Terrestrial Time.
 **********************************************************************/
EquatorialPosition moonEquatorial(double julianEphemerisDay);

/// Julian day (UT) of a Unix time.
double julianDayFromUnix(double unixTimeS);

/// TT - UT (seconds) for a decimal year: Espenak & Meeus (NASA, 2006) polynomials for 1900-2150.
double deltaTSeconds(double decimalYear);

/**
 * Refraction to add to a geometric elevation (Meeus eq. 16.4, scaled for pressure and temperature).
 *
 * @param[in] elevationDeg geometric elevation (degrees).
 * @param[in] air pressure and temperature.
 * @return the correction (degrees, >= 0), 0 below -0.8333 degrees.
 **********************************************************************/
double refractionDeg(double elevationDeg, const RefractionConditions& air);


}  // namespace sky
