// SPDX-License-Identifier: MIT
#include "weather_ingest/crc32c.h"

#include <array>
#include <cstring>

namespace sky
{
namespace
{

constexpr uint32_t kPolyReflected = 0x82F63B78u;  // RFC 3720 §12.1

using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr Tables makeTables()
{
    Tables t{};
    for (uint32_t i = 0; i < 256; ++i)
    {
        uint32_t c = i;
        for (int k = 0; k < 8; ++k)
            c = (c & 1u) ? (c >> 1) ^ kPolyReflected : c >> 1;
        t[0][i] = c;
    }
    for (uint32_t i = 0; i < 256; ++i)
        for (size_t s = 1; s < 8; ++s)
            t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFFu];
    return t;
}

constexpr Tables kTables = makeTables();

uint32_t crcSoftware(const uint8_t* p, size_t n, uint32_t c)
{
    while (n >= 8)
    {
        uint64_t w;
        std::memcpy(&w, p, 8);  // little-endian host (checked in snapshot_file.cpp)
        w ^= c;
        c = kTables[7][w & 0xFF] ^ kTables[6][(w >> 8) & 0xFF] ^ kTables[5][(w >> 16) & 0xFF] ^
            kTables[4][(w >> 24) & 0xFF] ^ kTables[3][(w >> 32) & 0xFF] ^ kTables[2][(w >> 40) & 0xFF] ^
            kTables[1][(w >> 48) & 0xFF] ^ kTables[0][w >> 56];
        p += 8;
        n -= 8;
    }
    while (n--)
        c = (c >> 8) ^ kTables[0][(c ^ *p++) & 0xFFu];
    return c;
}

#if defined(__x86_64__)
__attribute__((target("sse4.2"))) uint32_t crcHardware(const uint8_t* p, size_t n, uint32_t c)
{
    uint64_t c64 = c;
    while (n >= 8)
    {
        uint64_t w;
        std::memcpy(&w, p, 8);
        c64 = __builtin_ia32_crc32di(c64, w);
        p += 8;
        n -= 8;
    }
    c = static_cast<uint32_t>(c64);
    while (n--)
        c = __builtin_ia32_crc32qi(c, *p++);
    return c;
}

bool hasSse42()
{
    static const bool has = __builtin_cpu_supports("sse4.2");
    return has;
}
#endif

}  // namespace

uint32_t crc32c(const void* data, size_t size, uint32_t crc)
{
    if (size == 0)
        return crc;
    const auto* p = static_cast<const uint8_t*>(data);
    uint32_t c = ~crc;
#if defined(__x86_64__)
    if (hasSse42())
        return ~crcHardware(p, size, c);
#endif
    return ~crcSoftware(p, size, c);
}

}  // namespace sky
