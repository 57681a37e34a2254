// SPDX-License-Identifier: MIT
// The daemon's configuration: the [service] section of a TOML file (config/service.toml documents every
// field, its unit and default) plus the renderer's sections of the same file ([march], [lighting], …,
// read by skyservice/app/config_file.h's applyConfigFile on top of the `quality` preset).
#pragma once

#include "skyservice/render/render_types.h"
#include "skyservice/service/log.h"

#include <cstdint>
#include <string>

namespace sky
{

/// [cigi]: the CIGI 3.3 IG interface (skyservice/service/cigi_link.h); off while port is 0.
struct CigiConfig
{
    uint32_t port = 0;      ///< UDP port the host sends to (host -> IG); 0 = no CIGI
    uint32_t hostPort = 0;  ///< port on the sender's address that Start of Frame and responses go to; 0 = port + 1
    uint32_t viewId = 0;    ///< the View Definition / View Control this daemon renders
    uint32_t ownship = 0;   ///< the entity whose Entity Control poses the eye

    uint32_t replyPort() const { return hostPort != 0 ? hostPort : port + 1; }
    bool operator==(const CigiConfig&) const = default;
};

struct ServiceConfig
{
    std::string path;               ///< the file it was read from ("" = built-in defaults)
    std::string socketPath;         ///< default: defaultSocketPath()
    uint32_t socketMode = 0600;     ///< permission bits of the socket file
    std::string shmName;            ///< shm_open name of the frame ring; default: defaultShmName(socketPath)
    std::string weatherDir;         ///< watched for new snapshot files ("" = none)
    std::string weather = "builtin";///< initial weather: "builtin" or a snapshot file
    double renderRateHz = 30;       ///< frames per second; 0 = only on a `render` request
    uint32_t maxWidth = 1920;       ///< largest frame (pixels): ring size and protocol limit
    uint32_t maxHeight = 1080;
    uint32_t shmSlots = 3;          ///< slots in the shared-memory ring (2..4)
    uint32_t shadowMapSize = 0;     ///< shadow map texels per side with every frame; 0 = none
    double shadowMapExtentM = 150000;///< its edge length on the ground (m)
    uint32_t filesEvery = 0;        ///< write files every N frames (0 = never)
    std::string filesDir;           ///< where, relative to filesRoot (required when filesEvery > 0)
    std::string filesRoot;          ///< every file the daemon writes goes beneath it; default: defaultFilesRoot()
    std::string filesFormat = "png";///< png | exr | both
    LogLevel logLevel = LogLevel::Info;
    std::string device;             ///< Vulkan device: index or name part ("" = best)
    bool validate = false;          ///< Vulkan validation layers
    ViewRequest view;               ///< initial view (pose, fov, size)
    int64_t timeUnixS = 0;          ///< initial simulated UTC time
    double rate = 0;                ///< initial sim seconds per real second (0 = frozen)
    std::string quality = "medium"; ///< preset: high | medium | test
    QualitySettings qualitySettings;///< the preset with the file's renderer sections applied
    CigiConfig cigi;                ///< [cigi]
};

/// $XDG_RUNTIME_DIR/skyservice.sock, else /tmp/skyservice-<uid>.sock.
std::string defaultSocketPath();
/// "/skyservice-<uid>-<16 hex digits of a hash of socketPath>": the same for a restarted daemon.
std::string defaultShmName(const std::string& socketPath);

/// The defaults of every field (the file's absence). Quality is the default preset.
ServiceConfig defaultServiceConfig();

/// Reads `path` over the defaults. Unknown keys, wrong types and values out of range are refused with a
/// message naming the file and the field ("service.render_rate_hz"); `out` is then untouched.
bool loadServiceConfig(const std::string& path, ServiceConfig& out, std::string& error);

/// Cross-field checks (view within max sizes, files_dir with files_every, …) after command-line
/// overrides. `where` prefixes the message (the file name or "command line").
bool checkServiceConfig(const ServiceConfig& config, const std::string& where, std::string& error);

}  // namespace sky
