// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_frame_times.h"

#include <chrono>

namespace sky
{
namespace
{

// The service keeps its last 16 frames: read often enough to see each even at 3000 per second, seldom
// enough that the reads cost the daemon's control thread little.
constexpr auto kReadEvery = std::chrono::milliseconds(5);

} // namespace

bool DaemonFrameTimesReader::start(const std::string& socketPath, std::string& error)
{
    if (!connection_.open(socketPath, "sky-service-bench-frame-times", error))
        return false;
    stop_ = false;
    thread_ = std::thread(
        [this]
        {
            while (!stop_)
            {
                readOnce();
                std::this_thread::sleep_for(kReadEvery);
            }
        });
    return true;
}

void DaemonFrameTimesReader::readOnce()
{
    nlohmann::json status;
    std::string error;
    const bool ok = readServiceStatus(connection_.get(), status, error);
    std::lock_guard<std::mutex> lock(mutex_);
    if (!ok)
    {
        if (error_.empty())
            error_ = error;
        return;
    }
    if (!status.contains("recent_frames") || !status["recent_frames"].is_array())
        return;
    published_ = true;
    for (const nlohmann::json& f : status["recent_frames"])
    {
        DaemonFrameTimes t;
        t.frameMs = f.value("ms", 0.0);
        t.publishMs = f.value("publish_ms", 0.0);
        t.setupMs = f.value("setup_ms", -1.0);
        if (f.contains("gpu_ms") && f["gpu_ms"].is_object())
            for (const auto& [pass, ms] : f["gpu_ms"].items())
                if (ms.is_number())
                    t.gpuMs[pass] = ms.get<double>();
        times_[f.value("id", uint64_t(0))] = std::move(t);
    }
}

void DaemonFrameTimesReader::stopThread()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
}

std::map<uint64_t, DaemonFrameTimes> DaemonFrameTimesReader::finish(bool& published, std::string& error)
{
    stopThread();
    if (connection_.get() != nullptr)
        readOnce();
    std::lock_guard<std::mutex> lock(mutex_);
    published = published_;
    error = error_;
    return std::move(times_);
}

} // namespace sky
