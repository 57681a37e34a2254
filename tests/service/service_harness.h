// SPDX-License-Identifier: MIT
// Helpers of the service's end-to-end tests: the real daemon as a child process with a temporary
// config (tiny frames, quality "test", its own socket and shared-memory names), and a raw control
// socket client that speaks PROTOCOL.md line by line.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace skytest
{

/// A fresh folder under $TMPDIR (or /tmp), removed by the destructor.
struct TempDir
{
    TempDir();
    ~TempDir();
    std::string path;
};

/// What goes into the temp config's [service] section (plus a [march] section for speed).
struct DaemonConfig
{
    uint32_t width = 64, height = 36;
    double renderRateHz = 0;
    std::string weatherDir;
    std::string extraService;  ///< more [service] lines
    std::string extraSections; ///< more sections ([march] ...)
    bool defaultShmName = false;  ///< leave shm_name out: the daemon names its ring itself
    std::string logLevel = "debug"; ///< [service] log_level ("info": what a daemon in service logs)
};

/// The config most tests use: 16x9 frames (enough for the plumbing, fast on lavapipe) rendered at
/// `renderRateHz` (0: only on request).
inline DaemonConfig tinyFrames(double renderRateHz = 0)
{
    DaemonConfig c;
    c.width = 16;
    c.height = 9;
    c.renderRateHz = renderRateHz;
    return c;
}

class Daemon
{
public:
    ~Daemon();
    /// Writes DIR/service.toml from `config` and starts the daemon; waits until its socket answers hello.
    bool start(const std::string& dir, const DaemonConfig& config, std::string& error);
    /// Starts again with the same files (after stop()).
    bool restart(std::string& error);
    /// Sends `signo` and waits for the exit (timeout: SIGKILL and -1). Returns the exit code.
    int stop(int signo = 15, int timeoutMs = 20000);
    bool running();

    pid_t pid = -1;
    std::string socketPath, shmName, configPath, logPath, dir;
    std::string filesRoot() const { return dir + "/frames"; }  ///< the config's files_root

private:
    bool launch(std::string& error);
};

/// The skyservice binary (compile definition SKY_SERVICE_BIN).
std::string serviceBinary();

class RawClient
{
public:
    RawClient() = default;
    RawClient(const RawClient&) = delete;
    RawClient& operator=(const RawClient&) = delete;
    ~RawClient();

    bool connect(const std::string& path);
    /// Writes the bytes as they are (add "\n" yourself).
    bool sendRaw(const std::string& bytes);
    /// The next reply line, or nothing after timeoutMs / on EOF.
    std::optional<std::string> readLine(int timeoutMs = 5000);
    /// Sends one request (a newline is added) and parses its reply (null json on timeout/EOF).
    nlohmann::json request(const nlohmann::json& message, int timeoutMs = 5000);
    nlohmann::json requestLine(const std::string& line, int timeoutMs = 5000);
    /// As request(), also collecting file descriptors passed with the reply (SCM_RIGHTS); the caller owns them.
    nlohmann::json requestWithFds(const nlohmann::json& message, std::vector<int>& fds, int timeoutMs = 10000);
    /// connect + hello.
    bool open(const std::string& path);
    /// True when the service closed the connection (EOF seen within timeoutMs).
    bool closedByPeer(int timeoutMs);
    void close();
    int fd = -1;

private:
    std::string buffer_;
};

/// RSS of a process (kB) from /proc/PID/status, -1 when unreadable.
long residentKb(pid_t pid);
/// Writes a snapshot file with the built-in weather stamped at unixTimeS (sky-ingest's format).
bool writeBuiltinSnapshot(const std::string& path, int64_t unixTimeS, std::string& error);
/// Polls `status` until pred(status) or timeout.
bool waitForStatus(RawClient& client, const std::function<bool(const nlohmann::json&)>& pred, int timeoutMs,
                   nlohmann::json* last = nullptr);

}  // namespace skytest
