// SPDX-License-Identifier: MIT
#include "skyservice/cigi/cigi_validate.h"

#include "skyservice/cigi/cigi_fields.h"
#include "weather_ingest/civil_time.h"

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
    // The same checks of the field held in `Member`, named as its packet's field table names it.
    template <auto Member, typename Packet> void finite(const Packet& p) { finite(fieldName<Member>(), p.*Member); }
    template <auto Member, typename Packet> void range(const Packet& p, double lo, double hi)
    {
        range(fieldName<Member>(), p.*Member, lo, hi);
    }
    template <auto Member, typename Packet> void atLeast(const Packet& p, double lo)
    {
        atLeast(fieldName<Member>(), p.*Member, lo);
    }
    template <auto Member, typename Packet> void require(const Packet& p, bool ok, const char* why)
    {
        require(ok, fieldName<Member>(), p.*Member, why);
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

} // namespace

std::string validate(const IgControl& p)
{
    Checker c("IG Control");
    // The minor version is not checked: 3.2 and 3.3 share this 24-byte layout (3.0/3.1 hosts send a 16-byte IG
    // Control, refused by its size), and a host that leaves the nibble at 0 still sends the 3.2+ packets.
    c.require<&IgControl::majorVersion>(p, p.majorVersion == kCigiMajorVersion, "is not 3");
    return c.result();
}

std::string validate(const EntityControl& p)
{
    Checker c("Entity Control");
    c.require<&EntityControl::entityState>(p, p.entityState <= 2, "is not 0-2");
    c.range<&EntityControl::rollDeg>(p, -360, 360);
    c.range<&EntityControl::pitchDeg>(p, -90, 90);
    c.range<&EntityControl::yawDeg>(p, -360, 360);
    if (p.attached)
    {
        // The field table names these three by their detached meaning; attached, the ICD calls them offsets.
        c.finite("X Offset", p.latDegOrXM);
        c.finite("Y Offset", p.lonDegOrYM);
        c.finite("Z Offset", p.altMslMOrZM);
    }
    else
    {
        c.range<&EntityControl::latDegOrXM>(p, -90, 90);
        c.range<&EntityControl::lonDegOrYM>(p, -360, 360);
        c.range<&EntityControl::altMslMOrZM>(p, -1.0e5, 1.0e8);
    }
    return c.result();
}

std::string validate(const CelestialSphereControl& p)
{
    Checker c("Celestial Sphere Control");
    c.range<&CelestialSphereControl::starFieldIntensityPct>(p, 0, 100);
    if (p.dateTimeValid)
    {
        const unsigned month = p.dateMMDDYYYY / 1000000u, day = p.dateMMDDYYYY / 10000u % 100u,
                       year = p.dateMMDDYYYY % 10000u;
        c.require<&CelestialSphereControl::hour>(p, p.hour <= 23, "is not 0-23");
        c.require<&CelestialSphereControl::minute>(p, p.minute <= 59, "is not 0-59");
        c.require<&CelestialSphereControl::dateMMDDYYYY>(p, month >= 1 && month <= 12, "has no month 1-12");
        c.require<&CelestialSphereControl::dateMMDDYYYY>(
            p, month < 1 || month > 12 || (day >= 1 && day <= daysInMonth(int(year), month)),
            "has a day the month does not have");
    }
    return c.result();
}

std::string validate(const AtmosphereControl& p)
{
    Checker c("Atmosphere Control");
    c.require<&AtmosphereControl::humidityPct>(p, p.humidityPct <= 100, "is over 100 %");
    c.range<&AtmosphereControl::airTemperatureC>(p, -273.15, 1000);
    c.atLeast<&AtmosphereControl::visibilityM>(p, 0);
    c.atLeast<&AtmosphereControl::horizontalWindMps>(p, 0);
    c.finite<&AtmosphereControl::verticalWindMps>(p);
    c.range<&AtmosphereControl::windDirectionDeg>(p, -360, 360);
    c.atLeast<&AtmosphereControl::pressureHpa>(p, 0);
    return c.result();
}

