// SPDX-License-Identifier: MIT
// libFuzzer target: the snapshot reader behind a valid header. The input is a whole snapshot file whose
// header the target rewrites to be consistent (magic, version kept in range, payload size, payload and
// header checksums), so the fuzzer's mutations reach the metadata and the declared array sizes that a
// crafted file would carry, instead of stopping at a checksum. Whatever is accepted must validate.
#include "weather_ingest/crc32c.h"
#include "weather_ingest/snapshot_file.h"

#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size < 32)
        return 0;
    std::vector<uint8_t> file(data, data + size);
    static const uint8_t kMagic[8] = {0x89, 'S', 'K', 'Y', 'W', 'X', '\r', '\n'};
    std::memcpy(file.data(), kMagic, 8);
    uint32_t version = 0, count = 0;
    std::memcpy(&version, file.data() + 8, 4);
    std::memcpy(&count, file.data() + 12, 4);
    version = sky::kSnapshotFormatOldestVersion + version % 2;
    count = 1 + count % 3;
    const uint64_t payloadBytes = size - 32;
    const uint32_t payloadCrc = sky::crc32c(file.data() + 32, payloadBytes);
    std::memcpy(file.data() + 8, &version, 4);
    std::memcpy(file.data() + 12, &count, 4);
    std::memcpy(file.data() + 16, &payloadBytes, 8);
    std::memcpy(file.data() + 24, &payloadCrc, 4);
    const uint32_t headerCrc = sky::crc32c(file.data(), 28);
    std::memcpy(file.data() + 28, &headerCrc, 4);

    std::vector<sky::WeatherSnapshot> snapshots;
    std::string error;
    if (!sky::parseSnapshotBytes(file.data(), file.size(), "crafted", snapshots, error))
    {
        if (error.empty() || !snapshots.empty())
            std::abort();
        return 0;
    }
    for (const sky::WeatherSnapshot& s : snapshots)
        if (!sky::validateSnapshot(s, error))
            std::abort();
    return 0;
}
