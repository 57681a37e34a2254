// SPDX-License-Identifier: MIT
// CIGI 3.3 (SISO-STD-013, Common Image Generator Interface) packets this IG reads or writes: every field
// of each packet, in the ICD's units, decoded from and encoded to either byte order.
//
// Each packet's layout (offsets, sizes, bits) is its field table in cigi_fields.h. Where the layouts come from:
// the CIGI 3.3 ICD's packet tables as implemented by Wireshark's CIGI dissector
// (epan/dissectors/packet-cigi.c: cigi3_3_add_ig_control, cigi3_3_add_entity_control,
// cigi3_add_celestial_sphere_control, cigi3_add_atmosphere_control, cigi3_add_environmental_region_control,
// cigi3_add_weather_control, cigi3_add_view_control, cigi3_add_view_definition,
// cigi3_add_environmental_conditions_request, cigi3_2_add_start_of_frame,
// cigi3_add_weather_conditions_response, cigi3_add_aerosol_concentration_response, and the bit masks of
// their header fields), cross-checked with the CIGI Class Library's V3/V3_2/V3_3 Pack() functions (which
// put IG Control's and Start of Frame's Minor Version in bits 4-7 of byte 4 and 5 respectively). The
// tests decode what this file encodes with the tshark installed on the machine (tests/cigi/).
// Only the layouts were read there; the code is this project's own.
#pragma once

#include "shaders/shared/cloud_type.h"
#include "skyservice/cigi/cigi_wire.h"

#include <cstdint>
#include <vector>

namespace sky::cigi
{

/// Packet opcodes ("Packet ID", byte 0 of every packet).
enum Opcode : uint8_t
{
    kOpIgControl = 1,
    kOpEntityControl = 2,
    kOpCelestialSphereControl = 9,
    kOpAtmosphereControl = 10,
    kOpEnvironmentalRegionControl = 11,
    kOpWeatherControl = 12,
    kOpViewControl = 16,
    kOpViewDefinition = 21,
    kOpEnvironmentalConditionsRequest = 28,
    kOpStartOfFrame = 101,
    kOpWeatherConditionsResponse = 109,
    kOpAerosolConcentrationResponse = 110,
};

/// Fixed sizes ("Packet Size", byte 1) of the packets above, in bytes.
enum PacketSize : uint8_t
{
    kSizeIgControl = 24,
    kSizeEntityControl = 48,
    kSizeCelestialSphereControl = 16,
    kSizeAtmosphereControl = 32,
    kSizeEnvironmentalRegionControl = 48,
    kSizeWeatherControl = 56,
    kSizeViewControl = 32,
    kSizeViewDefinition = 32,
    kSizeEnvironmentalConditionsRequest = 32,
    kSizeStartOfFrame = 24,
    kSizeWeatherConditionsResponse = 32,
    kSizeAerosolConcentrationResponse = 8,
};

/// Written in the sender's byte order at bytes 6-7 of IG Control and Start of Frame.
constexpr uint16_t kByteSwapMagic = 0x8000;
constexpr uint8_t kCigiMajorVersion = 3;
constexpr uint8_t kCigiMinorVersion = 3;

/// Weather Control "Layer ID" values defined by the ICD; 10-255 are IG-defined.
enum WeatherLayerId : uint8_t
{
    kLayerGroundFog = 0,
    kLayerCloud1 = 1,
    kLayerCloud2 = 2,
    kLayerCloud3 = 3,
    kLayerRain = 4,
    kLayerSnow = 5,
    kLayerSleet = 6,
    kLayerHail = 7,
    kLayerSand = 8,
    kLayerDust = 9,
};

/// Weather Control "Cloud Type" (4 bits): the project's one list of genera (11-15 are "Other", IG-defined).
using sky::CloudType;

/// Weather Control "Scope" (2 bits; 3 is not defined).
enum class WeatherScope : uint8_t
{
    Global = 0,
    Regional = 1,
    Entity = 2,
};

/// Environmental Region Control "Region State" (2 bits; 3 is not defined).
enum class RegionState : uint8_t
{
    Inactive = 0,
    Active = 1,
    Destroyed = 2,
};

/// Environmental Conditions Request "Request Type" bits (4 bits, any combination).
enum EnvironmentalRequestBits : uint8_t
{
    kRequestMaritime = 0x1,
    kRequestTerrestrial = 0x2,
    kRequestWeather = 0x4,
    kRequestAerosol = 0x8,
};

// ---- host -> IG -----------------------------------------------------------------------------------------

/// IG Control (opcode 1, 24 bytes): the first packet of every host datagram.
struct IgControl
{
    uint8_t majorVersion = kCigiMajorVersion;
    int8_t databaseNumber = 0;                 ///< 0 = no change, negative = "not available"
    uint8_t igMode = 1;                        ///< 0 Reset/Standby, 1 Operate, 2 Debug
    bool timestampValid = false;
    bool extrapolationEnable = false;          ///< host allows dead reckoning
    uint8_t minorVersion = kCigiMinorVersion;
    uint32_t hostFrameNumber = 0;
    uint32_t timestamp10us = 0;                ///< host time, 10 µs ticks
    uint32_t lastIgFrameNumber = 0;            ///< IG frame of the last Start of Frame the host got

