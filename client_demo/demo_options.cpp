// SPDX-License-Identifier: MIT
#include "client_demo/demo_options.h"

#include "client_demo/utc_time.h"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cstdlib>
#include <map>
#include <vector>

namespace demo
{

std::string defaultSocketPath()
{
    // The same default as the service's socket_path (config/service.toml).
    if (const char* runtime = std::getenv("XDG_RUNTIME_DIR"); runtime != nullptr && *runtime != '\0')
        return std::string(runtime) + "/skyservice.sock";
    return "/tmp/skyservice-" + std::to_string(::getuid()) + ".sock";
}

int parseDemoOptions(int argc, char** argv, DemoOptions& o)
{
    CLI::App app{"client_demo: flies over the sky service's frames (a window, or --headless captures).\n"
                 "Exit codes: 0 ok, 1 runtime failure (no service, no frame, no window), 2 bad command line."};
    o.socketPath = defaultSocketPath();
    app.add_option("--socket", o.socketPath, "The service's control socket")->capture_default_str();
    const std::map<std::string, Transport> transports{
        {"auto", Transport::Auto}, {"shm", Transport::Shm}, {"vulkan", Transport::Vulkan}};
    app.add_option("--transport", o.transport, "auto (zero-copy when the service's GPU is ours, else shm) | shm | vulkan")
        ->transform(CLI::CheckedTransformer(transports, CLI::ignore_case));
    app.add_flag("--headless", o.headless, "No window: capture --frames frames into --out");
    app.add_option("--frames", o.frames, "Frames to capture (headless, default 8) or show (window, default: until closed)");
    app.add_option("--out", o.outDir, "Headless: folder for frame-NNNN.png and frame-NNNN.json")->capture_default_str();
    app.add_option("--screenshot", o.screenshotPath, "Window: write the last presented image to this PNG");
    app.add_option("--width", o.width, "Frame width (pixels)")->check(CLI::Range(8, 8192))->capture_default_str();
    app.add_option("--height", o.height, "Frame height (pixels)")->check(CLI::Range(8, 8192))->capture_default_str();
    CLI::Option* fovOption =
        app.add_option("--fov", o.angles.fovDeg, "Vertical field of view (degrees)")->check(CLI::Range(1.0, 170.0));
    std::vector<double> frustumDeg;
    app.add_option("--frustum", frustumDeg,
                   "An off-centre frustum, as one channel of a display wall: LEFT,RIGHT,UP,DOWN half-angles from the "
                   "view axis (degrees, each in (-85, 85), LEFT+RIGHT and UP+DOWN above 1); instead of --fov")
        ->delimiter(',')
        ->expected(4)
        ->check(CLI::Range(-84.999, 84.999))
        ->excludes(fovOption);
    Aircraft& a = o.aircraft;
    app.add_option("--lat", a.latDeg, "Start latitude (degrees)")->check(CLI::Range(-89.9, 89.9))->capture_default_str();
    app.add_option("--lon", a.lonDeg, "Start longitude (degrees)")->check(CLI::Range(-180.0, 180.0))->capture_default_str();
    app.add_option("--alt", a.altitudeM, "Start altitude above the WGS84 ellipsoid (m)")
        ->check(CLI::Range(kMinAltitudeM, kMaxAltitudeM))
        ->capture_default_str();
    app.add_option("--heading", a.headingDeg, "Start heading, clockwise from north (degrees)")->check(CLI::Range(0.0, 360.0));
    app.add_option("--pitch", a.pitchDeg, "Start pitch, + nose up (degrees)")->check(CLI::Range(-89.0, 89.0));
    app.add_option("--speed", a.speedMps, "Start speed (m/s)")->check(CLI::Range(0.0, 1000.0))->capture_default_str();
    app.add_option("--time", o.timeIso, "Set the simulated UTC time, ISO 8601 (e.g. 2026-06-21T12:00:00Z)");
    app.add_option("--rate", o.rate, "With --time: simulated seconds per real second (0 = frozen)");
    app.add_option("--step", o.stepS, "Headless: simulated flight seconds between frames")->capture_default_str();
    app.add_option("--frame-timeout-ms", o.frameTimeoutMs, "Longest wait for one frame (ms)")->capture_default_str();
    const std::map<std::string, CompositeMode> composites{{"layers", CompositeMode::Layers},
                                                          {"display", CompositeMode::Display}};
    app.add_option("--composite", o.composite,
                   "layers (terrain with relief by depth from the service's sky/clouds/depth layers; the "
                   "default) | display (flat ground over the finished frame)")
            ->transform(CLI::CheckedTransformer(composites, CLI::ignore_case));
    bool noGround = false;
    app.add_flag("--no-ground", noGround, "Show the service's frame as it is (no demo ground, no shadows)");
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
        return app.exit(e) == 0 ? 0 : 2;
    }
    o.ground = !noGround;
    if (frustumDeg.size() == 4)
    {
        if (frustumDeg[0] + frustumDeg[1] <= 1.0 || frustumDeg[2] + frustumDeg[3] <= 1.0)
        {
            std::fprintf(stderr, "client_demo: --frustum: LEFT+RIGHT and UP+DOWN must each be above 1 degree\n");
            return 2;
        }
        o.angles.asymmetric = true;
        o.angles.leftDeg = frustumDeg[0];
        o.angles.rightDeg = frustumDeg[1];
        o.angles.upDeg = frustumDeg[2];
        o.angles.downDeg = frustumDeg[3];
    }
    double unused = 0.0;
    if (!o.timeIso.empty() && !parseUtc(o.timeIso, unused))
    {
        std::fprintf(stderr, "client_demo: --time %s is not an ISO 8601 UTC time (2026-06-21T12:00:00Z)\n",
                     o.timeIso.c_str());
        return 2;
    }
    if (o.headless && o.frames == 0)
        o.frames = 8;
    return -1;
}

CompositeOptions compositeOptionsOf(const DemoOptions& o)
{
    CompositeOptions c;
    c.ground = o.ground;
    c.mode = o.composite;
    c.terrain = demoMountainAhead(o.aircraft.latDeg, o.aircraft.lonDeg, o.aircraft.headingDeg);
    return c;
}

}  // namespace demo
