// SPDX-License-Identifier: MIT
// sky-service-bench: what an image generator gets from the sky service, measured in the client.
//
//   sky-service-bench --scene all --size 1920x1080 --frames 300 --transport both --json service.json
//
// Per scene it starts the real daemon (`skyservice --config <generated>`: its own socket and ring in a
// temporary folder, quality medium, reprojected march, render on request or at --rate-hz), gives it the
// scene's time and weather (the same as sky-bench's), and per size and transport connects a fresh
// libskyclient client that times `frames` frames after `warmup` (service_client_run.h says how). It
// reports delivered frames per second, set_view -> frame latency (median/p95/p99, client clock), the
// daemon's CPU time per frame (/proc, all its threads: on lavapipe that includes the rendering itself),
// the daemon's own frame_ms, and the SM clock at each scene's start and end (nvidia-smi, where it exists).
// --flight-path flies one climbing, turning path through the cumulus instead (service_flight_bench.h).
// Exit codes: 0 ok, 1 runtime failure (daemon, socket, frames), 2 bad command line.
#include "skyservice/bench/service_client_run.h"
#include "skyservice/bench/service_daemon.h"
#include "skyservice/bench/service_flight_bench.h"
#include "skyservice/bench/service_host_metrics.h"
#include "skyservice/bench/service_session.h"
#include "skyservice/output/image_files.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace sky
{
namespace
{

constexpr int kExitOk = 0, kExitRuntime = 1, kExitUsage = 2;
constexpr double kDaemonStartTimeoutS = 300; // device creation and pipelines; minutes on a loaded lavapipe host
constexpr double kWeatherTimeoutS = 300;
constexpr double kDaemonStopTimeoutS = 60;
// The layers a subscription may name (skyservice/ipc/PROTOCOL.md "Compositing layers").
const char* const kKnownLayers[] = {"display", "sky", "clouds", "depth"};

struct ServiceBenchOptions
{
    std::string scene = "all";
    std::vector<std::string> sizes;
    uint32_t width = 0, height = 0;
    uint32_t frames = 300, warmup = 30;
    std::string transport = "shm";
    uint32_t shadowMapSize = 0;
    double rateHz = 0;
    double speedMps = 250;
    std::string layers = "display";
    std::string device;
    std::string daemon;
    std::string json;
    bool flightPath = false;
    FlightPathSpec flight;
    std::string framesCsv;
};

struct Size
{
    uint32_t width = 0, height = 0;
};

bool parseSizes(const ServiceBenchOptions& o, std::vector<Size>& sizes, std::string& error)
{
    for (const std::string& text : o.sizes)
    {
        Size s;
        char x = 0, extra = 0;
        if (std::sscanf(text.c_str(), "%u%c%u%c", &s.width, &x, &s.height, &extra) != 3 || (x != 'x' && x != 'X'))
        {
            error = "--size " + text + ": expected WIDTHxHEIGHT, e.g. 1920x1080";
            return false;
        }
        sizes.push_back(s);
    }
    if ((o.width > 0) != (o.height > 0))
    {
        error = "--width and --height go together";
        return false;
    }
    if (o.width > 0)
        sizes.push_back({o.width, o.height});
    if (sizes.empty())
        sizes.push_back({1920, 1080});
    for (const Size& s : sizes)
        if (s.width < 8 || s.height < 8 || s.width > 8192 || s.height > 8192)
        {
            error = "size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                    " is outside 8..8192 pixels per side (the service's max_width/max_height)";
            return false;
        }
    return true;
}

bool parseLayers(const std::string& spec, std::vector<std::string>& layers, std::string& error)
{
    size_t start = 0;
    while (start <= spec.size())
    {
        size_t comma = spec.find(',', start);
        std::string name = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (std::find(std::begin(kKnownLayers), std::end(kKnownLayers), name) == std::end(kKnownLayers))
        {
            error = "unknown layer \"" + name + "\"; known: display, sky, clouds, depth";
            return false;
        }
        layers.push_back(name);
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    return !layers.empty();
}

uint32_t layerBitOf(const std::string& name)
{
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        if (name == kKnownLayers[k])
            return 1u << k;
    return 0;
}

std::string makeTempDir()
{
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/sky-service-bench-XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    return mkdtemp(buffer.data()) ? std::string(buffer.data()) : std::string();
}

/// One scene: its daemon, its weather, and every size and transport. On failure `error` ends with the
/// daemon's log tail.
bool runScene(const ServiceBenchOptions& o, const std::vector<Size>& sizes, const std::vector<std::string>& transports,
              const BenchScene& scene, const std::string& dir, ServiceBenchRun& run, ServiceSceneResult& out,
              std::string& error)
{
    out.scene = scene;
    ServiceDaemonConfig config;
    config.binary = o.daemon;
    config.dir = dir;
    config.shmName =
        "/sky-service-bench-" + std::to_string(getpid()) + "-" + std::filesystem::path(dir).filename().string();
    config.renderRateHz = o.rateHz;
    config.maxWidth = config.maxHeight = 0; // the largest size asked for: the ring's slots fit it exactly
    for (const Size& s : sizes)
    {
        config.maxWidth = std::max(config.maxWidth, s.width);
        config.maxHeight = std::max(config.maxHeight, s.height);
    }
    config.shadowMapSize = o.shadowMapSize;
    config.device = o.device;
    config.scene = scene;
    config.width = sizes.front().width;
    config.height = sizes.front().height;

    ServiceDaemon daemon;
    if (!daemon.start(config, kDaemonStartTimeoutS, error))
        return false;
    auto failWithLog = [&](const std::string& what)
    {
        error = what + ": " + error;
        if (daemon.running())
            error += "\nthe daemon is still running; its log ends:\n" + daemon.logTail();
        else
        {
            std::string stopError;
            daemon.stop(kDaemonStopTimeoutS, stopError);
            error += "\n" + stopError;
        }
        return false;
    };
    if (run.deviceName.empty())
    {
        ServiceConnection c;
        nlohmann::json status;
        if (!c.open(daemon.socketPath(), "sky-service-bench-setup", error) ||
            !readServiceStatus(c.get(), status, error))
            return failWithLog("the daemon's status");
        run.deviceName = status.value("device", std::string());
        run.driver = status.value("driver", std::string());
    }
    if (!prepareSceneWeather(daemon.socketPath(), scene, dir, o.rateHz <= 0, kWeatherTimeoutS, error))
        return failWithLog("the scene's time and weather");

    out.smClockStartMhz = gpuSmClockMhz();
    for (const Size& size : sizes)
        for (const std::string& transport : transports)
        {
            ServiceRunSettings s;
            s.socketPath = daemon.socketPath();
            s.daemonPid = daemon.pid();
            s.scene = scene;
            s.width = size.width;
            s.height = size.height;
            s.transport = transport;
            s.frames = o.frames;
            s.warmup = o.warmup;
            s.speedMps = o.speedMps;
            s.onRequest = o.rateHz <= 0;
            for (const std::string& layer : run.layers)
                s.layers |= layerBitOf(layer);
            ServiceRunResult r;
            if (!runServiceClient(s, r, error))
                return failWithLog(std::to_string(size.width) + "x" + std::to_string(size.height) + " " + transport);
            std::fprintf(stderr, "sky-service-bench: %-19s %5ux%-5u %-6s %u frames, %.2f per second\n",
                         scene.name.c_str(), size.width, size.height, transport.c_str(), r.frames, r.deliveredFps);
            out.runs.push_back(std::move(r));
        }
    out.smClockEndMhz = gpuSmClockMhz();
    return daemon.stop(kDaemonStopTimeoutS, error);
}

/// --flight-path: one size, one transport, the path instead of the scenes.
int runFlightPath(const ServiceBenchOptions& o)
{
    std::vector<Size> sizes;
    std::string error;
    if (!parseSizes(o, sizes, error) || sizes.size() != 1 || o.transport == "both" || o.rateHz > 0 ||
        o.shadowMapSize > 0 || o.layers != "display")
    {
        std::fprintf(stderr, "sky-service-bench: --flight-path: %s\n",
                     error.empty() ? "one --size, --transport shm or vulkan, no --rate-hz, --shadow-map or --layers"
                                   : error.c_str());
        return kExitUsage;
    }
    FlightBenchSettings s;
    s.spec = o.flight;
    s.width = sizes.front().width;
    s.height = sizes.front().height;
    s.transport = o.transport;
    s.warmup = o.warmup;
    s.device = o.device;
    s.daemon = o.daemon;
    s.json = o.json;
    s.csv = o.framesCsv;
    s.dir = makeTempDir();
    if (s.dir.empty())
    {
        std::fprintf(stderr, "sky-service-bench: cannot create a temporary folder under $TMPDIR or /tmp: %s\n",
                     std::strerror(errno));
        return kExitRuntime;
    }
    const int code = runFlightPathBench(s);
    std::error_code ec;
    std::filesystem::remove_all(s.dir, ec);
    return code;
}

int runServiceBench(const ServiceBenchOptions& o)
{
    if (o.flightPath)
        return runFlightPath(o);
    std::vector<BenchScene> scenes;
    std::vector<Size> sizes;
    ServiceBenchRun run;
    std::string error;
    if (!selectBenchScenes(o.scene, scenes, error))
    {
        std::fprintf(stderr, "sky-service-bench: --scene %s: %s\n", o.scene.c_str(), error.c_str());
        return kExitUsage;
    }
    if (!parseSizes(o, sizes, error) || !parseLayers(o.layers, run.layers, error))
    {
        std::fprintf(stderr, "sky-service-bench: %s\n", error.c_str());
        return kExitUsage;
    }
    if (o.shadowMapSize > 0 && o.shadowMapSize < 8)
    {
        std::fprintf(stderr, "sky-service-bench: --shadow-map %u: must be 0 (none) or at least 8\n", o.shadowMapSize);
        return kExitUsage;
    }
    std::vector<std::string> transports;
    if (o.transport == "both")
        transports = {"shm", "vulkan"};
    else
        transports = {o.transport};

    ServiceBenchOptions options = o;
    if (options.daemon.empty())
        options.daemon = defaultDaemonBinary();
    run.daemonBinary = options.daemon;
    run.frames = o.frames;
    run.warmup = o.warmup;
    run.speedMps = o.speedMps;
    run.renderRateHz = o.rateHz;
    run.shadowMapSize = o.shadowMapSize;
    const std::string tempDir = makeTempDir();
    if (tempDir.empty())
    {
        std::fprintf(stderr, "sky-service-bench: cannot create a temporary folder under $TMPDIR or /tmp: %s\n",
                     std::strerror(errno));
        return kExitRuntime;
    }
    int code = kExitOk;
    for (size_t i = 0; i < scenes.size() && code == kExitOk; ++i)
    {
        const std::string dir = tempDir + "/s" + std::to_string(i);
        std::filesystem::create_directory(dir);
        run.scenes.emplace_back();
        if (!runScene(options, sizes, transports, scenes[i], dir, run, run.scenes.back(), error))
        {
            std::fprintf(stderr, "sky-service-bench: scene %s: %s\n", scenes[i].name.c_str(), error.c_str());
            code = kExitRuntime;
        }
    }
    std::error_code ec;
    std::filesystem::remove_all(tempDir, ec);
    if (code != kExitOk)
        return code;
    printServiceBenchTable(stdout, run);
    if (!o.json.empty() && !writeJsonAtomic(o.json, serviceBenchToJson(run), error))
    {
        std::fprintf(stderr, "sky-service-bench: --json %s: %s\n", o.json.c_str(), error.c_str());
        return kExitRuntime;
    }
    return kExitOk;
}

} // namespace
} // namespace sky

int main(int argc, char** argv)
{
    sky::ServiceBenchOptions o;
    CLI::App app{"sky-service-bench: frames per second and set_view -> frame latency that a libskyclient client "
                 "gets from the real sky service, per bench scene, size and transport.\n"
                 "Exit codes: 0 ok, 1 runtime failure, 2 bad command line."};
    app.add_option("--scene", o.scene, "Scene name, comma-separated names, or all");
    app.add_option("--size", o.sizes, "Frame size WIDTHxHEIGHT (repeat for several; default 1920x1080)");
    app.add_option("--width", o.width, "Frame width (pixels), with --height: one more size")
        ->check(CLI::Range(8, 8192));
    app.add_option("--height", o.height, "Frame height (pixels)")->check(CLI::Range(8, 8192));
    app.add_option("--frames", o.frames, "Timed frames per scene, size and transport")->check(CLI::Range(1, 1000000));
    app.add_option("--warmup", o.warmup, "Untimed frames before them")->check(CLI::Range(0, 1000000));
    app.add_option("--transport", o.transport, "shm, vulkan (zero-copy) or both")
        ->check(CLI::IsMember({"shm", "vulkan", "both"}));
    app.add_option("--shadow-map", o.shadowMapSize, "Cloud shadow map texels per side with every frame (0: none)")
        ->check(CLI::Range(0, 8192));
    app.add_option("--rate-hz", o.rateHz,
                   "The daemon renders at this rate and the client only waits (0: the client asks for each frame)")
        ->check(CLI::Range(0.0, 1000.0));
    app.add_option("--speed", o.speedMps, "Eye speed along its heading when asking for frames (m/s, 60 Hz steps)")
        ->check(CLI::Range(0.0, 10000.0));
    app.add_option("--layers", o.layers,
                   "What each subscription asks for: display,sky,clouds,depth (comma-separated; vulkan: as images)");
    app.add_option("--device", o.device, "The daemon's Vulkan device: index or part of its name");
    app.add_option("--daemon", o.daemon, "The skyservice executable (default: next to this program)");
    app.add_option("--json", o.json, "Write the results as JSON to this file");
    app.add_flag("--flight-path", o.flightPath,
                 "Fly the flight path instead of the scenes: from 44.3 N 7.5 E at 300 m, 250 m/s, climbing 15 m/s "
                 "and turning 3 deg/s through the built-in cumulus, one frame per --flight-step");
    app.add_option("--flight-step", o.flight.stepS, "Flight path: simulated seconds per delivered frame")
        ->check(CLI::Range(1e-4, 60.0));
    app.add_option("--flight-seconds", o.flight.seconds, "Flight path: simulated length (s; 240 reaches 3900 m)")
        ->check(CLI::Range(1e-3, 3600.0));
    app.add_option("--frames-csv", o.framesCsv, "Flight path: write each frame's pose and times to this CSV file");
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
        int code = app.exit(e);
        return code == 0 ? sky::kExitOk : sky::kExitUsage;
    }
    return sky::runServiceBench(o);
}