    bool operator==(const IgControl&) const = default;
};

/// Entity Control (opcode 2, 48 bytes).
struct EntityControl
{
    uint16_t entityId = 0;
    uint8_t entityState = 1;           ///< 0 Inactive/Standby, 1 Active, 2 Destroyed
    bool attached = false;             ///< pose is relative to the parent entity
    bool collisionDetection = false;
    bool inheritAlpha = false;
    uint8_t groundOceanClamp = 0;      ///< 0 none, 1 non-conformal, 2 conformal
    bool animationBackward = false;    ///< Animation Direction
    bool animationContinuous = false;  ///< Animation Loop Mode
    uint8_t animationState = 0;        ///< 0 Stop, 1 Pause, 2 Play, 3 Continue
    bool extrapolationEnable = false;
    uint8_t alpha = 255;
    uint16_t entityType = 0;
    uint16_t parentId = 0;
    float rollDeg = 0;
    float pitchDeg = 0;
    float yawDeg = 0;
    double latDegOrXM = 0;             ///< geodetic latitude (detached) or X offset (attached, m)
    double lonDegOrYM = 0;             ///< longitude (detached) or Y offset (attached, m)
    double altMslMOrZM = 0;            ///< altitude above mean sea level (detached) or Z offset (m)

    bool operator==(const EntityControl&) const = default;
};

/// Celestial Sphere Control (opcode 9, 16 bytes). The 3.3 packet carries no seconds field.
struct CelestialSphereControl
{
    uint8_t hour = 0;              ///< UTC 0-23
    uint8_t minute = 0;            ///< 0-59
    bool ephemerisEnable = false;  ///< time advances on the IG (else static)
    bool sunEnable = false;
    bool moonEnable = false;
    bool starFieldEnable = false;
    bool dateTimeValid = false;    ///< hour, minute and date are to be used
    uint32_t dateMMDDYYYY = 0;     ///< e.g. 6212026 for 21 June 2026
    float starFieldIntensityPct = 0;  ///< 0-100

    bool operator==(const CelestialSphereControl&) const = default;
};

/// Atmosphere Control (opcode 10, 32 bytes).
struct AtmosphereControl
{
    bool atmosphericModelEnable = false;
    uint8_t humidityPct = 0;              ///< 0-100
    float airTemperatureC = 0;
    float visibilityM = 0;                ///< >= 0
    float horizontalWindMps = 0;          ///< >= 0
    float verticalWindMps = 0;
    float windDirectionDeg = 0;           ///< the direction the wind blows from, true north
    float pressureHpa = 0;                ///< mb

