// SPDX-License-Identifier: MIT
// One field table per CIGI 3.3 packet: each field's byte offset, wire type (and bits), the member of the
// packet struct that holds it, the ICD's name and the name Wireshark's dissector shows it under. The
// decoder and the encoder walk these tables (cigi_packets.cpp), the range checks name fields by them
// (cigi_validate.cpp), and the tests compare them with tshark (tests/cigi/), so a layout is written once.
//
// Offsets are bytes from the packet's first byte, bit 0 is the least significant. Bytes 0-1 of every packet
// are its opcode and size (PacketLayout::opcode, ::size); IG Control and Start of Frame carry the byte-swap
// magic at bytes 6-7 (PacketLayout::magicOffset). Bytes no field covers are reserved and written as zero.
// Where the layouts come from: cigi_packets.h.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <tuple>
#include <type_traits>

namespace sky::cigi
{

/// How a field is stored on the wire. Multi-byte types follow the sender's byte order; bit fields never swap.
enum class FieldType : uint8_t
{
    U8,
    I8,
    U16,
    U32,
    F32,
    F64,
    Bits, ///< `width` bits of one byte from bit `shift`
};

/// Bytes a field of this type spans (a bit field lies in one byte).
constexpr uint8_t fieldBytes(FieldType type)
{
    switch (type)
    {
    case FieldType::U16:
        return 2;
    case FieldType::U32:
    case FieldType::F32:
        return 4;
    case FieldType::F64:
        return 8;
    default:
        return 1;
    }
}

/// One field of `Packet`, held in its member `member` of type `Value`.
template <typename Packet, typename Value> struct Field
{
    Value Packet::*member;
    uint8_t offset; ///< bytes from the packet's first byte
    FieldType type;
    uint8_t shift;         ///< Bits: the field's lowest bit in its byte
    uint8_t width;         ///< Bits: how many bits; 0 for whole-byte fields
    const char* name;      ///< the ICD's name, as the range checks' messages give it
    const char* dissector; ///< Wireshark's field name (`tshark -e`), or nullptr where the dissector has none

    constexpr uint8_t size() const { return fieldBytes(type); }
};

/// The wire type of a whole-byte field held in a `Value`.
template <typename Value> constexpr FieldType wireTypeOf()
{
    if constexpr (std::is_same_v<Value, uint8_t>)
        return FieldType::U8;
    else if constexpr (std::is_same_v<Value, int8_t>)
        return FieldType::I8;
    else if constexpr (std::is_same_v<Value, uint16_t>)
        return FieldType::U16;
    else if constexpr (std::is_same_v<Value, uint32_t>)
        return FieldType::U32;
    else if constexpr (std::is_same_v<Value, float>)
        return FieldType::F32;
    else
    {
        static_assert(std::is_same_v<Value, double>, "a whole-byte field is u8, i8, u16, u32, f32 or f64");
        return FieldType::F64;
    }
}

/// A whole-byte field; its wire type follows the member's type.
template <typename Packet, typename Value>
constexpr Field<Packet, Value> field(Value Packet::*member, uint8_t offset, const char* name, const char* dissector)
{
    return {member, offset, wireTypeOf<Value>(), 0, 0, name, dissector};
}

/// `width` bits of byte `offset` from bit `shift`, held in a bool (one bit) or a small unsigned number.
template <typename Packet, typename Value>
constexpr Field<Packet, Value> bits(Value Packet::*member, uint8_t offset, uint8_t shift, uint8_t width,
                                    const char* name, const char* dissector)
{
    static_assert(std::is_same_v<Value, bool> || std::is_same_v<Value, uint8_t>, "a bit field is bool or u8");
    return {member, offset, FieldType::Bits, shift, width, name, dissector};
}

/// Specialised for each packet: `opcode`, `size` (bytes) and `fields` (a tuple of Field).
template <typename Packet> struct PacketLayout;

template <> struct PacketLayout<IgControl>
{
    using P = IgControl;
    static constexpr uint8_t opcode = kOpIgControl, size = kSizeIgControl, magicOffset = 6;
    static constexpr auto fields = std::tuple{
        field(&P::majorVersion, 2, "CIGI Version", nullptr),
        field(&P::databaseNumber, 3, "Database Number", "cigi.ig_control.db_number"),
        bits(&P::igMode, 4, 0, 2, "IG Mode", "cigi.ig_control.ig_mode"),
        bits(&P::timestampValid, 4, 2, 1, "Timestamp Valid", "cigi.ig_control.timestamp_valid"),
        bits(&P::extrapolationEnable, 4, 3, 1, "Extrapolation/Interpolation Enable",
             "cigi.ig_control.extrapolation_enable"),
        bits(&P::minorVersion, 4, 4, 4, "Minor Version", "cigi.ig_control.minor_version"),
        field(&P::hostFrameNumber, 8, "Host Frame Number", "cigi.ig_control.host_frame_number"),
        field(&P::timestamp10us, 12, "Timestamp", "cigi.ig_control.timestamp"),
        field(&P::lastIgFrameNumber, 16, "Last IG Frame Number", "cigi.ig_control.last_ig_frame_number"),
    };
};

template <> struct PacketLayout<EntityControl>
{
    using P = EntityControl;
    static constexpr uint8_t opcode = kOpEntityControl, size = kSizeEntityControl;
    // Latitude, Longitude and Altitude are the X, Y and Z offsets (m) of an attached entity.
    static constexpr auto fields = std::tuple{
        field(&P::entityId, 2, "Entity ID", "cigi.entity_control.entity_id"),
        bits(&P::entityState, 4, 0, 2, "Entity State", "cigi.entity_control.entity_state"),
        bits(&P::attached, 4, 2, 1, "Attach State", "cigi.entity_control.attach_state"),
        bits(&P::collisionDetection, 4, 3, 1, "Collision Detection Enable", nullptr),
        bits(&P::inheritAlpha, 4, 4, 1, "Inherit Alpha", "cigi.entity_control.inherit_alpha"),
        bits(&P::groundOceanClamp, 4, 5, 2, "Ground/Ocean Clamp", "cigi.entity_control.ground_ocean_clamp"),
        bits(&P::animationBackward, 5, 0, 1, "Animation Direction", "cigi.entity_control.animation_dir"),
        bits(&P::animationContinuous, 5, 1, 1, "Animation Loop Mode", "cigi.entity_control.animation_loop_mode"),
        bits(&P::animationState, 5, 2, 2, "Animation State", "cigi.entity_control.animation_state"),
        bits(&P::extrapolationEnable, 5, 4, 1, "Linear Extrapolation/Interpolation Enable",
             "cigi.entity_control.extrapolation_enable"),
        field(&P::alpha, 6, "Alpha", "cigi.entity_control.alpha"),
        field(&P::entityType, 8, "Entity Type", "cigi.entity_control.entity_type"),
        field(&P::parentId, 10, "Parent ID", "cigi.entity_control.parent_id"),
        field(&P::rollDeg, 12, "Roll", "cigi.entity_control.roll"),
        field(&P::pitchDeg, 16, "Pitch", "cigi.entity_control.pitch"),
        field(&P::yawDeg, 20, "Yaw", "cigi.entity_control.yaw"),
        field(&P::latDegOrXM, 24, "Latitude", "cigi.entity_control.lat_xoff"),
        field(&P::lonDegOrYM, 32, "Longitude", "cigi.entity_control.lon_yoff"),
        field(&P::altMslMOrZM, 40, "Altitude", "cigi.entity_control.alt_zoff"),
    };
};

template <> struct PacketLayout<CelestialSphereControl>
{
    using P = CelestialSphereControl;
    static constexpr uint8_t opcode = kOpCelestialSphereControl, size = kSizeCelestialSphereControl;
    static constexpr auto fields = std::tuple{
        field(&P::hour, 2, "Hour", "cigi.celestial_sphere_control.hour"),
        field(&P::minute, 3, "Minute", "cigi.celestial_sphere_control.minute"),
        bits(&P::ephemerisEnable, 4, 0, 1, "Ephemeris Model Enable", "cigi.celestial_sphere_control.ephemeris_enable"),
        bits(&P::sunEnable, 4, 1, 1, "Sun Enable", "cigi.celestial_sphere_control.sun_enable"),
        bits(&P::moonEnable, 4, 2, 1, "Moon Enable", "cigi.celestial_sphere_control.moon_enable"),
        bits(&P::starFieldEnable, 4, 3, 1, "Star Field Enable", "cigi.celestial_sphere_control.star_enable"),
        bits(&P::dateTimeValid, 4, 4, 1, "Date/Time Valid", "cigi.celestial_sphere_control.date_time_valid"),
        field(&P::dateMMDDYYYY, 8, "Date (MMDDYYYY)", "cigi.celestial_sphere_control.date"),
        field(&P::starFieldIntensityPct, 12, "Star Field Intensity", "cigi.celestial_sphere_control.star_intensity"),
    };
};

template <> struct PacketLayout<AtmosphereControl>
{
    using P = AtmosphereControl;
    static constexpr uint8_t opcode = kOpAtmosphereControl, size = kSizeAtmosphereControl;
    static constexpr auto fields = std::tuple{
        bits(&P::atmosphericModelEnable, 2, 0, 1, "Atmospheric Model Enable",
             "cigi.atmosphere_control.atmospheric_model_enable"),
        field(&P::humidityPct, 3, "Global Humidity", "cigi.atmosphere_control.humidity"),
        field(&P::airTemperatureC, 4, "Global Air Temperature", "cigi.atmosphere_control.air_temp"),
        field(&P::visibilityM, 8, "Global Visibility Range", "cigi.atmosphere_control.visibility_range"),
        field(&P::horizontalWindMps, 12, "Global Horizontal Wind Speed", "cigi.atmosphere_control.horiz_wind"),
        field(&P::verticalWindMps, 16, "Global Vertical Wind Speed", "cigi.atmosphere_control.vert_wind"),
        field(&P::windDirectionDeg, 20, "Global Wind Direction", "cigi.atmosphere_control.wind_direction"),
        field(&P::pressureHpa, 24, "Global Barometric Pressure", "cigi.atmosphere_control.barometric_pressure"),
    };
};

template <> struct PacketLayout<EnvironmentalRegionControl>
{
    using P = EnvironmentalRegionControl;
    static constexpr uint8_t opcode = kOpEnvironmentalRegionControl, size = kSizeEnvironmentalRegionControl;
    static constexpr auto fields = std::tuple{
        field(&P::regionId, 2, "Region ID", "cigi.env_region_control.region_id"),
        bits(&P::regionState, 4, 0, 2, "Region State", "cigi.env_region_control.region_state"),
        bits(&P::mergeWeather, 4, 2, 1, "Merge Weather Properties", "cigi.env_region_control.merge_weather"),
        bits(&P::mergeAerosol, 4, 3, 1, "Merge Aerosol Concentrations", "cigi.env_region_control.merge_aerosol"),
        bits(&P::mergeMaritime, 4, 4, 1, "Merge Maritime Surface Conditions", "cigi.env_region_control.merge_maritime"),
        bits(&P::mergeTerrestrial, 4, 5, 1, "Merge Terrestrial Surface Conditions",
             "cigi.env_region_control.merge_terrestrial"),
        field(&P::latDeg, 8, "Latitude", "cigi.env_region_control.lat"),
        field(&P::lonDeg, 16, "Longitude", "cigi.env_region_control.lon"),
        field(&P::sizeXM, 24, "Size X", "cigi.env_region_control.size_x"),
        field(&P::sizeYM, 28, "Size Y", "cigi.env_region_control.size_y"),
        field(&P::cornerRadiusM, 32, "Corner Radius", "cigi.env_region_control.corner_radius"),
        field(&P::rotationDeg, 36, "Rotation", "cigi.env_region_control.rotation"),
        field(&P::transitionPerimeterM, 40, "Transition Perimeter", "cigi.env_region_control.transition_perimeter"),
    };
};

template <> struct PacketLayout<WeatherControl>
{
    using P = WeatherControl;
    static constexpr uint8_t opcode = kOpWeatherControl, size = kSizeWeatherControl;
    static constexpr auto fields = std::tuple{
        field(&P::entityOrRegionId, 2, "Entity ID/Region ID", "cigi.weather_control.entity_region_id"),
        field(&P::layerId, 4, "Layer ID", "cigi.weather_control.layer_id"),
        field(&P::humidityPct, 5, "Humidity", "cigi.weather_control.humidity"),
        bits(&P::weatherEnable, 6, 0, 1, "Weather Enable", "cigi.weather_control.weather_enable"),
        bits(&P::scudEnable, 6, 1, 1, "Scud Enable", "cigi.weather_control.scud_enable"),
        bits(&P::randomWindsEnable, 6, 2, 1, "Random Winds Enable", "cigi.weather_control.random_winds_enable"),
        bits(&P::randomLightningEnable, 6, 3, 1, "Random Lightning Enable",
             "cigi.weather_control.random_lightning_enable"),
        bits(&P::cloudType, 6, 4, 4, "Cloud Type", "cigi.weather_control.cloud_type"),
        bits(&P::scope, 7, 0, 2, "Scope", "cigi.weather_control.scope"),
        bits(&P::severity, 7, 2, 3, "Severity", "cigi.weather_control.severity"),
        field(&P::airTemperatureC, 8, "Air Temperature", "cigi.weather_control.air_temp"),
        field(&P::visibilityM, 12, "Visibility Range", "cigi.weather_control.visibility_range"),
        field(&P::scudFrequencyPct, 16, "Scud Frequency", "cigi.weather_control.scud_frequency"),
        field(&P::coveragePct, 20, "Coverage", "cigi.weather_control.coverage"),
        field(&P::baseElevationM, 24, "Base Elevation", "cigi.weather_control.base_elevation"),
        field(&P::thicknessM, 28, "Thickness", "cigi.weather_control.thickness"),
        field(&P::transitionBandM, 32, "Transition Band", "cigi.weather_control.transition_band"),
        field(&P::horizontalWindMps, 36, "Horizontal Wind Speed", "cigi.weather_control.horiz_wind"),
        field(&P::verticalWindMps, 40, "Vertical Wind Speed", "cigi.weather_control.vert_wind"),
        field(&P::windDirectionDeg, 44, "Wind Direction", "cigi.weather_control.wind_direction"),
        field(&P::pressureHpa, 48, "Barometric Pressure", "cigi.weather_control.barometric_pressure"),
        field(&P::aerosolGPerM3, 52, "Aerosol Concentration", "cigi.weather_control.aerosol_concentration"),
    };
};

template <> struct PacketLayout<ViewControl>
{
    using P = ViewControl;
    static constexpr uint8_t opcode = kOpViewControl, size = kSizeViewControl;
    static constexpr auto fields = std::tuple{
        field(&P::viewId, 2, "View ID", "cigi.view_control.view_id"),
        field(&P::groupId, 4, "Group ID", "cigi.view_control.group_id"),
        bits(&P::xOffsetEnable, 5, 0, 1, "X Offset Enable", "cigi.view_control.xoff_enable"),
        bits(&P::yOffsetEnable, 5, 1, 1, "Y Offset Enable", "cigi.view_control.yoff_enable"),
        bits(&P::zOffsetEnable, 5, 2, 1, "Z Offset Enable", "cigi.view_control.zoff_enable"),
        bits(&P::rollEnable, 5, 3, 1, "Roll Enable", "cigi.view_control.roll_enable"),
        bits(&P::pitchEnable, 5, 4, 1, "Pitch Enable", "cigi.view_control.pitch_enable"),
        bits(&P::yawEnable, 5, 5, 1, "Yaw Enable", "cigi.view_control.yaw_enable"),
        field(&P::entityId, 6, "Entity ID", "cigi.view_control.entity_id"),
        field(&P::xOffsetM, 8, "X Offset", "cigi.view_control.xoff"),
        field(&P::yOffsetM, 12, "Y Offset", "cigi.view_control.yoff"),
        field(&P::zOffsetM, 16, "Z Offset", "cigi.view_control.zoff"),
        field(&P::rollDeg, 20, "Roll", "cigi.view_control.roll"),
        field(&P::pitchDeg, 24, "Pitch", "cigi.view_control.pitch"),
        field(&P::yawDeg, 28, "Yaw", "cigi.view_control.yaw"),
    };
};

template <> struct PacketLayout<ViewDefinition>
{
    using P = ViewDefinition;
    static constexpr uint8_t opcode = kOpViewDefinition, size = kSizeViewDefinition;
    static constexpr auto fields = std::tuple{
        field(&P::viewId, 2, "View ID", "cigi.view_def.view_id"),
        field(&P::groupId, 4, "Group ID", "cigi.view_def.group_id"),
        bits(&P::nearEnable, 5, 0, 1, "Near Enable", "cigi.view_def.near_enable"),
        bits(&P::farEnable, 5, 1, 1, "Far Enable", "cigi.view_def.far_enable"),
        bits(&P::leftEnable, 5, 2, 1, "Left Enable", "cigi.view_def.left_enable"),
        bits(&P::rightEnable, 5, 3, 1, "Right Enable", "cigi.view_def.right_enable"),
        bits(&P::topEnable, 5, 4, 1, "Top Enable", "cigi.view_def.top_enable"),
        bits(&P::bottomEnable, 5, 5, 1, "Bottom Enable", "cigi.view_def.bottom_enable"),
        bits(&P::mirrorMode, 5, 6, 2, "Mirror Mode", "cigi.view_def.mirror_mode"),
        bits(&P::pixelReplication, 6, 0, 3, "Pixel Replication Mode", "cigi.view_def.pixel_replication"),
        bits(&P::orthographic, 6, 3, 1, "Projection Type", "cigi.view_def.projection_type"),
        bits(&P::reorder, 6, 4, 1, "Reorder", "cigi.view_def.reorder"),
        bits(&P::viewType, 6, 5, 3, "View Type", "cigi.view_def.view_type"),
        field(&P::nearM, 8, "Near", "cigi.view_def.near"),
        field(&P::farM, 12, "Far", "cigi.view_def.far"),
        field(&P::leftDeg, 16, "Left", "cigi.view_def.left"),
        field(&P::rightDeg, 20, "Right", "cigi.view_def.right"),
        field(&P::topDeg, 24, "Top", "cigi.view_def.top"),
        field(&P::bottomDeg, 28, "Bottom", "cigi.view_def.bottom"),
    };
};

template <> struct PacketLayout<EnvironmentalConditionsRequest>
{
    using P = EnvironmentalConditionsRequest;
    static constexpr uint8_t opcode = kOpEnvironmentalConditionsRequest, size = kSizeEnvironmentalConditionsRequest;
    static constexpr auto fields = std::tuple{
        bits(&P::requestType, 2, 0, 4, "Request Type", "cigi.env_cond_request.type"),
        field(&P::requestId, 3, "Request ID", "cigi.env_cond_request.id"),
        field(&P::latDeg, 8, "Latitude", "cigi.env_cond_request.lat"),
        field(&P::lonDeg, 16, "Longitude", "cigi.env_cond_request.lon"),
        field(&P::altMslM, 24, "Altitude", "cigi.env_cond_request.alt"),
    };
};

template <> struct PacketLayout<StartOfFrame>
{
    using P = StartOfFrame;
    static constexpr uint8_t opcode = kOpStartOfFrame, size = kSizeStartOfFrame, magicOffset = 6;
    static constexpr auto fields = std::tuple{
        field(&P::majorVersion, 2, "CIGI Version", "cigi.version"),
        field(&P::databaseNumber, 3, "Database Number", "cigi.sof.db_number"),
        field(&P::igStatus, 4, "IG Status", "cigi.sof.ig_status"),
        bits(&P::igMode, 5, 0, 2, "IG Mode", "cigi.sof.ig_mode"),
        bits(&P::timestampValid, 5, 2, 1, "Timestamp Valid", "cigi.sof.timestamp_valid"),
        bits(&P::earthReferenceModelCustom, 5, 3, 1, "Earth Reference Model", "cigi.sof.earth_reference_model"),
        bits(&P::minorVersion, 5, 4, 4, "Minor Version", "cigi.sof.minor_version"),
        field(&P::igFrameNumber, 8, "IG Frame Number", "cigi.sof.ig_frame_number"),
        field(&P::timestamp10us, 12, "Timestamp", "cigi.sof.timestamp"),
        field(&P::lastHostFrameNumber, 16, "Last Host Frame Number", "cigi.sof.last_host_frame_number"),
    };
};

template <> struct PacketLayout<WeatherConditionsResponse>
{
    using P = WeatherConditionsResponse;
    static constexpr uint8_t opcode = kOpWeatherConditionsResponse, size = kSizeWeatherConditionsResponse;
    static constexpr auto fields = std::tuple{
        field(&P::requestId, 2, "Request ID", "cigi.wea_cond_response.request_id"),
        field(&P::humidityPct, 3, "Humidity", "cigi.wea_cond_response.humidity"),
        field(&P::airTemperatureC, 4, "Air Temperature", "cigi.wea_cond_response.air_temp"),
        field(&P::visibilityM, 8, "Visibility Range", "cigi.wea_cond_response.visibility_range"),
        field(&P::horizontalWindMps, 12, "Horizontal Wind Speed", "cigi.wea_cond_response.horiz_speed"),
        field(&P::verticalWindMps, 16, "Vertical Wind Speed", "cigi.wea_cond_response.vert_speed"),
        field(&P::windDirectionDeg, 20, "Wind Direction", "cigi.wea_cond_response.wind_direction"),
        field(&P::pressureHpa, 24, "Barometric Pressure", "cigi.wea_cond_response.barometric_pressure"),
    };
};

template <> struct PacketLayout<AerosolConcentrationResponse>
{
    using P = AerosolConcentrationResponse;
    static constexpr uint8_t opcode = kOpAerosolConcentrationResponse, size = kSizeAerosolConcentrationResponse;
    static constexpr auto fields = std::tuple{
        field(&P::requestId, 2, "Request ID", "cigi.aerosol_concentration_response.request_id"),
        field(&P::layerId, 3, "Layer ID", "cigi.aerosol_concentration_response.layer_id"),
        field(&P::aerosolGPerM3, 4, "Aerosol Concentration",
              "cigi.aerosol_concentration_response.aerosol_concentration"),
    };
};

/// Calls `visit(field)` for each field of `Packet`'s table, in the table's order.
template <typename Packet, typename Visit> constexpr void forEachField(Visit&& visit)
{
    std::apply([&](const auto&... f) { (visit(f), ...); }, PacketLayout<Packet>::fields);
}

/// The packet struct a pointer to one of its members belongs to.
template <typename MemberPointer> struct MemberOf;
template <typename Class, typename Value> struct MemberOf<Value Class::*>
{
    using Packet = Class;
};

/// The ICD name of the field held in `Member` (&WeatherControl::coveragePct -> "Coverage"); a member the
/// table does not hold does not compile.
template <auto Member> consteval const char* fieldName()
{
    const char* name = nullptr;
    forEachField<typename MemberOf<decltype(Member)>::Packet>(
        [&](const auto& f)
        {
            if constexpr (std::is_same_v<decltype(f.member), decltype(Member)>)
                if (f.member == Member)
                    name = f.name;
        });
    if (name == nullptr)
        throw "the member is not in its packet's field table";
    return name;
}

/// True when every field lies inside the packet, after its opcode and size, off the byte-swap magic, and
/// no two fields share a bit: checked at compile time for every table (cigi_packets.cpp).
template <typename Packet> constexpr bool layoutIsSound()
{
    using L = PacketLayout<Packet>;
    uint8_t used[256] = {}; // bit masks of the bytes taken
    used[0] = used[1] = 0xFF;
    if constexpr (requires { L::magicOffset; })
        used[L::magicOffset] = used[L::magicOffset + 1] = 0xFF;
    bool sound = true;
    forEachField<Packet>(
        [&](const auto& f)
        {
            if (f.offset + f.size() > L::size || (f.type == FieldType::Bits && (f.width == 0 || f.shift + f.width > 8)))
            {
                sound = false;
                return;
            }
            for (unsigned b = 0; b < f.size(); ++b)
            {
                const unsigned mask = f.type == FieldType::Bits ? ((1u << f.width) - 1u) << f.shift : 0xFFu;
                if (used[f.offset + b] & mask)
                    sound = false;
                used[f.offset + b] = static_cast<uint8_t>(used[f.offset + b] | mask);
            }
        });
    return sound;
}

} // namespace sky::cigi
