// SPDX-License-Identifier: MIT
// Loads weather snapshot files off the render thread: one worker reads and validates each queued file
// (WeatherTimeline::loadFile: checksums, sizes, grid) and hands the result to a callback. The render
// thread never waits for a load; the daemon swaps a good timeline in at the next frame boundary.
#pragma once

#include "weather_ingest/weather_timeline.h"

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace sky
{

class WeatherLoader
{
public:
    /// `timeline` is null when the file was refused; `error` then says why (names the file).
    using Done = std::function<void(const std::string& path, std::shared_ptr<const WeatherTimeline> timeline,
                                    const std::string& error)>;

    WeatherLoader() = default;
    WeatherLoader(const WeatherLoader&) = delete;
    WeatherLoader& operator=(const WeatherLoader&) = delete;
    ~WeatherLoader() { stop(); }

    void start(Done done);
    /// Queues a file (a path already queued is not queued twice). Returns at once.
    void enqueue(const std::string& path);
    /// Finishes the file in progress, drops the rest, joins.
    void stop();

private:
    void run();

    Done done_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::string> queue_;
    bool stop_ = false;
    std::thread thread_;
};

}  // namespace sky
