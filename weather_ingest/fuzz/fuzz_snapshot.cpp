// SPDX-License-Identifier: MIT
// libFuzzer target: the snapshot reader must reject any byte string cleanly, and whatever it accepts
// must be a valid snapshot that the timeline can sample.
#include "weather_ingest/snapshot_file.h"
#include "weather_ingest/weather_timeline.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::vector<sky::WeatherSnapshot> snapshots;
    std::string error;
    if (!sky::parseSnapshotBytes(data, size, "fuzz", snapshots, error))
    {
        if (error.empty() || !snapshots.empty())
            std::abort();  // a failure must say why and return nothing
        return 0;
    }
    for (const sky::WeatherSnapshot& s : snapshots)
        if (!sky::validateSnapshot(s, error))
            std::abort();
    sky::WeatherTimeline timeline;
    if (timeline.setSnapshots(snapshots, error))
        (void)timeline.sample(double(timeline.firstTimeUnixS()) + 1.5);
    return 0;
}
