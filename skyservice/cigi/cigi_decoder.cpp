// SPDX-License-Identifier: MIT
#include "skyservice/cigi/cigi_decoder.h"

#include "skyservice/cigi/cigi_fields.h"
#include "skyservice/cigi/cigi_validate.h"

#include <cstdio>
#include <numeric>

namespace sky::cigi
{
namespace
{

// The fixed size of each opcode this IG decodes; 0 for the rest.
uint8_t fixedSize(uint8_t opcode)
{
    switch (opcode)
    {
    case kOpIgControl: return kSizeIgControl;
    case kOpEntityControl: return kSizeEntityControl;
    case kOpCelestialSphereControl: return kSizeCelestialSphereControl;
    case kOpAtmosphereControl: return kSizeAtmosphereControl;
    case kOpEnvironmentalRegionControl: return kSizeEnvironmentalRegionControl;
    case kOpWeatherControl: return kSizeWeatherControl;
    case kOpViewControl: return kSizeViewControl;
    case kOpViewDefinition: return kSizeViewDefinition;
    case kOpEnvironmentalConditionsRequest: return kSizeEnvironmentalConditionsRequest;
    default: return 0;
    }
}

// "<what> (opcode 12, Weather Control) at byte 80"
std::string describe(const std::string& what, uint8_t opcode, size_t offset)
{
    const char* name = opcodeName(opcode);
    return what + " (opcode " + std::to_string(opcode) + (name ? std::string(", ") + name : std::string()) +
           ") at byte " + std::to_string(offset);
}

template <typename Packet>
void keepIfValid(DecodeResult& result, const Packet& packet, std::string& error)
{
    error = validate(packet);
    if (error.empty())
        result.packets.emplace_back(packet);
}

} // namespace

const char* decodeErrorName(DecodeErrorKind kind)
{
    switch (kind)
    {
    case DecodeErrorKind::ShortDatagram: return "short_datagram";
    case DecodeErrorKind::MissingIgControl: return "missing_ig_control";
    case DecodeErrorKind::BadMagic: return "bad_magic";
    case DecodeErrorKind::BadVersion: return "bad_version";
    case DecodeErrorKind::BadSize: return "bad_size";
    case DecodeErrorKind::Truncated: return "truncated";
    case DecodeErrorKind::SizeMismatch: return "size_mismatch";
    case DecodeErrorKind::UnknownOpcode: return "unknown_opcode";
    case DecodeErrorKind::UnexpectedPacket: return "unexpected_packet";
    case DecodeErrorKind::BadValue: return "bad_value";
    case DecodeErrorKind::Count: break;
    }
    return "unknown";
}

uint64_t DecodeCounters::totalErrors() const
{
    return std::accumulate(errors.begin(), errors.end(), uint64_t{0});
}

void Decoder::fail(DecodeResult& result, DecodeErrorKind kind, size_t offset, std::string message)
{
    uint64_t& count = counters_.errors[static_cast<size_t>(kind)];
    result.errors.push_back({kind, offset, std::move(message), count == 0});
    ++count;
}

DecodeResult Decoder::decode(const uint8_t* data, size_t size)
{
    DecodeResult result;
    ++counters_.datagrams;
    const auto drop = [&](DecodeErrorKind kind, std::string message) {
        fail(result, kind, 0, std::move(message));
        ++counters_.datagramsDropped;
        return result;
    };
    if (data == nullptr || size < kSizeIgControl)
        return drop(DecodeErrorKind::ShortDatagram,
                    "datagram of " + std::to_string(size) + " bytes is shorter than an IG Control (24)");
    if (data[0] != kOpIgControl || data[1] != kSizeIgControl)
        return drop(DecodeErrorKind::MissingIgControl,
                    describe("datagram does not begin with a 24-byte IG Control but with a packet", data[0], 0) +
                        " of size " + std::to_string(data[1]));
    constexpr uint8_t kMagicAt = PacketLayout<IgControl>::magicOffset;
    const uint16_t magic = static_cast<uint16_t>(data[kMagicAt] << 8 | data[kMagicAt + 1]);
    if (magic != kByteSwapMagic && magic != 0x0080)
    {
        char text[96];
        std::snprintf(text, sizeof text, "IG Control byte-swap magic 0x%04x is neither 0x8000 nor 0x0080", magic);
        return drop(DecodeErrorKind::BadMagic, text);
    }
    result.order = magic == kByteSwapMagic ? ByteOrder::Big : ByteOrder::Little;
    result.igControl = decodeIgControl(data, result.order);
    if (std::string error = validate(result.igControl); !error.empty())
        return drop(DecodeErrorKind::BadVersion, std::move(error));
    result.accepted = true;
    ++counters_.packetsDecoded;

    size_t offset = kSizeIgControl;
    while (offset < size)
    {
        const uint8_t opcode = data[offset];
        if (size - offset < 2)
        {
            fail(result, DecodeErrorKind::Truncated, offset,
                 describe("a packet header is cut off by the datagram's end", opcode, offset));
            break;
        }
        const uint8_t packetSize = data[offset + 1];
        if (packetSize < 2)
        {
            fail(result, DecodeErrorKind::BadSize, offset,
                 describe("size field " + std::to_string(packetSize) + " is less than 2 for a packet", opcode,
                          offset));
            break;
        }
        if (packetSize > size - offset)
        {
            fail(result, DecodeErrorKind::Truncated, offset,
                 describe("size field " + std::to_string(packetSize) + " runs past the datagram's end (" +
                              std::to_string(size - offset) + " bytes left) for a packet",
                          opcode, offset));
            break;
        }
        decodePacket(result, data + offset, opcode, offset);
        offset += packetSize;
    }
    return result;
}

void Decoder::decodePacket(DecodeResult& result, const uint8_t* packet, uint8_t opcode, size_t offset)
{
    const uint8_t packetSize = packet[1];
    const uint8_t expected = fixedSize(opcode);
    if (opcode == kOpIgControl)
    {
        fail(result, DecodeErrorKind::UnexpectedPacket, offset, describe("a second IG Control", opcode, offset));
        return;
    }
    if (expected == 0)
    {
        const char* name = opcodeName(opcode);
        if (name == nullptr)
            fail(result, DecodeErrorKind::UnknownOpcode, offset,
                 describe("a packet CIGI 3.3 does not define", opcode, offset));
        else if (opcode >= kOpStartOfFrame && opcode < 201)
            fail(result, DecodeErrorKind::UnexpectedPacket, offset,
                 describe("an IG-to-host packet from the host", opcode, offset));
        else
            ++counters_.packetsIgnored;
        return;
    }
    if (packetSize != expected)
    {
        fail(result, DecodeErrorKind::SizeMismatch, offset,
             describe("size field " + std::to_string(packetSize) + " is not " + std::to_string(expected) +
                          " for a packet",
                      opcode, offset));
        return;
    }
    const ByteOrder order = result.order;
    std::string error;
    switch (opcode)
    {
    case kOpEntityControl: keepIfValid(result, decodeEntityControl(packet, order), error); break;
    case kOpCelestialSphereControl: keepIfValid(result, decodeCelestialSphereControl(packet, order), error); break;
    case kOpAtmosphereControl: keepIfValid(result, decodeAtmosphereControl(packet, order), error); break;
    case kOpEnvironmentalRegionControl:
        keepIfValid(result, decodeEnvironmentalRegionControl(packet, order), error);
        break;
    case kOpWeatherControl: keepIfValid(result, decodeWeatherControl(packet, order), error); break;
    case kOpViewControl: keepIfValid(result, decodeViewControl(packet, order), error); break;
    case kOpViewDefinition: keepIfValid(result, decodeViewDefinition(packet, order), error); break;
    case kOpEnvironmentalConditionsRequest:
        keepIfValid(result, decodeEnvironmentalConditionsRequest(packet, order), error);
        break;
    default: break;
    }
    if (error.empty())
        ++counters_.packetsDecoded;
    else
        fail(result, DecodeErrorKind::BadValue, offset, error + " (byte " + std::to_string(offset) + ")");
}

} // namespace sky::cigi
