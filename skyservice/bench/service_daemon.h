// SPDX-License-Identifier: MIT
// The real sky service as a child process of sky-service-bench: a generated config (its own socket and
// shared-memory ring in a temporary folder), started, waited for, stopped, and its log read back when
// something goes wrong.
#pragma once

#include "skyservice/bench/bench_scenes.h"

#include <cstdint>
#include <string>
#include <sys/types.h>

namespace sky
{

/// What goes into the daemon's generated config.
struct ServiceDaemonConfig
{
    std::string binary;                         ///< the skyservice executable
    std::string dir;                            ///< folder for the config, socket and log (exists, writable)
    std::string shmName;                        ///< shm_open name of the frame ring ("/...")
    double renderRateHz = 0;                    ///< 0: frames only on request
    uint32_t maxWidth = 1920, maxHeight = 1080; ///< largest frame asked for (pixels)
    uint32_t shadowMapSize = 0;                 ///< cloud shadow map texels per side; 0 = none
    std::string device;                         ///< Vulkan device selector ("" = the daemon's choice)
    BenchScene scene;                           ///< initial view and time
    uint32_t width = 320, height = 180;         ///< initial view size (pixels)
};

class ServiceDaemon
{
  public:
    ServiceDaemon() = default;
    ServiceDaemon(const ServiceDaemon&) = delete;
    ServiceDaemon& operator=(const ServiceDaemon&) = delete;
    /// Kills a daemon still running.
    ~ServiceDaemon();

    /**
     * Writes DIR/service.toml (quality medium, reprojected march) and starts the daemon; returns once its
     * socket accepts a client, or fails when it exits first or is silent for `startTimeoutS`.
     *
     * @param[in] config the generated config's content.
     * @param[in] startTimeoutS how long the daemon may take to create its device and pipelines (s).
     * @param[out] error on failure: what failed, with the tail of the daemon's log.
     **********************************************************************/
    bool start(const ServiceDaemonConfig& config, double startTimeoutS, std::string& error);

    /**
     * SIGTERM, then waits for a clean exit (SIGKILL after `timeoutS`).
     *
     * @param[out] error when the daemon exited other than with 0: its status and log tail.
     * @return true for exit code 0.
     **********************************************************************/
    bool stop(double timeoutS, std::string& error);

    /// Whether the child is still running (false after it exited or was stopped).
    bool running();
    /// The last `lines` lines of the daemon's log (stdout and stderr).
    std::string logTail(size_t lines = 20) const;

    pid_t pid() const { return pid_; }
    const std::string& socketPath() const { return socketPath_; }

  private:
    pid_t pid_ = -1;
    int exitStatus_ = 0;
    std::string socketPath_, configPath_, logPath_;
};

/// The skyservice executable next to this program (its folder from /proc/self/exe), "" if unknown.
std::string defaultDaemonBinary();

} // namespace sky
