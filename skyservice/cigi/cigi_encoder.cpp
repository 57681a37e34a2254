// SPDX-License-Identifier: MIT
#include "skyservice/cigi/cigi_encoder.h"

#include <cmath>

namespace sky::cigi
{

uint32_t timestampTicks10us(double seconds)
{
    if (!std::isfinite(seconds) || seconds <= 0)
        return 0;
    const double ticks = std::fmod(std::floor(seconds * 1.0e5), 4294967296.0);
    return static_cast<uint32_t>(ticks);
}

void IgEncoder::beginFrame(uint32_t lastHostFrame, double timeS, StartOfFrame sof)
{
    datagram_.clear();
    sof.majorVersion = kCigiMajorVersion;
    sof.minorVersion = kCigiMinorVersion;
    sof.igFrameNumber = nextFrame_++;
    sof.lastHostFrameNumber = lastHostFrame;
    sof.timestamp10us = timestampTicks10us(timeS);
    sof.timestampValid = true;
    encode(sof, order_, datagram_);
}

} // namespace sky::cigi
