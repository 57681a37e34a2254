// SPDX-License-Identifier: MIT
#include "skyservice/service/weather_loader.h"

#include <algorithm>

namespace sky
{

void WeatherLoader::start(Done done)
{
    done_ = std::move(done);
    stop_ = false;
    thread_ = std::thread([this] { run(); });
}

void WeatherLoader::enqueue(const std::string& path)
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (std::find(queue_.begin(), queue_.end(), path) == queue_.end())
            queue_.push_back(path);
    }
    wake_.notify_one();
}

void WeatherLoader::stop()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        queue_.clear();
    }
    wake_.notify_one();
    if (thread_.joinable())
        thread_.join();
}

void WeatherLoader::run()
{
    for (;;)
    {
        std::string path;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
            if (stop_)
                return;
            path = queue_.front();
            queue_.pop_front();
        }
        auto timeline = std::make_shared<WeatherTimeline>();
        std::string error;
        if (timeline->loadFile(path, error))
            done_(path, timeline, "");
        else
            done_(path, nullptr, error.empty() ? path + ": could not be loaded" : error);
    }
}

}  // namespace sky
