// SPDX-License-Identifier: MIT
// The renderer's one weather worker: a thread that makes staged weathers and prefetched windows
// (weather_stage.h, window_provider.h) while frames go on.
//
// One thread, started with the renderer, instead of a thread per job: the steady frame path starts no
// threads, and the weather's CPU work (tens of milliseconds per window) never takes more than one core from the
// frames. Jobs run one at a time in the order of their priority, then of submission: a staged weather
// (something the user asked for) goes before a prefetched window (a guess about where the eye goes).
// A job is never abandoned once started; the destructor runs the jobs still queued, then joins.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>

namespace sky
{

enum class WeatherJobPriority
{
    Staged,    ///< a weather the user staged: runs before any queued prefetch
    Prefetch,  ///< a window made ahead of the eye
};

class WeatherWorker
{
public:
    WeatherWorker();
    ~WeatherWorker();
    WeatherWorker(const WeatherWorker&) = delete;
    WeatherWorker& operator=(const WeatherWorker&) = delete;

    /// Queues `job`; its result (or its exception) arrives through the future.
    template <class Result>
    std::future<Result> submit(WeatherJobPriority priority, std::function<Result()> job)
    {
        auto task = std::make_shared<std::packaged_task<Result()>>(std::move(job));
        std::future<Result> out = task->get_future();
        enqueue(priority, [task] { (*task)(); });
        return out;
    }

    /// Jobs taken from the queue since the worker started (tests).
    uint64_t jobsStarted() const;
    /// The worker thread's id (tests: every job runs on it).
    std::thread::id threadId() const { return thread_.get_id(); }

private:
    void enqueue(WeatherJobPriority priority, std::function<void()> job);
    void run();

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> staged_;
    std::deque<std::function<void()>> prefetch_;
    bool stopping_ = false;
    uint64_t jobsStarted_ = 0;
    std::thread thread_;  // last: starts after the queues exist
};

}  // namespace sky
