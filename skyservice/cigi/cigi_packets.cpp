// SPDX-License-Identifier: MIT
// Field offsets: see cigi_packets.h (ICD 3.3 tables, as Wireshark's dissector and CCL lay them out).
#include "skyservice/cigi/cigi_packets.h"

namespace sky::cigi
{
namespace
{

WireWriter begin(std::vector<uint8_t>& out, uint8_t opcode, uint8_t size, ByteOrder order)
{
    WireWriter w(out, size, order);
    w.u8(0, opcode);
    w.u8(1, size);
    return w;
}

} // namespace

IgControl decodeIgControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    IgControl p;
    p.majorVersion = r.u8(2);
    p.databaseNumber = r.i8(3);
    p.igMode = r.bits(4, 0, 2);
    p.timestampValid = r.flag(4, 2);
    p.extrapolationEnable = r.flag(4, 3);
    p.minorVersion = r.bits(4, 4, 4);
    p.hostFrameNumber = r.u32(8);
    p.timestamp10us = r.u32(12);
    p.lastIgFrameNumber = r.u32(16);
    return p;
}

void encode(const IgControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpIgControl, kSizeIgControl, order);
    w.u8(2, p.majorVersion);
    w.i8(3, p.databaseNumber);
    w.bits(4, 0, 2, p.igMode);
    w.flag(4, 2, p.timestampValid);
    w.flag(4, 3, p.extrapolationEnable);
    w.bits(4, 4, 4, p.minorVersion);
    w.u16(6, kByteSwapMagic);
    w.u32(8, p.hostFrameNumber);
    w.u32(12, p.timestamp10us);
    w.u32(16, p.lastIgFrameNumber);
}

EntityControl decodeEntityControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    EntityControl p;
    p.entityId = r.u16(2);
    p.entityState = r.bits(4, 0, 2);
    p.attached = r.flag(4, 2);
    p.collisionDetection = r.flag(4, 3);
    p.inheritAlpha = r.flag(4, 4);
    p.groundOceanClamp = r.bits(4, 5, 2);
    p.animationBackward = r.flag(5, 0);
    p.animationContinuous = r.flag(5, 1);
    p.animationState = r.bits(5, 2, 2);
    p.extrapolationEnable = r.flag(5, 4);
    p.alpha = r.u8(6);
    p.entityType = r.u16(8);
    p.parentId = r.u16(10);
    p.rollDeg = r.f32(12);
    p.pitchDeg = r.f32(16);
    p.yawDeg = r.f32(20);
    p.latDegOrXM = r.f64(24);
    p.lonDegOrYM = r.f64(32);
    p.altMslMOrZM = r.f64(40);
    return p;
}

void encode(const EntityControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpEntityControl, kSizeEntityControl, order);
    w.u16(2, p.entityId);
    w.bits(4, 0, 2, p.entityState);
    w.flag(4, 2, p.attached);
    w.flag(4, 3, p.collisionDetection);
    w.flag(4, 4, p.inheritAlpha);
    w.bits(4, 5, 2, p.groundOceanClamp);
    w.flag(5, 0, p.animationBackward);
    w.flag(5, 1, p.animationContinuous);
    w.bits(5, 2, 2, p.animationState);
    w.flag(5, 4, p.extrapolationEnable);
    w.u8(6, p.alpha);
    w.u16(8, p.entityType);
    w.u16(10, p.parentId);
    w.f32(12, p.rollDeg);
    w.f32(16, p.pitchDeg);
    w.f32(20, p.yawDeg);
    w.f64(24, p.latDegOrXM);
    w.f64(32, p.lonDegOrYM);
    w.f64(40, p.altMslMOrZM);
}

CelestialSphereControl decodeCelestialSphereControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    CelestialSphereControl p;
    p.hour = r.u8(2);
    p.minute = r.u8(3);
    p.ephemerisEnable = r.flag(4, 0);
    p.sunEnable = r.flag(4, 1);
    p.moonEnable = r.flag(4, 2);
    p.starFieldEnable = r.flag(4, 3);
    p.dateTimeValid = r.flag(4, 4);
    p.dateMMDDYYYY = r.u32(8);
    p.starFieldIntensityPct = r.f32(12);
    return p;
}

void encode(const CelestialSphereControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpCelestialSphereControl, kSizeCelestialSphereControl, order);
    w.u8(2, p.hour);
    w.u8(3, p.minute);
    w.flag(4, 0, p.ephemerisEnable);
    w.flag(4, 1, p.sunEnable);
    w.flag(4, 2, p.moonEnable);
    w.flag(4, 3, p.starFieldEnable);
    w.flag(4, 4, p.dateTimeValid);
    w.u32(8, p.dateMMDDYYYY);
    w.f32(12, p.starFieldIntensityPct);
}

