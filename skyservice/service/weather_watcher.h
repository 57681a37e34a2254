// SPDX-License-Identifier: MIT
// Watches the weather folder (inotify) for snapshot files: a file whose name ends in ".skywx" (the
// extension sky-ingest writes) that was closed after writing (IN_CLOSE_WRITE) or renamed into the
// folder (IN_MOVED_TO: sky-ingest writes "<name>.tmp.<pid>" and renames it, so a reader never sees
// half a file). Each such file is reported once per event; loading it is the WeatherLoader's job.
// Anything but a regular file (a FIFO, a link, a folder with that name) is ignored.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <thread>

namespace sky
{

class WeatherWatcher
{
public:
    WeatherWatcher() = default;
    WeatherWatcher(const WeatherWatcher&) = delete;
    WeatherWatcher& operator=(const WeatherWatcher&) = delete;
    ~WeatherWatcher() { stop(); }

    /// Starts watching `dir` (which must exist); `onFile(absolutePath)` runs on the watcher's thread.
    /// False + error naming the folder.
    bool start(const std::string& dir, std::function<void(const std::string&)> onFile, std::string& error);
    /// Joins the thread (within ~100 ms) and closes the inotify descriptor. Safe to call twice.
    void stop();
    const std::string& dir() const { return dir_; }

private:
    std::string dir_;
    int fd_ = -1;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

/// True for the names the watcher reports ("x.skywx", not "x.skywx.tmp.12").
bool isSnapshotFileName(const std::string& name);

}  // namespace sky
