// SPDX-License-Identifier: MIT
// libFuzzer target: GRIB bytes through ecCodes, our decoding (scanning modes, bitmaps, grid checks) and
// the GFS/ECMWF mapping, strict and lenient. Any IngestError is a correct outcome; a crash is not.
#include "weather_ingest/grib_fields.h"
#include "weather_ingest/grib_mapping.h"
#include "weather_ingest/ingest_error.h"
#include "weather_ingest/snapshot_file.h"

#include <cstdlib>
#include <map>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0)
        return 0;  // fmemopen refuses empty buffers; the CLI rejects empty files before ecCodes
    try
    {
        sky::GribFile file("fuzz.grib2", data, size);
        // A small cell limit keeps each run fast; the limit path itself is part of what is fuzzed.
        const std::vector<sky::GribRecord> records = sky::readGribRecords(file, 1u << 16, {});
        std::map<int64_t, std::vector<const sky::GribRecord*>> byTime;
        for (const sky::GribRecord& r : records)
            byTime[r.info.validTimeUnixS].push_back(&r);
        for (const bool lenient : {false, true})
            for (const auto& [time, group] : byTime)
            {
                sky::MappingOptions options;
                options.lenient = lenient;
                options.keepLevelFields = true;
                std::vector<std::string> warnings;
                try
                {
                    const sky::WeatherSnapshot s = sky::mapGribRecords(group, options, warnings);
                    std::string error;
                    if (!sky::validateSnapshot(s, error))
                        std::abort();  // the mapping must never produce an invalid snapshot
                }
                catch (const sky::IngestError&)
                {
                }
            }
    }
    catch (const sky::IngestError&)
    {
    }
    return 0;
}
