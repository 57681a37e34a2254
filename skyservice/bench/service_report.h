// SPDX-License-Identifier: MIT
// What sky-service-bench measured, and its two renderings: a JSON document and a table for humans.
#pragma once

#include "skyservice/bench/bench_report.h"

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sky
{

/// One scene at one size through one transport: what the client got, and what the daemon spent.
struct ServiceRunResult
{
    uint32_t width = 0, height = 0;
    std::string transport;           ///< "shm" or "vulkan"
    bool timelineSemaphore = false;  ///< vulkan: the client waited on the service's semaphore per frame
    uint32_t frames = 0;             ///< frames in hand during the timed part
    uint32_t torn = 0;               ///< of those, released as torn (the service rewrote the slot meanwhile)
    uint64_t skipped = 0;            ///< rate mode: frames published that the client never held (id gaps)
    double elapsedS = 0;             ///< client clock, first timed frame asked for (or waited on) to last in hand
    double deliveredFps = 0;         ///< frames / elapsedS
    std::vector<double> latencyMs;   ///< request mode: set_view -> frame in hand (pixels read), per frame
    std::vector<double> intervalMs;  ///< between consecutive frames in hand, per frame after the first
    std::vector<double> inHandS;     ///< request mode: when each frame was in hand (s since the first timed set_view)
    std::vector<uint64_t> frameIds;  ///< request mode: each timed frame's id
    uint64_t daemonFrames = 0;       ///< frames the daemon rendered during the timed part (status frames_rendered)
    double daemonCpuS = -1;          ///< the daemon's CPU time during the timed part (all threads; -1 unknown)
    double daemonCpuMsPerFrame = -1; ///< daemonCpuS / daemonFrames (ms; -1 unknown)
    nlohmann::json daemonFrameMs;    ///< status "frame_ms" right after the timed part (its last 128 frames)
};

/// One scene: its daemon's runs, and the SM clock around them.
struct ServiceSceneResult
{
    BenchScene scene;
    std::string smClockStartMhz = "n/a", smClockEndMhz = "n/a"; ///< nvidia-smi clocks.sm, or "n/a"
    std::vector<ServiceRunResult> runs;
};

struct ServiceBenchRun
{
    std::string deviceName, driver; ///< the daemon's, from its status
    std::string daemonBinary;
    uint32_t frames = 0, warmup = 0;
    double speedMps = 0;     ///< eye speed along its heading (request mode; 60 Hz steps)
    double renderRateHz = 0; ///< 0: the client asks for every frame; > 0: the daemon's own rate
    uint32_t shadowMapSize = 0;
    std::vector<std::string> layers; ///< what each subscription asked for
    std::vector<ServiceSceneResult> scenes;
};

/// The whole run as JSON: settings, and per scene and run the summaries (median, p95, p99, ...).
nlohmann::json serviceBenchToJson(const ServiceBenchRun& run);

/// A readable table: one row per scene, size and transport.
void printServiceBenchTable(std::FILE* out, const ServiceBenchRun& run);

} // namespace sky
