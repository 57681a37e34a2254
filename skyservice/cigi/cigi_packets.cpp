// SPDX-License-Identifier: MIT
// Every packet is read and written by walking its field table (cigi_fields.h).
#include "skyservice/cigi/cigi_packets.h"

#include "skyservice/cigi/cigi_fields.h"

namespace sky::cigi
{
namespace
{

template <typename Packet, typename Value> void readField(const WireReader& r, const Field<Packet, Value>& f, Packet& p)
{
    Value& v = p.*f.member;
    switch (f.type)
    {
    case FieldType::U8:
        v = static_cast<Value>(r.u8(f.offset));
        break;
    case FieldType::I8:
        v = static_cast<Value>(r.i8(f.offset));
        break;
    case FieldType::U16:
        v = static_cast<Value>(r.u16(f.offset));
        break;
    case FieldType::U32:
        v = static_cast<Value>(r.u32(f.offset));
        break;
    case FieldType::F32:
        v = static_cast<Value>(r.f32(f.offset));
        break;
    case FieldType::F64:
        v = static_cast<Value>(r.f64(f.offset));
        break;
    case FieldType::Bits:
        v = static_cast<Value>(r.bits(f.offset, f.shift, f.width));
        break;
    }
}

template <typename Packet, typename Value>
void writeField(WireWriter& w, const Field<Packet, Value>& f, const Packet& p)
{
    const Value v = p.*f.member;
    switch (f.type)
    {
    case FieldType::U8:
        w.u8(f.offset, static_cast<uint8_t>(v));
        break;
    case FieldType::I8:
        w.i8(f.offset, static_cast<int8_t>(v));
        break;
    case FieldType::U16:
        w.u16(f.offset, static_cast<uint16_t>(v));
        break;
    case FieldType::U32:
        w.u32(f.offset, static_cast<uint32_t>(v));
        break;
    case FieldType::F32:
        w.f32(f.offset, static_cast<float>(v));
        break;
    case FieldType::F64:
        w.f64(f.offset, static_cast<double>(v));
        break;
    case FieldType::Bits:
        w.bits(f.offset, f.shift, f.width, static_cast<unsigned>(v));
        break;
    }
}

template <typename Packet> Packet decodeByTable(const uint8_t* packet, ByteOrder order)
{
    static_assert(layoutIsSound<Packet>(), "a field lies outside its packet or on another field");
    const WireReader r(packet, order);
    Packet p;
    forEachField<Packet>([&](const auto& f) { readField(r, f, p); });
    return p;
}

template <typename Packet> void encodeByTable(const Packet& p, ByteOrder order, std::vector<uint8_t>& out)
{
    using Layout = PacketLayout<Packet>;
    WireWriter w(out, Layout::size, order);
    w.u8(0, Layout::opcode);
    w.u8(1, Layout::size);
    if constexpr (requires { Layout::magicOffset; })
        w.u16(Layout::magicOffset, kByteSwapMagic);
    forEachField<Packet>([&](const auto& f) { writeField(w, f, p); });
}

} // namespace

IgControl decodeIgControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<IgControl>(packet, order);
}
void encode(const IgControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
EntityControl decodeEntityControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<EntityControl>(packet, order);
}
void encode(const EntityControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
CelestialSphereControl decodeCelestialSphereControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<CelestialSphereControl>(packet, order);
}
void encode(const CelestialSphereControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
AtmosphereControl decodeAtmosphereControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<AtmosphereControl>(packet, order);
}
void encode(const AtmosphereControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
EnvironmentalRegionControl decodeEnvironmentalRegionControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<EnvironmentalRegionControl>(packet, order);
}
void encode(const EnvironmentalRegionControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
WeatherControl decodeWeatherControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<WeatherControl>(packet, order);
}
void encode(const WeatherControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
ViewControl decodeViewControl(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<ViewControl>(packet, order);
}
void encode(const ViewControl& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
ViewDefinition decodeViewDefinition(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<ViewDefinition>(packet, order);
}
void encode(const ViewDefinition& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
EnvironmentalConditionsRequest decodeEnvironmentalConditionsRequest(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<EnvironmentalConditionsRequest>(packet, order);
}
void encode(const EnvironmentalConditionsRequest& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
StartOfFrame decodeStartOfFrame(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<StartOfFrame>(packet, order);
}
void encode(const StartOfFrame& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
WeatherConditionsResponse decodeWeatherConditionsResponse(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<WeatherConditionsResponse>(packet, order);
}
void encode(const WeatherConditionsResponse& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}
AerosolConcentrationResponse decodeAerosolConcentrationResponse(const uint8_t* packet, ByteOrder order)
{
    return decodeByTable<AerosolConcentrationResponse>(packet, order);
}
void encode(const AerosolConcentrationResponse& p, ByteOrder order, std::vector<uint8_t>& out)
{
    encodeByTable(p, order, out);
}

const char* opcodeName(uint8_t opcode)
{
    // ICD 3.3 section 4.1 (host -> IG, 1-35) and 4.2 (IG -> host, 101-117); 201-255 are user-defined.
    static const char* const kHostToIg[] = {"IG Control",
                                            "Entity Control",
                                            "Conformal Clamped Entity Control",
                                            "Component Control",
                                            "Short Component Control",
                                            "Articulated Part Control",
                                            "Short Articulated Part Control",
                                            "Rate Control",
                                            "Celestial Sphere Control",
                                            "Atmosphere Control",
                                            "Environmental Region Control",
                                            "Weather Control",
                                            "Maritime Surface Conditions Control",
                                            "Wave Control",
                                            "Terrestrial Surface Conditions Control",
                                            "View Control",
                                            "Sensor Control",
                                            "Motion Tracker Control",
                                            "Earth Reference Model Definition",
                                            "Trajectory Definition",
                                            "View Definition",
                                            "Collision Detection Segment Definition",
                                            "Collision Detection Volume Definition",
                                            "HAT/HOT Request",
                                            "Line of Sight Segment Request",
                                            "Line of Sight Vector Request",
                                            "Position Request",
                                            "Environmental Conditions Request",
                                            "Symbol Surface Definition",
                                            "Symbol Text Definition",
                                            "Symbol Circle Definition",
                                            "Symbol Line Definition",
                                            "Symbol Clone",
                                            "Symbol Control",
                                            "Short Symbol Control"};
    static const char* const kIgToHost[] = {"Start of Frame",
                                            "HAT/HOT Response",
                                            "HAT/HOT Extended Response",
                                            "Line of Sight Response",
                                            "Line of Sight Extended Response",
                                            "Sensor Response",
                                            "Sensor Extended Response",
                                            "Position Response",
                                            "Weather Conditions Response",
                                            "Aerosol Concentration Response",
                                            "Maritime Surface Conditions Response",
                                            "Terrestrial Surface Conditions Response",
                                            "Collision Detection Segment Notification",
                                            "Collision Detection Volume Notification",
                                            "Animation Stop Notification",
                                            "Event Notification",
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
