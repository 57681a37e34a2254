// SPDX-License-Identifier: MIT
// `skyservice` without a subcommand: the long-running service (skyservice/ipc/PROTOCOL.md). Wires the parts together:
// config -> renderer -> shared-memory ring -> control socket, then the threads (signals, weather
// loader and watcher, render loop) until SIGTERM/SIGINT. SIGHUP reloads the config file.
#pragma once

#include <cstdint>
#include <string>

namespace sky
{

/// Command-line options; each non-empty one overrides the config file's field.
struct DaemonOptions
{
    std::string config;      ///< TOML file ([service] plus renderer sections); "" = defaults
    std::string socket;      ///< service.socket_path
    std::string weatherDir;  ///< service.weather_dir
    std::string logLevel;    ///< service.log_level
    std::string device;      ///< service.device
    bool validate = false;   ///< service.validate = true
    // [cigi] overrides; -1 = as the config file says.
    int64_t cigiPort = -1;      ///< cigi.port
    int64_t cigiHostPort = -1;  ///< cigi.host_port
    int64_t cigiViewId = -1;    ///< cigi.view_id
    int64_t cigiOwnship = -1;   ///< cigi.ownship
};

/// Runs until SIGTERM/SIGINT. Returns 0 after a clean shutdown, 1 on a runtime failure (device, socket,
/// shared memory, leaked device memory, validation messages), 2 for a bad config or command line.
int runDaemon(const DaemonOptions& options);

}  // namespace sky
