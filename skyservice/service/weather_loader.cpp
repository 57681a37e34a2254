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
        // An exception escaping this thread would end the process: anything that can still throw
        // (an allocation the file's checked sizes allow but memory does not) is that file's error.
        std::shared_ptr<WeatherTimeline> timeline;
        std::string error;
        bool ok = false;
        try
        {
            timeline = std::make_shared<WeatherTimeline>();
            ok = timeline->loadFile(path, error);
        }
        catch (const std::exception& e)
        {
            error = path + ": " + e.what();
        }
        if (ok)
            done_(path, timeline, "");
        else
            done_(path, nullptr, error.empty() ? path + ": could not be loaded" : error);
    }
}

}  // namespace sky