    bool operator==(const AtmosphereControl&) const = default;
};

/// Environmental Region Control (opcode 11, 48 bytes): a rounded rectangle, rotated, with a transition band.
struct EnvironmentalRegionControl
{
    uint16_t regionId = 0;
    uint8_t regionState = 0;          ///< RegionState
    bool mergeWeather = false;
    bool mergeAerosol = false;
    bool mergeMaritime = false;
    bool mergeTerrestrial = false;
    double latDeg = 0;                ///< centre
    double lonDeg = 0;
    float sizeXM = 0;                 ///< along the region's X axis (north when rotation is 0)
    float sizeYM = 0;
    float cornerRadiusM = 0;
    float rotationDeg = 0;            ///< yaw from true north
    float transitionPerimeterM = 0;   ///< band outside the rectangle over which it fades out

    bool operator==(const EnvironmentalRegionControl&) const = default;
};

/// Weather Control (opcode 12, 56 bytes).
struct WeatherControl
{
    uint16_t entityOrRegionId = 0;     ///< unused for global scope
    uint8_t layerId = 0;               ///< WeatherLayerId
    uint8_t humidityPct = 0;           ///< 0-100
    bool weatherEnable = false;
    bool scudEnable = false;
    bool randomWindsEnable = false;
    bool randomLightningEnable = false;
    uint8_t cloudType = 0;             ///< CloudType (shaders/shared/cloud_type.h)
    uint8_t scope = 0;                 ///< WeatherScope
    uint8_t severity = 0;              ///< 0 (least) - 5 (most)
    float airTemperatureC = 0;
    float visibilityM = 0;             ///< >= 0
    float scudFrequencyPct = 0;        ///< 0-100
    float coveragePct = 0;             ///< 0-100
    float baseElevationM = 0;          ///< above mean sea level
    float thicknessM = 0;              ///< >= 0
    float transitionBandM = 0;         ///< >= 0: fade above and below the layer
    float horizontalWindMps = 0;       ///< >= 0
    float verticalWindMps = 0;
    float windDirectionDeg = 0;
    float pressureHpa = 0;
    float aerosolGPerM3 = 0;           ///< >= 0

    bool operator==(const WeatherControl&) const = default;
};

/// View Control (opcode 16, 32 bytes): the eye's offset and attitude relative to an entity.
struct ViewControl
{
    uint16_t viewId = 0;
    uint8_t groupId = 0;         ///< 0 = the view alone, else every view of that group
    bool xOffsetEnable = false;
    bool yOffsetEnable = false;
    bool zOffsetEnable = false;
    bool rollEnable = false;
    bool pitchEnable = false;
    bool yawEnable = false;
    uint16_t entityId = 0;
    float xOffsetM = 0;          ///< entity body axes: X forward, Y right, Z down
    float yOffsetM = 0;
    float zOffsetM = 0;
    float rollDeg = 0;
    float pitchDeg = 0;
    float yawDeg = 0;

    bool operator==(const ViewControl&) const = default;
};

/// View Definition (opcode 21, 32 bytes): the view's asymmetric frustum.
struct ViewDefinition
{
    uint16_t viewId = 0;
    uint8_t groupId = 0;
    bool nearEnable = false;
    bool farEnable = false;
    bool leftEnable = false;
    bool rightEnable = false;
    bool topEnable = false;
    bool bottomEnable = false;
    uint8_t mirrorMode = 0;       ///< 0 none, 1 horizontal, 2 vertical, 3 both
    uint8_t pixelReplication = 0;
    bool orthographic = false;    ///< Projection Type
    bool reorder = false;
    uint8_t viewType = 0;         ///< IG-defined
    float nearM = 0;
    float farM = 0;
    float leftDeg = 0;            ///< half-angle, negative to the left of the view axis
    float rightDeg = 0;
    float topDeg = 0;
    float bottomDeg = 0;          ///< negative below the view axis

