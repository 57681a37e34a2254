// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_conditions.h"

#include "skyservice/service/cigi_weather.h"
#include "skyservice/sky/atmosphere.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

constexpr double kContrastFactor = 3.0; // -ln(0.05): 5 % contrast left
constexpr double kWaterDensityGPerM3 = 1.0e6;
constexpr double kDropletEffectiveRadiusM = 10.0e-6;
constexpr double kGravity = 9.80665, kGasConstantAir = 287.053, kLapseKPerM = 0.0065;

/// The drawn cloud layer (index into CigiCloudsAt) that contains the altitude, the densest if several; -1 none.
int layerContaining(const CigiCloudsAt& clouds, double altitudeM)
{
    int found = -1;
    for (int i = 0; i < 3; ++i)
    {
        const CigiCloudAt& c = clouds[size_t(i)];
        if (c.coverage > 0 && altitudeM >= double(c.baseMslM) && altitudeM <= double(c.topMslM) &&
            (found < 0 || c.coverage > clouds[size_t(found)].coverage))
            found = i;
    }
    return found;
}

uint8_t percent(double v)
{
    return uint8_t(std::clamp(std::lround(v), 0L, 100L));
}

} // namespace

double clearAirVisibilityM(double altitudeM)
{
    return cigiAirVisibilityM(cigi::CigiState{}, altitudeM);
}

double cigiAirVisibilityM(const cigi::CigiState& state, double altitudeM)
{
    AtmosphereParams a = makeEarthAtmosphere(6371000.0);
    const cigi::AtmosphereState& air = state.atmosphere;
    if (air.set && air.visibilityM > 0) // as the frame draws it (CigiApplier::applyAir)
        setHazeVisibility(a, double(air.visibilityM));
    const double h = std::max(0.0, altitudeM);
    // Green channel (550 nm): what the eye's contrast threshold is defined for.
    double extinction = double(a.rayleighScattering.y) * std::exp(-h / double(a.rayleighScattering.w)) +
                        double(a.mieExtinction.y) * std::exp(-h / double(a.mieScattering.w));
    auto fog = state.globalLayers.find(0);
    if (fog != state.globalLayers.end() && fog->second.enabled && fog->second.thicknessM > 0 &&
        fog->second.visibilityM > 0 && altitudeM >= double(fog->second.baseElevationMslM) &&
        altitudeM <= double(fog->second.baseElevationMslM) + double(fog->second.thicknessM))
        extinction += kVisibilityOpticalDepth / double(fog->second.visibilityM);
    return kContrastFactor / extinction;
}

void standardAtmosphere(double altitudeM, double seaLevelC, double seaLevelHpa, double& temperatureC,
                        double& pressureHpa)
{
    const double h = std::clamp(altitudeM, 0.0, 32000.0);
    const double t0 = seaLevelC + 273.15;
    const double exponent = kGravity / (kLapseKPerM * kGasConstantAir);
    const double tropopauseM = 11000.0, stratopauseM = 20000.0;
    const double t11 = t0 - kLapseKPerM * tropopauseM;
    double t = 0, p = 0;
    if (h <= tropopauseM)
    {
        t = t0 - kLapseKPerM * h;
        p = seaLevelHpa * std::pow(t / t0, exponent);
    }
    else
    {
        const double p11 = seaLevelHpa * std::pow(t11 / t0, exponent);
        const double p20 = p11 * std::exp(-kGravity * (stratopauseM - tropopauseM) / (kGasConstantAir * t11));
        if (h <= stratopauseM)
        {
            t = t11;
            p = p11 * std::exp(-kGravity * (h - tropopauseM) / (kGasConstantAir * t11));
        }
        else
        {
            const double lapse = -0.001; // +1 K/km in the lower stratosphere
            t = t11 - lapse * (h - stratopauseM);
            p = p20 * std::pow(t / t11, kGravity / (lapse * kGasConstantAir));
        }
    }
    temperatureC = t - 273.15;
    pressureHpa = p;
}

cigi::WeatherConditionsResponse cigiWeatherConditions(const cigi::CigiState& state,
                                                      const cigi::EnvironmentalConditionsRequest& request,
                                                      double extinctionPerM)
{
    const cigi::AtmosphereState& air = state.atmosphere;
    cigi::WeatherConditionsResponse r;
    r.requestId = request.requestId;
    const CigiCloudsAt clouds = cigiCloudsAt(state, request.latDeg, request.lonDeg);
    const int inside = layerContaining(clouds, request.altMslM);
    double temperatureC = 15, pressureHpa = 1013.25;
    standardAtmosphere(request.altMslM, air.set ? double(air.airTemperatureC) : 15.0,
                       air.set && air.pressureHpa > 0 ? double(air.pressureHpa) : 1013.25, temperatureC, pressureHpa);
    r.airTemperatureC = float(temperatureC);
    r.pressureHpa = float(pressureHpa);
    if (inside >= 0)
    {
        const CigiCloudAt& c = clouds[size_t(inside)];
        r.visibilityM = float(kContrastFactor / (extinctionPerM * double(c.coverage)));
        r.humidityPct = 100;
        r.horizontalWindMps = std::hypot(c.windEastMps, c.windNorthMps);
        r.verticalWindMps = c.verticalWindMps;
        // Back from components: the direction the wind blows from.
        r.windDirectionDeg =
            r.horizontalWindMps > 0
                ? float(std::fmod(std::atan2(-double(c.windEastMps), -double(c.windNorthMps)) * 180.0 / M_PI + 360.0,
                                  360.0))
                : 0.0f;
        return r;
    }
    r.visibilityM = float(cigiAirVisibilityM(state, request.altMslM));
    r.humidityPct = air.set ? percent(air.humidityPct) : 0;
    if (air.set)
    {
        r.horizontalWindMps = air.horizontalWindMps;
        r.verticalWindMps = air.verticalWindMps;
        r.windDirectionDeg = air.windDirectionDeg;
    }
    return r;
}

std::vector<cigi::AerosolConcentrationResponse>
cigiAerosolConcentrations(const cigi::CigiState& state, const cigi::EnvironmentalConditionsRequest& request,
                          double extinctionPerM)
{
    std::vector<cigi::AerosolConcentrationResponse> out;
    const CigiCloudsAt clouds = cigiCloudsAt(state, request.latDeg, request.lonDeg);
    for (const CigiCloudAt& c : clouds)
    {
        if (!c.set)
            continue;
        cigi::AerosolConcentrationResponse a;
        a.requestId = request.requestId;
        a.layerId = c.layerId;
        const bool inside =
            c.coverage > 0 && request.altMslM >= double(c.baseMslM) && request.altMslM <= double(c.topMslM);
        if (inside)
            a.aerosolGPerM3 = c.aerosolGPerM3 > 0 ? c.aerosolGPerM3
                                                  : float(2.0 / 3.0 * kWaterDensityGPerM3 * kDropletEffectiveRadiusM *
                                                          extinctionPerM * double(c.coverage));
        out.push_back(a);
    }
    return out;
}

} // namespace sky
