// SPDX-License-Identifier: MIT
// Helpers of the ipc tests: unique names, a temporary folder, and a raw socket client that reads lines
// (with the fds that came along) under a timeout, so that a broken server fails a test, never hangs it.
#pragma once

#include "skyservice/ipc/fd_passing.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <poll.h>
#include <stdexcept>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>

namespace sky::test
{

/// "/skyipc-test-<pid>-<n>": unique per process and call, for shm_open.
inline std::string uniqueShmName()
{
    static std::atomic<int> counter{0};
    return "/skyipc-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

/// A fresh folder under /tmp (short: socket paths are limited to 107 bytes). Removed by the destructor.
struct TempDir
{
    std::string path;
    TempDir()
    {
        char pattern[] = "/tmp/skyipc-XXXXXX";
        if (!::mkdtemp(pattern))
            throw std::runtime_error("mkdtemp failed");
        path = pattern;
    }
    ~TempDir() { std::system(("rm -rf '" + path + "'").c_str()); }
    std::string file(const std::string& name) const { return path + "/" + name; }
};

struct RawClient
{
    int fd = -1;
    std::string input;
    std::vector<int> fds;

    explicit RawClient(const std::string& path)
    {
        fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
        if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
        {
            ::close(fd);
            fd = -1;
        }
    }
    ~RawClient()
    {
        if (fd >= 0)
            ::close(fd);
        for (int f : fds)
            ::close(f);
    }
    bool connected() const { return fd >= 0; }
    bool sendAll(const std::string& data) const
    {
        size_t sent = 0;
        while (sent < data.size())
        {
            ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
            if (n <= 0)
                return false;
            sent += size_t(n);
        }
        return true;
    }
    enum class Read
    {
        Line,
        Closed,
        Timeout
    };
    /// The next line (without newline), or Closed (EOF/reset) / Timeout.
    Read readLine(std::string& line, int timeoutMs = 3000)
    {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeoutMs);
        for (;;)
        {
            size_t nl = input.find('\n');
            if (nl != std::string::npos)
            {
                line = input.substr(0, nl);
                input.erase(0, nl + 1);
                return Read::Line;
            }
            auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0)
                return Read::Timeout;
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, int(left.count())) <= 0)
                continue;
            char buffer[65536];
            ssize_t n = receiveWithFds(fd, buffer, sizeof buffer, fds);
            if (n < 0 && errno == EAGAIN)
                continue;
            if (n <= 0)
                return Read::Closed;
            input.append(buffer, size_t(n));
        }
    }
};

}  // namespace sky::test
