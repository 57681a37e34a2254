// SPDX-License-Identifier: MIT
// What sky-service-bench --flight-path measured along the path, and its renderings: frames per second
// over the whole path, the slowest 1 % of frames, and the slowest second of simulated flight with where
// the eye was and where the time went there (the daemon's passes, its copy into shared memory, the
// client's side), as JSON, a table and, frame by frame, CSV.
#pragma once

#include "skyservice/bench/service_flight_path.h"
#include "skyservice/bench/service_frame_times.h"
#include "skyservice/bench/service_report.h"

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sky
{

/// Means over a set of frames (ms); a daemon figure is -1 where no frame of the set has it.
struct FlightFrameMeans
{
    uint32_t frames = 0;
    uint32_t framesWithDaemonTimes = 0;
    double fps = 0;           ///< frames / the client's wall time for them
    double clientFrameMs = 0; ///< set_view -> frame in hand (pixels read)
    double daemonFrameMs = -1, publishMs = -1;
    double setupMs = -1; ///< the daemon's CPU preparation of the frame (status recent_frames setup_ms)
    double marchMs = -1, reconstructMs = -1, compositeMs = -1, skyMs = -1, gpuTotalMs = -1;
};

/// The slowest stretch of one simulated second (the most client wall time for its frames).
struct FlightWindow
{
    uint32_t firstFrame = 0, frames = 0;
    double startS = 0;   ///< simulated time of its first frame
    double wallS = 0;    ///< the client's wall time for its frames
    EyePose pose;        ///< the eye at its first frame
    bool insideCloudLayer = false;
    FlightFrameMeans means;
};

/// Everything the flight path's JSON and table say.
struct FlightReport
{
    std::string deviceName, driver, daemonBinary, transport;
    uint32_t width = 0, height = 0, warmup = 0;
    FlightPathSpec spec;
    std::string smClockStartMhz = "n/a", smClockEndMhz = "n/a";
    uint32_t frames = 0, torn = 0;
    double elapsedS = 0, fps = 0;
    double frameMsMedian = 0, frameMsP99 = 0, frameMsMax = 0;
    double slowestPercentMeanMs = 0; ///< mean of the slowest 1 % of frames (at least one)
    bool daemonTimesPublished = false; ///< the daemon's status has `recent_frames`
    FlightFrameMeans whole, insideCloudLayer, outsideCloudLayer;
    FlightWindow slowestWindow;
    std::vector<CloudLayerStretch> cloudLayers;
};

/// What the analysis needs: the path, the client's run over it and the daemon's per-frame times.
struct FlightInputs
{
    std::vector<FlightPose> poses;
    std::vector<bool> insideCloudLayer; ///< per pose
    std::vector<CloudLayerStretch> cloudLayers;
    ServiceRunResult run;               ///< request mode with the path: latencyMs, inHandS, frameIds per frame
    std::map<uint64_t, DaemonFrameTimes> daemonTimes;
    bool daemonTimesPublished = false;
};

/// The figures of a run over the path (run.frames == poses.size()). `report`'s settings
/// (device, sizes, spec, clocks) are kept; the figures are filled in.
void analyzeFlight(const FlightInputs& in, FlightReport& report);

nlohmann::json flightReportToJson(const FlightReport& report);

void printFlightReport(std::FILE* out, const FlightReport& report);

/// One line per frame: time, pose, inside a layer, client and daemon times (ms).
bool writeFlightFramesCsv(const std::string& path, const FlightInputs& in, std::string& error);

} // namespace sky
