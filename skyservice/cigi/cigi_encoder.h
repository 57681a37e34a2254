// SPDX-License-Identifier: MIT
// Builds the IG's datagrams to the host: Start of Frame first (every frame), then the responses of that
// frame (Weather Conditions, Aerosol Concentration). The byte order is the IG's choice, stated by the
// byte-swap magic in Start of Frame; replying in the host's own order spares the host a swap.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <vector>

namespace sky::cigi
{

/// A time in seconds as CIGI's 10 µs timestamp ticks, wrapping modulo 2^32 (about 11.9 hours) as the ICD
/// lets it. Negative or non-finite times give 0.
uint32_t timestampTicks10us(double seconds);

class IgEncoder
{
public:
    explicit IgEncoder(ByteOrder order = nativeByteOrder()) : order_(order) {}

    void setByteOrder(ByteOrder order) { order_ = order; }
    ByteOrder byteOrder() const { return order_; }

    /// Starts the next frame's datagram with a Start of Frame: the IG frame number counts up from 0 by one
    /// per call (wrapping), `lastHostFrame` echoes the last IG Control's Host Frame Number, `timeS` is the
    /// IG's time (timestamp valid). `sof` supplies the other fields (mode, status, database).
    void beginFrame(uint32_t lastHostFrame, double timeS, StartOfFrame sof = {});
    void add(const WeatherConditionsResponse& p) { encode(p, order_, datagram_); }
    void add(const AerosolConcentrationResponse& p) { encode(p, order_, datagram_); }

    /// The datagram built since beginFrame (empty before the first).
    const std::vector<uint8_t>& datagram() const { return datagram_; }
    /// The IG frame number the last beginFrame wrote.
    uint32_t igFrameNumber() const { return nextFrame_ - 1; }

private:
    ByteOrder order_;
    uint32_t nextFrame_ = 0;
    std::vector<uint8_t> datagram_;
};

} // namespace sky::cigi
