// SPDX-License-Identifier: MIT
// sky-service-bench --flight-path: the real daemon, one libskyclient client flying the flight path
// (service_flight_path.h) with frames asked for back to back, the simulated clock moving one step per
// frame delivered, and a second connection reading the daemon's per-frame times beside it.
#pragma once

#include "skyservice/bench/service_flight_path.h"

#include <string>

namespace sky
{

struct FlightBenchSettings
{
    FlightPathSpec spec;
    uint32_t width = 1920, height = 1080;
    std::string transport = "shm";
    uint32_t warmup = 30; ///< untimed frames at the first pose
    std::string device, daemon;
    std::string dir;      ///< an empty writable folder for the daemon's config, socket and log
    std::string json, csv; ///< where to write the report and the frames ("" = not written)
};

/**
 * Runs the flight path and prints its table on stdout.
 *
 * @return 0, or 1 on a runtime failure (reported on stderr).
 **********************************************************************/
int runFlightPathBench(const FlightBenchSettings& s);

} // namespace sky
