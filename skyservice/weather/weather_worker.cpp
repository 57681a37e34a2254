// SPDX-License-Identifier: MIT
#include "skyservice/weather/weather_worker.h"

namespace sky
{

WeatherWorker::WeatherWorker() : thread_([this] { run(); }) {}

WeatherWorker::~WeatherWorker()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

uint64_t WeatherWorker::jobsStarted() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return jobsStarted_;
}

void WeatherWorker::enqueue(WeatherJobPriority priority, std::function<void()> job)
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        (priority == WeatherJobPriority::Staged ? staged_ : prefetch_).push_back(std::move(job));
    }
    wake_.notify_one();
}

void WeatherWorker::run()
{
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;)
    {
        wake_.wait(lock, [this] { return stopping_ || !staged_.empty() || !prefetch_.empty(); });
        std::deque<std::function<void()>>& queue = !staged_.empty() ? staged_ : prefetch_;
        if (queue.empty())
            return;  // stopping, and every queued job has run
        std::function<void()> job = std::move(queue.front());
        queue.pop_front();
        ++jobsStarted_;
        lock.unlock();
        job();  // a packaged_task: its exceptions go to its future
        lock.lock();
    }
}

}  // namespace sky