    bool operator==(const ViewDefinition&) const = default;
};

/// Environmental Conditions Request (opcode 28, 32 bytes).
struct EnvironmentalConditionsRequest
{
    uint8_t requestType = 0;  ///< EnvironmentalRequestBits
    uint8_t requestId = 0;
    double latDeg = 0;
    double lonDeg = 0;
    double altMslM = 0;

    bool operator==(const EnvironmentalConditionsRequest&) const = default;
};

// ---- IG -> host -----------------------------------------------------------------------------------------

/// Start of Frame (opcode 101, 24 bytes): the first packet of every IG datagram.
struct StartOfFrame
{
    uint8_t majorVersion = kCigiMajorVersion;
    int8_t databaseNumber = 0;
    uint8_t igStatus = 0;                      ///< 0 = normal, else an IG-defined error code
    uint8_t igMode = 1;                        ///< 0 Reset/Standby, 1 Operate, 2 Debug, 3 Offline
    bool timestampValid = false;
    bool earthReferenceModelCustom = false;    ///< false = WGS 84
    uint8_t minorVersion = kCigiMinorVersion;
    uint32_t igFrameNumber = 0;
    uint32_t timestamp10us = 0;
    uint32_t lastHostFrameNumber = 0;

    bool operator==(const StartOfFrame&) const = default;
};

/// Weather Conditions Response (opcode 109, 32 bytes).
struct WeatherConditionsResponse
{
    uint8_t requestId = 0;
    uint8_t humidityPct = 0;
    float airTemperatureC = 0;
    float visibilityM = 0;
    float horizontalWindMps = 0;
    float verticalWindMps = 0;
    float windDirectionDeg = 0;
    float pressureHpa = 0;

    bool operator==(const WeatherConditionsResponse&) const = default;
};

/// Aerosol Concentration Response (opcode 110, 8 bytes): one per weather layer at the point asked.
struct AerosolConcentrationResponse
{
    uint8_t requestId = 0;
    uint8_t layerId = 0;
    float aerosolGPerM3 = 0;

    bool operator==(const AerosolConcentrationResponse&) const = default;
};

// Decoders read a packet whose first `kSize...` bytes the caller has checked are present; they never fail
// (range checks are cigi_validate.h's). Encoders append the packet, opcode and size included.
IgControl decodeIgControl(const uint8_t* packet, ByteOrder order);
EntityControl decodeEntityControl(const uint8_t* packet, ByteOrder order);
CelestialSphereControl decodeCelestialSphereControl(const uint8_t* packet, ByteOrder order);
AtmosphereControl decodeAtmosphereControl(const uint8_t* packet, ByteOrder order);
EnvironmentalRegionControl decodeEnvironmentalRegionControl(const uint8_t* packet, ByteOrder order);
WeatherControl decodeWeatherControl(const uint8_t* packet, ByteOrder order);
ViewControl decodeViewControl(const uint8_t* packet, ByteOrder order);
ViewDefinition decodeViewDefinition(const uint8_t* packet, ByteOrder order);
EnvironmentalConditionsRequest decodeEnvironmentalConditionsRequest(const uint8_t* packet, ByteOrder order);
StartOfFrame decodeStartOfFrame(const uint8_t* packet, ByteOrder order);
WeatherConditionsResponse decodeWeatherConditionsResponse(const uint8_t* packet, ByteOrder order);
AerosolConcentrationResponse decodeAerosolConcentrationResponse(const uint8_t* packet, ByteOrder order);

void encode(const IgControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const EntityControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const CelestialSphereControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const AtmosphereControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const EnvironmentalRegionControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const WeatherControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const ViewControl& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const ViewDefinition& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const EnvironmentalConditionsRequest& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const StartOfFrame& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const WeatherConditionsResponse& p, ByteOrder order, std::vector<uint8_t>& out);
void encode(const AerosolConcentrationResponse& p, ByteOrder order, std::vector<uint8_t>& out);

/// The name the ICD gives an opcode ("Weather Control"), or nullptr when CIGI 3.3 defines none.
const char* opcodeName(uint8_t opcode);

} // namespace sky::cigi
