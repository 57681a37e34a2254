// SPDX-License-Identifier: MIT
// Splits a host datagram into CIGI 3.3 packets and keeps the good ones. A datagram must begin with IG
// Control, whose byte-swap magic says the sender's byte order; every later packet is read in that order.
// Nothing here throws or reads past the datagram, whatever the bytes: a bad packet is counted under its
// kind, named in the result, and skipped (or, when its size cannot be trusted, ends the datagram).
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace sky::cigi
{

/// What can be wrong with a datagram or one of its packets.
enum class DecodeErrorKind : uint8_t
{
    ShortDatagram,     ///< fewer bytes than an IG Control: the datagram is dropped
    MissingIgControl,  ///< the first packet is not a 24-byte IG Control: dropped
    BadMagic,          ///< IG Control's byte-swap magic is neither 0x8000 nor 0x0080: dropped
    BadVersion,        ///< IG Control's major version is not 3: dropped
    BadSize,           ///< a packet's size field is < 2: nothing after it can be found, the rest is dropped
    Truncated,         ///< a packet's size runs past the datagram's end: the rest is dropped
    SizeMismatch,      ///< a known packet whose size field is not its fixed size: that packet is skipped
    UnknownOpcode,     ///< an opcode CIGI 3.3 does not define: skipped by its size
    UnexpectedPacket,  ///< an IG->host packet, or a second IG Control, from the host: skipped
    BadValue,          ///< NaN, infinity or a value outside the ICD's range: that packet is skipped
    Count,
};
constexpr size_t kDecodeErrorKindCount = static_cast<size_t>(DecodeErrorKind::Count);

/// Short snake_case name of a kind, for logs and the daemon's status reply ("bad_magic").
const char* decodeErrorName(DecodeErrorKind kind);

/// Running totals since the decoder was made; plain data the daemon can copy into its status reply.
struct DecodeCounters
{
    uint64_t datagrams = 0;          ///< datagrams given to decode()
    uint64_t datagramsDropped = 0;   ///< of which nothing was applied (bad header)
    uint64_t packetsDecoded = 0;     ///< good packets handed on (IG Control included)
    uint64_t packetsIgnored = 0;     ///< packets this IG does not use (Component Control, user-defined, ...)
    std::array<uint64_t, kDecodeErrorKindCount> errors{};  ///< indexed by DecodeErrorKind

    uint64_t error(DecodeErrorKind kind) const { return errors[static_cast<size_t>(kind)]; }
    uint64_t totalErrors() const;
};

struct DecodeError
{
    DecodeErrorKind kind = DecodeErrorKind::ShortDatagram;
    size_t offset = 0;         ///< byte offset of the offending packet in the datagram
    std::string message;       ///< names what was wrong ("Weather Control: Coverage 140 is outside 0..100")
    bool firstOfKind = false;  ///< the first error of this kind since the decoder was made: log it
};

/// The host packets this IG acts on (IG Control is kept apart: there is exactly one per datagram).
using HostPacket = std::variant<EntityControl, CelestialSphereControl, AtmosphereControl, EnvironmentalRegionControl,
                                WeatherControl, ViewControl, ViewDefinition, EnvironmentalConditionsRequest>;

struct DecodeResult
{
    bool accepted = false;  ///< the header was good: igControl and packets may be applied
    ByteOrder order = ByteOrder::Big;  ///< the sender's byte order (meaningful when accepted)
    IgControl igControl;
    std::vector<HostPacket> packets;  ///< the good packets, in datagram order
    std::vector<DecodeError> errors;
};

/// Stateless apart from its counters; one per socket.
class Decoder
{
public:
    DecodeResult decode(const uint8_t* data, size_t size);
    const DecodeCounters& counters() const { return counters_; }

private:
    void fail(DecodeResult& result, DecodeErrorKind kind, size_t offset, std::string message);
    void decodePacket(DecodeResult& result, const uint8_t* packet, uint8_t opcode, size_t offset);

    DecodeCounters counters_;
};

} // namespace sky::cigi
