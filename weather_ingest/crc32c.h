// SPDX-License-Identifier: MIT
// CRC-32C (Castagnoli) checksum used by the snapshot file format.
#pragma once

#include <cstddef>
#include <cstdint>

namespace sky
{

/// CRC-32C (polynomial 0x1EDC6F41, reflected 0x82F63B78; RFC 3720 §12.1) of a byte range.
///
/// @param[in] data bytes to checksum (may be null when size is 0).
/// @param[in] size number of bytes.
/// @param[in] crc  the CRC of the preceding bytes, to checksum a stream in pieces (0 to start).
/// @return the CRC of everything so far. crc32c("123456789", 9) == 0xE3069283 (RFC 3720 check value).
///
/// Uses the SSE4.2 crc32 instruction when the CPU has it (fast enough that checking a 0.25° snapshot is a
/// small part of loading it), else a portable slicing-by-8 table.
uint32_t crc32c(const void* data, size_t size, uint32_t crc = 0);

}  // namespace sky
