// SPDX-License-Identifier: MIT
// The subcommands of the skyservice executable. Each returns the process exit code:
//   0 success, 1 runtime failure (Vulkan, files), 2 bad command line or values, 3 unreadable weather.
#pragma once

#include "skyservice/render/render_types.h"
#include "skyservice/vk/context.h"

#include <optional>
#include <string>

namespace CLI
{
class App;
}

namespace sky
{

struct Renderer;

enum ExitCode : int
{
    kExitOk = 0,
    kExitRuntime = 1,
    kExitUsage = 2,
    kExitWeather = 3,
};

/// Options shared by every command that renders.
struct CommonRenderOptions
{
    std::string device;
    bool validate = false;
    std::string quality = "high";   ///< preset: high | medium | test
    /// --seed: replaces the config file's noise.seed when given (the default seed is QualitySettings's)
    std::optional<uint32_t> seed;
    int steps = 0;                  ///< overrides the preset's view steps when > 0
    int accumulate = 0;             ///< overrides the preset's accumulated frames when > 0
    std::string config;             ///< TOML file applied after the preset (config/default.toml)
};

struct RenderCommandOptions
{
    CommonRenderOptions common;
    ViewRequest request;
    std::string time = "2026-06-21T12:00:00Z";
    std::string weather = "builtin";
    std::string out = "render";
    bool noDetail = false;
    bool noHighCloud = false;
    bool reference = false;            ///< path-trace the clouds (skyservice/render/reference_renderer.h)
    uint32_t referenceSpp = 64;        ///< its samples per pixel
    std::string referencePhase = "model";  ///< model | mie
    double dropletDiameterUm = 20.0;   ///< mie: droplet diameter (um)
};

struct ShowcaseOptions
{
    CommonRenderOptions common;
    std::string outDir = "out";
    uint32_t width = 640;
    uint32_t height = 360;
    /// look-reference-pairs.png: the reference's samples per pixel (0: no pairs). The default keeps the four
    /// pairs near a minute on a 2-core CPU (lavapipe).
    uint32_t referenceSpp = 8;
};

void addCommonOptions(CLI::App& app, CommonRenderOptions& o);
/// --shadow-map, --shadow-size, --shadow-extent (fill the request's shadow-map fields).
void addShadowMapOptions(CLI::App& app, ViewRequest& request);
/// Fills `q` from the preset name; returns false (and a message) for an unknown preset.
bool qualityFromOptions(const CommonRenderOptions& o, QualitySettings& q, std::string& error);

/// Creates `renderer` on the device the options name; on failure prints "skyservice <command>: why",
/// leaves nothing allocated and returns false.
bool startRenderer(const CommonRenderOptions& o, uint32_t noiseSeed, Renderer& renderer, const char* command);

int runRenderCommand(const RenderCommandOptions& options);
int runShowcaseCommand(const ShowcaseOptions& options);

}  // namespace sky
