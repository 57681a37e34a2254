// SPDX-License-Identifier: MIT
#include "skyservice/service/signals.h"

#include <csignal>
#include <ctime>
#include <pthread.h>

namespace sky
{
namespace
{

sigset_t serviceSignals()
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGHUP);
    return set;
}

}  // namespace

void blockServiceSignals()
{
    sigset_t set = serviceSignals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::signal(SIGPIPE, SIG_IGN);
}

void SignalWatcher::start(std::function<void(int)> onSignal)
{
    stop_ = false;
    thread_ = std::thread([this, onSignal = std::move(onSignal)] {
        sigset_t set = serviceSignals();
        // Polls the stop flag every 100 ms: a shutdown never waits longer than that for this thread.
        const timespec timeout{0, 100 * 1000 * 1000};
        while (!stop_.load())
        {
            siginfo_t info{};
            int signo = sigtimedwait(&set, &info, &timeout);
            if (signo > 0)
                onSignal(signo);
        }
    });
}

void SignalWatcher::stop()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
}

}  // namespace sky