AtmosphereControl decodeAtmosphereControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    AtmosphereControl p;
    p.atmosphericModelEnable = r.flag(2, 0);
    p.humidityPct = r.u8(3);
    p.airTemperatureC = r.f32(4);
    p.visibilityM = r.f32(8);
    p.horizontalWindMps = r.f32(12);
    p.verticalWindMps = r.f32(16);
    p.windDirectionDeg = r.f32(20);
    p.pressureHpa = r.f32(24);
    return p;
}

void encode(const AtmosphereControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpAtmosphereControl, kSizeAtmosphereControl, order);
    w.flag(2, 0, p.atmosphericModelEnable);
    w.u8(3, p.humidityPct);
    w.f32(4, p.airTemperatureC);
    w.f32(8, p.visibilityM);
    w.f32(12, p.horizontalWindMps);
    w.f32(16, p.verticalWindMps);
    w.f32(20, p.windDirectionDeg);
    w.f32(24, p.pressureHpa);
}

EnvironmentalRegionControl decodeEnvironmentalRegionControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    EnvironmentalRegionControl p;
    p.regionId = r.u16(2);
    p.regionState = r.bits(4, 0, 2);
    p.mergeWeather = r.flag(4, 2);
    p.mergeAerosol = r.flag(4, 3);
    p.mergeMaritime = r.flag(4, 4);
    p.mergeTerrestrial = r.flag(4, 5);
    p.latDeg = r.f64(8);
    p.lonDeg = r.f64(16);
    p.sizeXM = r.f32(24);
    p.sizeYM = r.f32(28);
    p.cornerRadiusM = r.f32(32);
    p.rotationDeg = r.f32(36);
    p.transitionPerimeterM = r.f32(40);
    return p;
}

void encode(const EnvironmentalRegionControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpEnvironmentalRegionControl, kSizeEnvironmentalRegionControl, order);
    w.u16(2, p.regionId);
    w.bits(4, 0, 2, p.regionState);
    w.flag(4, 2, p.mergeWeather);
    w.flag(4, 3, p.mergeAerosol);
    w.flag(4, 4, p.mergeMaritime);
    w.flag(4, 5, p.mergeTerrestrial);
    w.f64(8, p.latDeg);
    w.f64(16, p.lonDeg);
    w.f32(24, p.sizeXM);
    w.f32(28, p.sizeYM);
    w.f32(32, p.cornerRadiusM);
    w.f32(36, p.rotationDeg);
    w.f32(40, p.transitionPerimeterM);
}

WeatherControl decodeWeatherControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    WeatherControl p;
    p.entityOrRegionId = r.u16(2);
    p.layerId = r.u8(4);
    p.humidityPct = r.u8(5);
    p.weatherEnable = r.flag(6, 0);
    p.scudEnable = r.flag(6, 1);
    p.randomWindsEnable = r.flag(6, 2);
    p.randomLightningEnable = r.flag(6, 3);
    p.cloudType = r.bits(6, 4, 4);
    p.scope = r.bits(7, 0, 2);
    p.severity = r.bits(7, 2, 3);
    p.airTemperatureC = r.f32(8);
    p.visibilityM = r.f32(12);
    p.scudFrequencyPct = r.f32(16);
    p.coveragePct = r.f32(20);
    p.baseElevationM = r.f32(24);
    p.thicknessM = r.f32(28);
    p.transitionBandM = r.f32(32);
    p.horizontalWindMps = r.f32(36);
    p.verticalWindMps = r.f32(40);
    p.windDirectionDeg = r.f32(44);
    p.pressureHpa = r.f32(48);
    p.aerosolGPerM3 = r.f32(52);
    return p;
}

void encode(const WeatherControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpWeatherControl, kSizeWeatherControl, order);
    w.u16(2, p.entityOrRegionId);
    w.u8(4, p.layerId);
    w.u8(5, p.humidityPct);
    w.flag(6, 0, p.weatherEnable);
    w.flag(6, 1, p.scudEnable);
    w.flag(6, 2, p.randomWindsEnable);
    w.flag(6, 3, p.randomLightningEnable);
    w.bits(6, 4, 4, p.cloudType);
    w.bits(7, 0, 2, p.scope);
    w.bits(7, 2, 3, p.severity);
    w.f32(8, p.airTemperatureC);
    w.f32(12, p.visibilityM);
    w.f32(16, p.scudFrequencyPct);
    w.f32(20, p.coveragePct);
    w.f32(24, p.baseElevationM);
    w.f32(28, p.thicknessM);
    w.f32(32, p.transitionBandM);
    w.f32(36, p.horizontalWindMps);
    w.f32(40, p.verticalWindMps);
    w.f32(44, p.windDirectionDeg);
    w.f32(48, p.pressureHpa);
    w.f32(52, p.aerosolGPerM3);
}

