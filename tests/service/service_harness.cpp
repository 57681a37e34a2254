// SPDX-License-Identifier: MIT
#include "tests/service/service_harness.h"

#include "skyservice/sky/builtin_weather.h"
#include "weather_ingest/snapshot_file.h"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace skytest
{
namespace
{

int64_t nowMs()
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

std::string serviceBinary() { return SKY_SERVICE_BIN; }

TempDir::TempDir()
{
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/skysvc-XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    if (mkdtemp(buf.data()))
        path = buf.data();
}

TempDir::~TempDir()
{
    std::error_code ec;
    if (!path.empty() && !std::getenv("SKY_KEEP_TEST_DIRS"))
        std::filesystem::remove_all(path, ec);
}

Daemon::~Daemon()
{
    if (pid > 0)
        stop(SIGKILL, 5000);
}

bool Daemon::start(const std::string& folder, const DaemonConfig& c, std::string& error)
{
    dir = folder;
    socketPath = dir + "/service.sock";
    // Unique per test process and folder: tests run in parallel (ctest -j).
    shmName = "/skysvc-test-" + std::to_string(getpid()) + "-" + std::filesystem::path(dir).filename().string();
    configPath = dir + "/service.toml";
    logPath = dir + "/service.log";
    std::ofstream f(configPath);
    f << "[service]\n"
      << "socket_path = \"" << socketPath << "\"\n"
      << (c.defaultShmName ? "" : "shm_name = \"" + shmName + "\"\n")
      << "files_root = \"" << dir << "/frames\"\n"
      << "render_rate_hz = " << c.renderRateHz << "\n"
      << "max_width = 128\nmax_height = 72\n"
      << "quality = \"test\"\n"
      << "log_level = \"" << c.logLevel << "\"\n"
      << "time = \"2026-06-21T12:00:00Z\"\n"
      << "rate = 0\n";
    if (!c.weatherDir.empty())
        f << "weather_dir = \"" << c.weatherDir << "\"\n";
    f << c.extraService << "\n"
      << "[service.view]\nlat = 44.3\nlon = 7.5\nalt = 1500\nwidth = " << c.width << "\nheight = " << c.height
      << "\n\n"
      << c.extraSections << "\n";
    f.close();
    return launch(error);
}

bool Daemon::restart(std::string& error) { return launch(error); }

bool Daemon::launch(std::string& error)
{
    std::filesystem::remove(socketPath);
    pid = fork();
    if (pid == 0)
    {
        int log = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (log >= 0)
        {
            dup2(log, 1);
            dup2(log, 2);
        }
        std::string bin = serviceBinary();
        execl(bin.c_str(), bin.c_str(), "--config", configPath.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    int64_t deadline = nowMs() + 60000;
    while (nowMs() < deadline)
    {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid)
        {
            pid = -1;
            std::ifstream in(logPath);
            error = "daemon exited with " + std::to_string(WEXITSTATUS(status)) + ": " +
                    std::string(std::istreambuf_iterator<char>(in), {});
            return false;
        }
        RawClient probe;
        if (probe.open(socketPath))
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    error = "daemon did not answer hello within 60 s";
    return false;
}

int Daemon::stop(int signo, int timeoutMs)
{
    if (pid <= 0)
        return -1;
    ::kill(pid, signo);
    int64_t deadline = nowMs() + timeoutMs;
    while (nowMs() < deadline)
    {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid)
        {
            pid = -1;
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    pid = -1;
    return -1;
}

bool Daemon::running()
{
    if (pid <= 0)
        return false;
    int status = 0;
    return waitpid(pid, &status, WNOHANG) == 0;
}

RawClient::~RawClient() { close(); }

void RawClient::close()
{
    if (fd >= 0)
        ::close(fd);
    fd = -1;
    buffer_.clear();
}

bool RawClient::connect(const std::string& path)
{
    close();
    fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path.c_str(), sizeof addr.sun_path - 1);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
    {
        close();
        return false;
    }
    return true;
}

bool RawClient::open(const std::string& path)
{
    if (!connect(path))
        return false;
    nlohmann::json r = request({{"type", "hello"}, {"protocol", 1}, {"client", "test"}}, 2000);
    return r.is_object() && r.value("type", "") == "hello";
}

bool RawClient::sendRaw(const std::string& bytes)
{
    size_t at = 0;
    while (at < bytes.size())
    {
        ssize_t n = ::send(fd, bytes.data() + at, bytes.size() - at, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        at += size_t(n);
    }
    return true;
}

std::optional<std::string> RawClient::readLine(int timeoutMs)
{
    int64_t deadline = nowMs() + timeoutMs;
    for (;;)
    {
        size_t nl = buffer_.find('\n');
        if (nl != std::string::npos)
        {
            std::string line = buffer_.substr(0, nl);
            buffer_.erase(0, nl + 1);
            return line;
        }
        int64_t left = deadline - nowMs();
        if (left <= 0)
            return std::nullopt;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, int(left)) <= 0)
            continue;
        char chunk[65536];
        ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
        if (n <= 0)
            return std::nullopt;
        buffer_.append(chunk, size_t(n));
    }
}

nlohmann::json RawClient::requestLine(const std::string& line, int timeoutMs)
{
    if (!sendRaw(line + "\n"))
        return nullptr;
    std::optional<std::string> reply = readLine(timeoutMs);
    if (!reply)
        return nullptr;
    return nlohmann::json::parse(*reply, nullptr, false);
}

nlohmann::json RawClient::request(const nlohmann::json& message, int timeoutMs)
{
    return requestLine(message.dump(), timeoutMs);
}

nlohmann::json RawClient::requestWithFds(const nlohmann::json& message, std::vector<int>& fds, int timeoutMs)
{
    if (!sendRaw(message.dump() + "\n"))
        return nullptr;
    int64_t deadline = nowMs() + timeoutMs;
    while (buffer_.find('\n') == std::string::npos && nowMs() < deadline)
    {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 100) <= 0)
            continue;
        char chunk[65536];
        alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int) * 16)];
        iovec iov{chunk, sizeof chunk};
        msghdr msg{};
        msg.msg_iov = &iov;
        msg.msg_iovlen = 1;
        msg.msg_control = control;
        msg.msg_controllen = sizeof control;
        ssize_t n = ::recvmsg(fd, &msg, MSG_CMSG_CLOEXEC);
        if (n <= 0)
            return nullptr;
        for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
        {
            if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SCM_RIGHTS)
                continue;
            size_t count = (c->cmsg_len - CMSG_LEN(0)) / sizeof(int);
            const int* passed = reinterpret_cast<const int*>(CMSG_DATA(c));
            fds.insert(fds.end(), passed, passed + count);
        }
        buffer_.append(chunk, size_t(n));
    }
    std::optional<std::string> reply = readLine(0);
    return reply ? nlohmann::json::parse(*reply, nullptr, false) : nlohmann::json();
}

bool RawClient::closedByPeer(int timeoutMs)
{
    int64_t deadline = nowMs() + timeoutMs;
    while (nowMs() < deadline)
    {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 100) <= 0)
            continue;
        char chunk[65536];
        ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
        if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN))
            return true;
    }
    return false;
}

long residentKb(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0)
            return std::strtol(line.c_str() + 6, nullptr, 10);
    return -1;
}

bool writeBuiltinSnapshot(const std::string& path, int64_t unixTimeS, std::string& error)
{
    return sky::writeSnapshotFile(path, {sky::makeBuiltinWeather(unixTimeS)}, error);
}

bool waitForStatus(RawClient& client, const std::function<bool(const nlohmann::json&)>& pred, int timeoutMs,
                   nlohmann::json* last)
{
    int64_t deadline = nowMs() + timeoutMs;
    while (nowMs() < deadline)
    {
        nlohmann::json s = client.request({{"type", "status"}});
        if (last)
            *last = s;
        if (s.is_object() && pred(s))
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
}

}  // namespace skytest
