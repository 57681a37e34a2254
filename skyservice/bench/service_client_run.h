// SPDX-License-Identifier: MIT
// One timed run of sky-service-bench: a fresh libskyclient client subscribes (shared memory or zero-copy
// Vulkan), takes `warmup` frames untimed, then `frames` frames timed on its own clock.
//
// Render on request (the service's render_rate_hz 0): per frame the eye moves one 60 Hz step along its
// heading, then set_view, request_frame, wait_frame, acquire_frame, read (shared memory: one byte per
// 4 KiB page of the pixels and shadow map, so that the pages are really fetched; zero-copy: wait for the
// service's timeline semaphore where it exports one), release_frame. Latency = set_view -> read. A path
// of poses (the flight path) replaces the straight line.
// At the service's own rate: the view is set once and the client only waits, acquires, reads, releases.
#pragma once

#include "skyservice/bench/service_report.h"
#include "skyservice/ipc/shm_layout.h"

#include <string>
#include <sys/types.h>
#include <vector>

namespace sky
{

struct ServiceRunSettings
{
    std::string socketPath;
    pid_t daemonPid = -1; ///< for its CPU time (/proc)
    BenchScene scene;
    uint32_t width = 320, height = 180;
    std::string transport = "shm"; ///< "shm" or "vulkan"
    uint32_t layers = 1u << SKY_LAYER_DISPLAY; ///< shm: the layers subscribed (bit k = SKY_LAYER_k); each is read
    uint32_t frames = 300, warmup = 30;
    double speedMps = 250;      ///< request mode: eye speed along its heading
    /// Request mode: when not empty, the eye of each timed frame (frames = its size; the warm-up frames
    /// hold its first pose) instead of the scene's pose moved at speedMps.
    std::vector<EyePose> path;
    bool onRequest = true;      ///< false: the service renders at its own rate, the client only waits
    double frameTimeoutS = 120; ///< longest wait for one frame
};

/**
 * @param[in] s what to run.
 * @param[out] out the measurements (width, height, transport filled in).
 * @param[out] error on failure, the step that failed (subscribe, set_view, a frame not delivered, ...).
 **********************************************************************/
bool runServiceClient(const ServiceRunSettings& s, ServiceRunResult& out, std::string& error);

} // namespace sky
