// SPDX-License-Identifier: MIT
#include "skyservice/service/weather_watcher.h"

#include <cerrno>
#include <cstring>
#include <poll.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sky
{

bool isSnapshotFileName(const std::string& name)
{
    static const std::string ext = ".skywx";
    return name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0 && name[0] != '.';
}

bool WeatherWatcher::start(const std::string& dir, std::function<void(const std::string&)> onFile, std::string& error)
{
    stop();
    fd_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (fd_ < 0)
    {
        error = "weather_dir " + dir + ": inotify: " + std::strerror(errno);
        return false;
    }
    if (inotify_add_watch(fd_, dir.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO | IN_ONLYDIR) < 0)
    {
        error = "weather_dir " + dir + ": " + std::strerror(errno);
        ::close(fd_);
        fd_ = -1;
        return false;
    }
    dir_ = dir;
    stop_ = false;
    thread_ = std::thread([this, onFile = std::move(onFile)] {
        alignas(inotify_event) char buffer[16384];
        while (!stop_.load())
        {
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0)
                continue;
            ssize_t n = ::read(fd_, buffer, sizeof buffer);
            for (ssize_t at = 0; n > 0 && at < n;)
            {
                const auto* e = reinterpret_cast<const inotify_event*>(buffer + at);
                at += ssize_t(sizeof(inotify_event) + e->len);
                if (e->len == 0 || (e->mask & IN_ISDIR))
                    continue;
                std::string name(e->name);
                // Only regular files go to the loader (a FIFO renamed in must not even be queued).
                struct stat st{};
                const std::string path = dir_ + "/" + name;
                if (isSnapshotFileName(name) && ::lstat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
                    onFile(path);
            }
        }
    });
    return true;
}

void WeatherWatcher::stop()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
    if (fd_ >= 0)
        ::close(fd_);
    fd_ = -1;
}

}  // namespace sky