ViewControl decodeViewControl(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    ViewControl p;
    p.viewId = r.u16(2);
    p.groupId = r.u8(4);
    p.xOffsetEnable = r.flag(5, 0);
    p.yOffsetEnable = r.flag(5, 1);
    p.zOffsetEnable = r.flag(5, 2);
    p.rollEnable = r.flag(5, 3);
    p.pitchEnable = r.flag(5, 4);
    p.yawEnable = r.flag(5, 5);
    p.entityId = r.u16(6);
    p.xOffsetM = r.f32(8);
    p.yOffsetM = r.f32(12);
    p.zOffsetM = r.f32(16);
    p.rollDeg = r.f32(20);
    p.pitchDeg = r.f32(24);
    p.yawDeg = r.f32(28);
    return p;
}

void encode(const ViewControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpViewControl, kSizeViewControl, order);
    w.u16(2, p.viewId);
    w.u8(4, p.groupId);
    w.flag(5, 0, p.xOffsetEnable);
    w.flag(5, 1, p.yOffsetEnable);
    w.flag(5, 2, p.zOffsetEnable);
    w.flag(5, 3, p.rollEnable);
    w.flag(5, 4, p.pitchEnable);
    w.flag(5, 5, p.yawEnable);
    w.u16(6, p.entityId);
    w.f32(8, p.xOffsetM);
    w.f32(12, p.yOffsetM);
    w.f32(16, p.zOffsetM);
    w.f32(20, p.rollDeg);
    w.f32(24, p.pitchDeg);
    w.f32(28, p.yawDeg);
}

ViewDefinition decodeViewDefinition(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    ViewDefinition p;
    p.viewId = r.u16(2);
    p.groupId = r.u8(4);
    p.nearEnable = r.flag(5, 0);
    p.farEnable = r.flag(5, 1);
    p.leftEnable = r.flag(5, 2);
    p.rightEnable = r.flag(5, 3);
    p.topEnable = r.flag(5, 4);
    p.bottomEnable = r.flag(5, 5);
    p.mirrorMode = r.bits(5, 6, 2);
    p.pixelReplication = r.bits(6, 0, 3);
    p.orthographic = r.flag(6, 3);
    p.reorder = r.flag(6, 4);
    p.viewType = r.bits(6, 5, 3);
    p.nearM = r.f32(8);
    p.farM = r.f32(12);
    p.leftDeg = r.f32(16);
    p.rightDeg = r.f32(20);
    p.topDeg = r.f32(24);
    p.bottomDeg = r.f32(28);
    return p;
}

void encode(const ViewDefinition& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpViewDefinition, kSizeViewDefinition, order);
    w.u16(2, p.viewId);
    w.u8(4, p.groupId);
    w.flag(5, 0, p.nearEnable);
    w.flag(5, 1, p.farEnable);
    w.flag(5, 2, p.leftEnable);
    w.flag(5, 3, p.rightEnable);
    w.flag(5, 4, p.topEnable);
    w.flag(5, 5, p.bottomEnable);
    w.bits(5, 6, 2, p.mirrorMode);
    w.bits(6, 0, 3, p.pixelReplication);
    w.flag(6, 3, p.orthographic);
    w.flag(6, 4, p.reorder);
    w.bits(6, 5, 3, p.viewType);
    w.f32(8, p.nearM);
    w.f32(12, p.farM);
    w.f32(16, p.leftDeg);
    w.f32(20, p.rightDeg);
    w.f32(24, p.topDeg);
    w.f32(28, p.bottomDeg);
}

EnvironmentalConditionsRequest decodeEnvironmentalConditionsRequest(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    EnvironmentalConditionsRequest p;
    p.requestType = r.bits(2, 0, 4);
    p.requestId = r.u8(3);
    p.latDeg = r.f64(8);
    p.lonDeg = r.f64(16);
    p.altMslM = r.f64(24);
    return p;
}

void encode(const EnvironmentalConditionsRequest& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpEnvironmentalConditionsRequest, kSizeEnvironmentalConditionsRequest, order);
    w.bits(2, 0, 4, p.requestType);
    w.u8(3, p.requestId);
    w.f64(8, p.latDeg);
    w.f64(16, p.lonDeg);
    w.f64(24, p.altMslM);
}

StartOfFrame decodeStartOfFrame(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    StartOfFrame p;
    p.majorVersion = r.u8(2);
    p.databaseNumber = r.i8(3);
    p.igStatus = r.u8(4);
    p.igMode = r.bits(5, 0, 2);
    p.timestampValid = r.flag(5, 2);
    p.earthReferenceModelCustom = r.flag(5, 3);
    p.minorVersion = r.bits(5, 4, 4);
    p.igFrameNumber = r.u32(8);
    p.timestamp10us = r.u32(12);
    p.lastHostFrameNumber = r.u32(16);
    return p;
}

