// SPDX-License-Identifier: MIT
// Where the daemon's time went, frame by frame: a second connection reads the service's status every few
// milliseconds beside the frame loop and keeps each published frame's `recent_frames` entry (PROTOCOL.md
// `status`: the frame's wall-clock time, its copy into shared memory, the GPU time of each pass).
#pragma once

#include "skyservice/bench/service_session.h"

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace sky
{

/// One published frame's times as the daemon measured them (ms).
struct DaemonFrameTimes
{
    double frameMs = 0;   ///< submission to publication, wall clock
    double publishMs = 0; ///< the copy into the shared-memory ring and the zero-copy export
    double setupMs = -1;  ///< the CPU's preparation of the frame (-1: a daemon that does not say)
    std::map<std::string, double> gpuMs; ///< per pass ("march", "reconstruct", "composite", "sky", "total", ...)
};

class DaemonFrameTimesReader
{
  public:
    DaemonFrameTimesReader() = default;
    DaemonFrameTimesReader(const DaemonFrameTimesReader&) = delete;
    DaemonFrameTimesReader& operator=(const DaemonFrameTimesReader&) = delete;
    ~DaemonFrameTimesReader() { stopThread(); }

    /// Connects and starts reading status in a thread of its own.
    bool start(const std::string& socketPath, std::string& error);

    /**
     * Reads status once more, stops the thread and hands over what it kept.
     *
     * @param[out] published false when the service's status has no `recent_frames` (an older daemon).
     * @param[out] error the first failure of the thread's reads, if any ("" otherwise).
     * @return the times by frame id.
     **********************************************************************/
    std::map<uint64_t, DaemonFrameTimes> finish(bool& published, std::string& error);

  private:
    void readOnce();
    void stopThread();

    ServiceConnection connection_;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    std::mutex mutex_;
    std::map<uint64_t, DaemonFrameTimes> times_;
    bool published_ = false;
    std::string error_;
};

} // namespace sky
