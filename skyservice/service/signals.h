// SPDX-License-Identifier: MIT
// SIGTERM, SIGINT and SIGHUP for the daemon, without async-signal-safety puzzles: the signals are
// blocked in every thread (blockServiceSignals() before any thread starts, so threads inherit the
// mask) and one watcher thread takes them with sigtimedwait() and calls an ordinary function.
// SIGPIPE is ignored: a client that hangs up must not kill the service (send() then fails with EPIPE).
#pragma once

#include <atomic>
#include <functional>
#include <thread>

namespace sky
{

/// Blocks SIGTERM, SIGINT, SIGHUP in the calling thread (call it first in main's thread) and ignores SIGPIPE.
void blockServiceSignals();

class SignalWatcher
{
public:
    SignalWatcher() = default;
    SignalWatcher(const SignalWatcher&) = delete;
    SignalWatcher& operator=(const SignalWatcher&) = delete;
    ~SignalWatcher() { stop(); }

    /// Starts the thread; `onSignal(signo)` runs on it for every SIGTERM, SIGINT or SIGHUP.
    void start(std::function<void(int)> onSignal);
    /// Joins the thread (within ~100 ms). Safe to call twice.
    void stop();

private:
    std::thread thread_;
    std::atomic<bool> stop_{false};
};

}  // namespace sky