std::string validate(const EnvironmentalRegionControl& p)
{
    Checker c("Environmental Region Control");
    c.require<&EnvironmentalRegionControl::regionState>(p, p.regionState <= 2, "is not 0-2");
    c.range<&EnvironmentalRegionControl::latDeg>(p, -90, 90);
    c.range<&EnvironmentalRegionControl::lonDeg>(p, -360, 360);
    c.atLeast<&EnvironmentalRegionControl::sizeXM>(p, 0);
    c.atLeast<&EnvironmentalRegionControl::sizeYM>(p, 0);
    c.atLeast<&EnvironmentalRegionControl::cornerRadiusM>(p, 0);
    c.range<&EnvironmentalRegionControl::rotationDeg>(p, -360, 360);
    c.atLeast<&EnvironmentalRegionControl::transitionPerimeterM>(p, 0);
    return c.result();
}

std::string validate(const WeatherControl& p)
{
    Checker c("Weather Control");
    c.require<&WeatherControl::humidityPct>(p, p.humidityPct <= 100, "is over 100 %");
    c.require<&WeatherControl::scope>(p, p.scope <= 2, "is not 0-2");
    c.require<&WeatherControl::severity>(p, p.severity <= 5, "is not 0-5");
    c.range<&WeatherControl::airTemperatureC>(p, -273.15, 1000);
    c.atLeast<&WeatherControl::visibilityM>(p, 0);
    c.range<&WeatherControl::scudFrequencyPct>(p, 0, 100);
    c.range<&WeatherControl::coveragePct>(p, 0, 100);
    c.range<&WeatherControl::baseElevationM>(p, -1.0e5, 1.0e6);
    c.atLeast<&WeatherControl::thicknessM>(p, 0);
    c.atLeast<&WeatherControl::transitionBandM>(p, 0);
    c.atLeast<&WeatherControl::horizontalWindMps>(p, 0);
    c.finite<&WeatherControl::verticalWindMps>(p);
    c.range<&WeatherControl::windDirectionDeg>(p, -360, 360);
    c.atLeast<&WeatherControl::pressureHpa>(p, 0);
    c.atLeast<&WeatherControl::aerosolGPerM3>(p, 0);
    return c.result();
}

std::string validate(const ViewControl& p)
{
    Checker c("View Control");
    c.finite<&ViewControl::xOffsetM>(p);
    c.finite<&ViewControl::yOffsetM>(p);
    c.finite<&ViewControl::zOffsetM>(p);
    c.range<&ViewControl::rollDeg>(p, -360, 360);
    c.range<&ViewControl::pitchDeg>(p, -90, 90);
    c.range<&ViewControl::yawDeg>(p, -360, 360);
    return c.result();
}

std::string validate(const ViewDefinition& p)
{
    Checker c("View Definition");
    if (p.nearEnable)
        c.require<&ViewDefinition::nearM>(p, std::isfinite(p.nearM) && p.nearM > 0, "is not a finite number > 0");
    if (p.farEnable)
        c.require<&ViewDefinition::farM>(p, std::isfinite(p.farM) && p.farM > 0, "is not a finite number > 0");
    if (p.nearEnable && p.farEnable)
        c.require<&ViewDefinition::farM>(p, p.farM > p.nearM, "is not beyond Near");
    const auto halfAngle = [&c](bool enabled, const char* field, float deg) {
        if (enabled)
            c.require(std::isfinite(deg) && deg > -90 && deg < 90, field, deg, "is not within ±90 (exclusive)");
    };
    halfAngle(p.leftEnable, fieldName<&ViewDefinition::leftDeg>(), p.leftDeg);
    halfAngle(p.rightEnable, fieldName<&ViewDefinition::rightDeg>(), p.rightDeg);
    halfAngle(p.topEnable, fieldName<&ViewDefinition::topDeg>(), p.topDeg);
    halfAngle(p.bottomEnable, fieldName<&ViewDefinition::bottomDeg>(), p.bottomDeg);
    if (p.leftEnable && p.rightEnable)
        c.require<&ViewDefinition::leftDeg>(p, p.leftDeg < p.rightDeg, "is not left of Right");
    if (p.topEnable && p.bottomEnable)
        c.require<&ViewDefinition::bottomDeg>(p, p.bottomDeg < p.topDeg, "is not below Top");
    return c.result();
}

std::string validate(const EnvironmentalConditionsRequest& p)
{
    Checker c("Environmental Conditions Request");
    c.range<&EnvironmentalConditionsRequest::latDeg>(p, -90, 90);
    c.range<&EnvironmentalConditionsRequest::lonDeg>(p, -360, 360);
    c.range<&EnvironmentalConditionsRequest::altMslM>(p, -1.0e5, 1.0e8);
    return c.result();
}

} // namespace sky::cigi
