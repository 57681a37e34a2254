// SPDX-License-Identifier: MIT
// GRIB framing, checked before ecCodes sees a byte: find each message, check that its sections chain
// exactly to the "7777" end marker, and split GRIB2 multi-field messages (NCEP packs u and v together)
// into single-field messages. ecCodes' own file reader overflows a heap buffer on some damaged inputs
// (found by our fuzzer with ecCodes 2.28), so it is only ever given buffers that passed these checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sky
{

/// One GRIB message found in a byte buffer.
struct GribFrame
{
    size_t offset = 0;                   ///< where the message starts in the buffer
    int edition = 0;                     ///< 1 or 2
    std::vector<std::vector<uint8_t>> fields;  ///< self-contained single-field messages
};

/// Finds and checks the next GRIB message at or after `offset` (bytes before "GRIB" are skipped, as
/// WMO bulletin headers are).
///
/// @param[in] data, size the buffer (the whole file).
/// @param[in,out] offset where to search from; on success, just after the message.
/// @param[out] frame the message, split into fields.
/// @param[out] error on failure why: truncated, bad section length, missing end marker, …
/// @return 1 when a message was found, 0 at the end (no further "GRIB"), -1 on a damaged message.
int nextGribFrame(const uint8_t* data, size_t size, size_t& offset, GribFrame& frame, std::string& error);

}  // namespace sky