void encode(const StartOfFrame& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpStartOfFrame, kSizeStartOfFrame, order);
    w.u8(2, p.majorVersion);
    w.i8(3, p.databaseNumber);
    w.u8(4, p.igStatus);
    w.bits(5, 0, 2, p.igMode);
    w.flag(5, 2, p.timestampValid);
    w.flag(5, 3, p.earthReferenceModelCustom);
    w.bits(5, 4, 4, p.minorVersion);
    w.u16(6, kByteSwapMagic);
    w.u32(8, p.igFrameNumber);
    w.u32(12, p.timestamp10us);
    w.u32(16, p.lastHostFrameNumber);
}

WeatherConditionsResponse decodeWeatherConditionsResponse(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    WeatherConditionsResponse p;
    p.requestId = r.u8(2);
    p.humidityPct = r.u8(3);
    p.airTemperatureC = r.f32(4);
    p.visibilityM = r.f32(8);
    p.horizontalWindMps = r.f32(12);
    p.verticalWindMps = r.f32(16);
    p.windDirectionDeg = r.f32(20);
    p.pressureHpa = r.f32(24);
    return p;
}

void encode(const WeatherConditionsResponse& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpWeatherConditionsResponse, kSizeWeatherConditionsResponse, order);
    w.u8(2, p.requestId);
    w.u8(3, p.humidityPct);
    w.f32(4, p.airTemperatureC);
    w.f32(8, p.visibilityM);
    w.f32(12, p.horizontalWindMps);
    w.f32(16, p.verticalWindMps);
    w.f32(20, p.windDirectionDeg);
    w.f32(24, p.pressureHpa);
}

AerosolConcentrationResponse decodeAerosolConcentrationResponse(const uint8_t* packet, ByteOrder order)
{
    const WireReader r(packet, order);
    AerosolConcentrationResponse p;
    p.requestId = r.u8(2);
    p.layerId = r.u8(3);
    p.aerosolGPerM3 = r.f32(4);
    return p;
}

void encode(const AerosolConcentrationResponse& p, ByteOrder order, std::vector<uint8_t>& out)
{
    WireWriter w = begin(out, kOpAerosolConcentrationResponse, kSizeAerosolConcentrationResponse, order);
    w.u8(2, p.requestId);
    w.u8(3, p.layerId);
    w.f32(4, p.aerosolGPerM3);
}

const char* opcodeName(uint8_t opcode)
{
    // ICD 3.3 section 4.1 (host -> IG, 1-35) and 4.2 (IG -> host, 101-117); 201-255 are user-defined.
    static const char* const kHostToIg[] = {
        "IG Control", "Entity Control", "Conformal Clamped Entity Control", "Component Control",
        "Short Component Control", "Articulated Part Control", "Short Articulated Part Control", "Rate Control",
        "Celestial Sphere Control", "Atmosphere Control", "Environmental Region Control", "Weather Control",
        "Maritime Surface Conditions Control", "Wave Control", "Terrestrial Surface Conditions Control",
        "View Control", "Sensor Control", "Motion Tracker Control", "Earth Reference Model Definition",
        "Trajectory Definition", "View Definition", "Collision Detection Segment Definition",
        "Collision Detection Volume Definition", "HAT/HOT Request", "Line of Sight Segment Request",
        "Line of Sight Vector Request", "Position Request", "Environmental Conditions Request",
        "Symbol Surface Definition", "Symbol Text Definition", "Symbol Circle Definition",
        "Symbol Line Definition", "Symbol Clone", "Symbol Control", "Short Symbol Control"};
    static const char* const kIgToHost[] = {
        "Start of Frame", "HAT/HOT Response", "HAT/HOT Extended Response", "Line of Sight Response",
        "Line of Sight Extended Response", "Sensor Response", "Sensor Extended Response", "Position Response",
        "Weather Conditions Response", "Aerosol Concentration Response", "Maritime Surface Conditions Response",
        "Terrestrial Surface Conditions Response", "Collision Detection Segment Notification",
        "Collision Detection Volume Notification", "Animation Stop Notification", "Event Notification",
        "Image Generator Message"};
    constexpr size_t kHostCount = sizeof(kHostToIg) / sizeof(kHostToIg[0]);
    constexpr size_t kIgCount = sizeof(kIgToHost) / sizeof(kIgToHost[0]);
    if (opcode >= 1 && opcode <= kHostCount)
        return kHostToIg[opcode - 1];
    if (opcode >= 101 && opcode < 101 + kIgCount)
        return kIgToHost[opcode - 101];
    if (opcode >= 201)
        return "User-Defined";
    return nullptr;
}

} // namespace sky::cigi
