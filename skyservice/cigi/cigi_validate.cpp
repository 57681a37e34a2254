// SPDX-License-Identifier: MIT
#include "skyservice/cigi/cigi_validate.h"

#include <cmath>
#include <cstdio>

namespace sky::cigi
{
namespace
{

// Builds the first complaint and ignores later ones, so that a packet's checks read as one list.
class Checker
{
public:
    explicit Checker(const char* packet) : packet_(packet) {}

    void finite(const char* field, double v)
    {
        if (error_.empty() && !std::isfinite(v))
            fail(field, v, "is not a finite number");
    }
    void range(const char* field, double v, double lo, double hi)
    {
        if (error_.empty() && !(v >= lo && v <= hi))
        {
            char why[96];
            std::snprintf(why, sizeof why, "is outside %g..%g", lo, hi);
            fail(field, v, why);
        }
    }
    void atLeast(const char* field, double v, double lo)
    {
        if (error_.empty() && !(std::isfinite(v) && v >= lo))
        {
            char why[64];
            std::snprintf(why, sizeof why, "is not a finite number >= %g", lo);
            fail(field, v, why);
        }
    }
    void require(bool ok, const char* field, double v, const char* why)
    {
        if (error_.empty() && !ok)
            fail(field, v, why);
    }
    std::string result() const { return error_; }

private:
    void fail(const char* field, double v, const char* why)
    {
        char text[256];
        std::snprintf(text, sizeof text, "%s: %s %g %s", packet_, field, v, why);
        error_ = text;
    }
    const char* packet_;
    std::string error_;
};

bool leapYear(unsigned year)
{
    return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

unsigned daysInMonth(unsigned month, unsigned year)
{
    static const unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    return month == 2 && leapYear(year) ? 29 : kDays[month - 1];
}

} // namespace

std::string validate(const IgControl& p)
{
    Checker c("IG Control");
    // The minor version is not checked: 3.2 and 3.3 share this 24-byte layout (3.0/3.1 hosts send a 16-byte IG
    // Control, refused by its size), and a host that leaves the nibble at 0 still sends the 3.2+ packets.
    c.require(p.majorVersion == kCigiMajorVersion, "CIGI Version", p.majorVersion, "is not 3");
    return c.result();
}

std::string validate(const EntityControl& p)
{
    Checker c("Entity Control");
    c.require(p.entityState <= 2, "Entity State", p.entityState, "is not 0-2");
    c.range("Roll", p.rollDeg, -360, 360);
    c.range("Pitch", p.pitchDeg, -90, 90);
    c.range("Yaw", p.yawDeg, -360, 360);
    if (p.attached)
    {
        c.finite("X Offset", p.latDegOrXM);
        c.finite("Y Offset", p.lonDegOrYM);
        c.finite("Z Offset", p.altMslMOrZM);
    }
    else
    {
        c.range("Latitude", p.latDegOrXM, -90, 90);
        c.range("Longitude", p.lonDegOrYM, -360, 360);
        c.range("Altitude", p.altMslMOrZM, -1.0e5, 1.0e8);
    }
    return c.result();
}

std::string validate(const CelestialSphereControl& p)
{
    Checker c("Celestial Sphere Control");
    c.range("Star Field Intensity", p.starFieldIntensityPct, 0, 100);
    if (p.dateTimeValid)
    {
        const unsigned month = p.dateMMDDYYYY / 1000000u, day = p.dateMMDDYYYY / 10000u % 100u,
                       year = p.dateMMDDYYYY % 10000u;
        c.require(p.hour <= 23, "Hour", p.hour, "is not 0-23");
        c.require(p.minute <= 59, "Minute", p.minute, "is not 0-59");
        c.require(month >= 1 && month <= 12, "Date (MMDDYYYY)", p.dateMMDDYYYY, "has no month 1-12");
        c.require(month < 1 || month > 12 || (day >= 1 && day <= daysInMonth(month, year)), "Date (MMDDYYYY)",
                  p.dateMMDDYYYY, "has a day the month does not have");
    }
    return c.result();
}

std::string validate(const AtmosphereControl& p)
{
    Checker c("Atmosphere Control");
    c.require(p.humidityPct <= 100, "Global Humidity", p.humidityPct, "is over 100 %");
    c.range("Global Air Temperature", p.airTemperatureC, -273.15, 1000);
    c.atLeast("Global Visibility Range", p.visibilityM, 0);
    c.atLeast("Global Horizontal Wind Speed", p.horizontalWindMps, 0);
    c.finite("Global Vertical Wind Speed", p.verticalWindMps);
    c.range("Global Wind Direction", p.windDirectionDeg, -360, 360);
    c.atLeast("Global Barometric Pressure", p.pressureHpa, 0);
    return c.result();
}

std::string validate(const EnvironmentalRegionControl& p)
{
    Checker c("Environmental Region Control");
    c.require(p.regionState <= 2, "Region State", p.regionState, "is not 0-2");
    c.range("Latitude", p.latDeg, -90, 90);
    c.range("Longitude", p.lonDeg, -360, 360);
    c.atLeast("Size X", p.sizeXM, 0);
    c.atLeast("Size Y", p.sizeYM, 0);
    c.atLeast("Corner Radius", p.cornerRadiusM, 0);
    c.range("Rotation", p.rotationDeg, -360, 360);
    c.atLeast("Transition Perimeter", p.transitionPerimeterM, 0);
    return c.result();
}

std::string validate(const WeatherControl& p)
{
    Checker c("Weather Control");
    c.require(p.humidityPct <= 100, "Humidity", p.humidityPct, "is over 100 %");
    c.require(p.scope <= 2, "Scope", p.scope, "is not 0-2");
    c.require(p.severity <= 5, "Severity", p.severity, "is not 0-5");
    c.range("Air Temperature", p.airTemperatureC, -273.15, 1000);
    c.atLeast("Visibility Range", p.visibilityM, 0);
    c.range("Scud Frequency", p.scudFrequencyPct, 0, 100);
    c.range("Coverage", p.coveragePct, 0, 100);
    c.range("Base Elevation", p.baseElevationM, -1.0e5, 1.0e6);
    c.atLeast("Thickness", p.thicknessM, 0);
    c.atLeast("Transition Band", p.transitionBandM, 0);
    c.atLeast("Horizontal Wind Speed", p.horizontalWindMps, 0);
    c.finite("Vertical Wind Speed", p.verticalWindMps);
    c.range("Wind Direction", p.windDirectionDeg, -360, 360);
    c.atLeast("Barometric Pressure", p.pressureHpa, 0);
    c.atLeast("Aerosol Concentration", p.aerosolGPerM3, 0);
    return c.result();
}

std::string validate(const ViewControl& p)
{
    Checker c("View Control");
    c.finite("X Offset", p.xOffsetM);
    c.finite("Y Offset", p.yOffsetM);
    c.finite("Z Offset", p.zOffsetM);
    c.range("Roll", p.rollDeg, -360, 360);
    c.range("Pitch", p.pitchDeg, -90, 90);
    c.range("Yaw", p.yawDeg, -360, 360);
    return c.result();
}

std::string validate(const ViewDefinition& p)
{
    Checker c("View Definition");
    if (p.nearEnable)
        c.require(std::isfinite(p.nearM) && p.nearM > 0, "Near", p.nearM, "is not a finite number > 0");
    if (p.farEnable)
        c.require(std::isfinite(p.farM) && p.farM > 0, "Far", p.farM, "is not a finite number > 0");
    if (p.nearEnable && p.farEnable)
        c.require(p.farM > p.nearM, "Far", p.farM, "is not beyond Near");
    const auto halfAngle = [&c](bool enabled, const char* field, float deg) {
        if (enabled)
            c.require(std::isfinite(deg) && deg > -90 && deg < 90, field, deg, "is not within ±90 (exclusive)");
    };
    halfAngle(p.leftEnable, "Left", p.leftDeg);
    halfAngle(p.rightEnable, "Right", p.rightDeg);
    halfAngle(p.topEnable, "Top", p.topDeg);
    halfAngle(p.bottomEnable, "Bottom", p.bottomDeg);
    if (p.leftEnable && p.rightEnable)
        c.require(p.leftDeg < p.rightDeg, "Left", p.leftDeg, "is not left of Right");
    if (p.topEnable && p.bottomEnable)
        c.require(p.bottomDeg < p.topDeg, "Bottom", p.bottomDeg, "is not below Top");
    return c.result();
}

std::string validate(const EnvironmentalConditionsRequest& p)
{
    Checker c("Environmental Conditions Request");
    c.range("Latitude", p.latDeg, -90, 90);
    c.range("Longitude", p.lonDeg, -360, 360);
    c.range("Altitude", p.altMslM, -1.0e5, 1.0e8);
    return c.result();
}

} // namespace sky::cigi
