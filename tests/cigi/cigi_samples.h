// SPDX-License-Identifier: MIT
// Packets with every field set to a distinct, non-default value (flags alternating), so that a field
// written to the wrong offset or bit, or not at all, changes what comes back.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <vector>

namespace sky::cigi::test
{

inline IgControl sampleIgControl()
{
    IgControl p;
    p.databaseNumber = -5;
    p.igMode = 2;
    p.timestampValid = true;
    p.extrapolationEnable = true;
    p.hostFrameNumber = 0x01020304;
    p.timestamp10us = 0xA0B0C0D0;
    p.lastIgFrameNumber = 77777;
    return p;
}

inline EntityControl sampleEntityControl()
{
    EntityControl p;
    p.entityId = 0x1234;
    p.entityState = 1;
    p.attached = false;
    p.collisionDetection = true;
    p.inheritAlpha = true;
    p.groundOceanClamp = 2;
    p.animationBackward = true;
    p.animationContinuous = false;
    p.animationState = 3;
    p.extrapolationEnable = true;
    p.alpha = 200;
    p.entityType = 0xBEEF;
    p.parentId = 0x0F0E;
    p.rollDeg = -12.5f;
    p.pitchDeg = 7.25f;
    p.yawDeg = 271.125f;
    p.latDegOrXM = 64.123456789;
    p.lonDegOrYM = -21.987654321;
    p.altMslMOrZM = 3048.5;
    return p;
}

inline CelestialSphereControl sampleCelestialSphereControl()
{
    CelestialSphereControl p;
    p.hour = 17;
    p.minute = 42;
    p.ephemerisEnable = true;
    p.sunEnable = false;
    p.moonEnable = true;
    p.starFieldEnable = false;
    p.dateTimeValid = true;
    p.dateMMDDYYYY = 6212026;
    p.starFieldIntensityPct = 55.5f;
    return p;
}

inline AtmosphereControl sampleAtmosphereControl()
{
    AtmosphereControl p;
    p.atmosphericModelEnable = true;
    p.humidityPct = 63;
    p.airTemperatureC = -4.5f;
    p.visibilityM = 23456.0f;
    p.horizontalWindMps = 12.25f;
    p.verticalWindMps = -0.75f;
    p.windDirectionDeg = 245.5f;
    p.pressureHpa = 1002.75f;
    return p;
}

inline EnvironmentalRegionControl sampleEnvironmentalRegionControl()
{
    EnvironmentalRegionControl p;
    p.regionId = 0x0203;
    p.regionState = 1;
    p.mergeWeather = true;
    p.mergeAerosol = false;
    p.mergeMaritime = true;
    p.mergeTerrestrial = false;
    p.latDeg = -33.8765;
    p.lonDeg = 151.2093;
    p.sizeXM = 20000.0f;
    p.sizeYM = 12000.0f;
    p.cornerRadiusM = 1500.0f;
    p.rotationDeg = 35.5f;
    p.transitionPerimeterM = 2500.0f;
    return p;
}

inline WeatherControl sampleWeatherControl()
{
    WeatherControl p;
    p.entityOrRegionId = 0x0203;
    p.layerId = 2;
    p.humidityPct = 88;
    p.weatherEnable = true;
    p.scudEnable = false;
    p.randomWindsEnable = true;
    p.randomLightningEnable = false;
    p.cloudType = 9;
    p.scope = 1;
    p.severity = 4;
    p.airTemperatureC = 2.5f;
    p.visibilityM = 150.0f;
    p.scudFrequencyPct = 33.0f;
    p.coveragePct = 62.5f;
    p.baseElevationM = 1234.5f;
    p.thicknessM = 678.25f;
    p.transitionBandM = 111.0f;
    p.horizontalWindMps = 15.5f;
    p.verticalWindMps = 1.25f;
    p.windDirectionDeg = 310.0f;
    p.pressureHpa = 870.5f;
    p.aerosolGPerM3 = 0.375f;
    return p;
}

inline ViewControl sampleViewControl()
{
    ViewControl p;
    p.viewId = 0x0102;
    p.groupId = 0;
    p.xOffsetEnable = true;
    p.yOffsetEnable = false;
    p.zOffsetEnable = true;
    p.rollEnable = false;
    p.pitchEnable = true;
    p.yawEnable = true;
    p.entityId = 0x0A0B;
    p.xOffsetM = 1.5f;
    p.yOffsetM = -0.25f;
    p.zOffsetM = -1.125f;
    p.rollDeg = 3.0f;
    p.pitchDeg = -5.5f;
    p.yawDeg = 45.0f;
    return p;
}

inline ViewDefinition sampleViewDefinition()
{
    ViewDefinition p;
    p.viewId = 0x0304;
    p.groupId = 6;
    p.nearEnable = true;
    p.farEnable = false;
    p.leftEnable = true;
    p.rightEnable = true;
    p.topEnable = false;
    p.bottomEnable = true;
    p.mirrorMode = 2;
    p.pixelReplication = 5;
    p.orthographic = true;
    p.reorder = false;
    p.viewType = 6;
    p.nearM = 0.5f;
    p.farM = 80000.0f;
    p.leftDeg = -40.0f;
    p.rightDeg = 10.5f;
    p.topDeg = 22.5f;
    p.bottomDeg = -17.75f;
    return p;
}

inline EnvironmentalConditionsRequest sampleEnvironmentalConditionsRequest()
{
    EnvironmentalConditionsRequest p;
    p.requestType = kRequestWeather | kRequestAerosol;
    p.requestId = 201;
    p.latDeg = 47.4647;
    p.lonDeg = 8.5492;
    p.altMslM = 1300.25;
    return p;
}

inline StartOfFrame sampleStartOfFrame()
{
    StartOfFrame p;
    p.databaseNumber = 12;
    p.igStatus = 3;
    p.igMode = 3;
    p.timestampValid = true;
    p.earthReferenceModelCustom = true;
    p.igFrameNumber = 0x11223344;
    p.timestamp10us = 987654321;
    p.lastHostFrameNumber = 0x55667788;
    return p;
}

inline WeatherConditionsResponse sampleWeatherConditionsResponse()
{
    WeatherConditionsResponse p;
    p.requestId = 201;
    p.humidityPct = 97;
    p.airTemperatureC = -1.5f;
    p.visibilityM = 180.5f;
    p.horizontalWindMps = 8.25f;
    p.verticalWindMps = -0.5f;
    p.windDirectionDeg = 275.0f;
    p.pressureHpa = 869.75f;
    return p;
}

inline AerosolConcentrationResponse sampleAerosolConcentrationResponse()
{
    AerosolConcentrationResponse p;
    p.requestId = 201;
    p.layerId = 1;
    p.aerosolGPerM3 = 0.4375f;
    return p;
}

} // namespace sky::cigi::test
