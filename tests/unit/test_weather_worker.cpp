// SPDX-License-Identifier: MIT
// The renderer's one weather worker (skyservice/weather/weather_worker.h): every job runs on its one
// thread, one at a time; a staged weather's job goes before prefetches queued earlier; a job's exception
// reaches its future; the destructor runs what is still queued.
#include "skyservice/weather/weather_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace sky;

namespace
{

/// Blocks the worker until opened, so that the jobs submitted meanwhile queue up.
struct Gate
{
    std::promise<void> open;
    std::shared_future<void> opened = open.get_future().share();
};

}  // namespace

TEST(WeatherWorker, RunsEveryJobOnItsOneThreadOneAtATime)
{
    WeatherWorker w;
    std::atomic<int> running{0};
    std::atomic<int> mostAtOnce{0};
    std::vector<std::future<std::thread::id>> jobs;
    for (int i = 0; i < 12; ++i)
    {
        const WeatherJobPriority p = i % 2 ? WeatherJobPriority::Staged : WeatherJobPriority::Prefetch;
        jobs.push_back(w.submit<std::thread::id>(p, [&] {
            const int now = ++running;
            int seen = mostAtOnce.load();
            while (now > seen && !mostAtOnce.compare_exchange_weak(seen, now))
            {
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            --running;
            return std::this_thread::get_id();
        }));
    }
    for (std::future<std::thread::id>& j : jobs)
    {
        const std::thread::id id = j.get();
        EXPECT_EQ(id, w.threadId());
        EXPECT_NE(id, std::this_thread::get_id());
    }
    EXPECT_EQ(mostAtOnce.load(), 1);
    EXPECT_EQ(w.jobsStarted(), 12u);
}

TEST(WeatherWorker, AStagedWeatherGoesBeforeQueuedPrefetches)
{
    Gate gate;  // what the jobs use is made before the worker, so it outlives them
    std::mutex orderMutex;
    std::string order;
    WeatherWorker w;
    auto note = [&](char c) {
        std::lock_guard<std::mutex> lock(orderMutex);
        order += c;
        return 0;
    };
    std::promise<void> started;
    std::future<int> blocker = w.submit<int>(WeatherJobPriority::Prefetch, [&] {
        started.set_value();
        gate.opened.wait();
        return note('b');
    });
    started.get_future().wait();  // the worker runs the blocker: the next three queue behind it
    std::future<int> p1 = w.submit<int>(WeatherJobPriority::Prefetch, [&] { return note('p'); });
    std::future<int> p2 = w.submit<int>(WeatherJobPriority::Prefetch, [&] { return note('q'); });
    std::future<int> s1 = w.submit<int>(WeatherJobPriority::Staged, [&] { return note('s'); });
    gate.open.set_value();
    blocker.get();
    p1.get();
    p2.get();
    s1.get();
    EXPECT_EQ(order, "bspq") << "the running job finishes; then the staged one; then the prefetches in order";
}

TEST(WeatherWorker, AJobsExceptionReachesItsFutureAndTheWorkerGoesOn)
{
    WeatherWorker w;
    std::future<int> bad = w.submit<int>(WeatherJobPriority::Staged, []() -> int { throw std::runtime_error("no"); });
    std::future<int> good = w.submit<int>(WeatherJobPriority::Staged, [] { return 7; });
    EXPECT_THROW(bad.get(), std::runtime_error);
    EXPECT_EQ(good.get(), 7);
}

TEST(WeatherWorker, TheDestructorRunsTheJobsStillQueued)
{
    std::atomic<int> ran{0};
    std::future<int> last;
    {
        Gate gate;  // before the worker: it must outlive the jobs, which the worker's destructor runs
        WeatherWorker w;
        std::future<int> blocker = w.submit<int>(WeatherJobPriority::Prefetch, [&] {
            gate.opened.wait();
            return ++ran;
        });
        for (int i = 0; i < 3; ++i)
            last = w.submit<int>(WeatherJobPriority::Prefetch, [&] { return ++ran; });
        gate.open.set_value();
    }
    EXPECT_EQ(ran.load(), 4);
    EXPECT_EQ(last.get(), 4);
}
