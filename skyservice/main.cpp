// SPDX-License-Identifier: MIT
// skyservice: the sky service's command line.
//   skyservice [--config FILE] [...]   the long-running service (skyservice/service/README.md)
//   skyservice render                  one view to PREFIX.png / .exr / .json
//   skyservice showcase                the views of `./sky run` into a folder, plus a contact sheet
// Exit codes: 0 ok (the service: clean shutdown after SIGTERM/SIGINT), 1 runtime failure, 2 bad command
// line, config or values, 3 unreadable weather (render).
#include "skyservice/app/commands.h"

#ifdef SKY_HAVE_SERVICE
#include "skyservice/render/view_limits.h"
#include "skyservice/service/daemon.h"
#endif

#include <CLI/CLI.hpp>
#include <vector>

namespace
{

using namespace sky;

CLI::App* addRenderCommand(CLI::App& app, RenderCommandOptions& render)
{
    CLI::App* cmd = app.add_subcommand("render", "Render one view to PREFIX.png, PREFIX.exr and PREFIX.json");
    addCommonOptions(*cmd, render.common);
    ViewRequest& v = render.request;
    v.pose.altitudeM = 1500.0;
    v.pose.latDeg = 44.3;
    v.pose.lonDeg = 7.5;
    cmd->add_option("--lat", v.pose.latDeg, "Eye latitude (degrees)")->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--lon", v.pose.lonDeg, "Eye longitude (degrees)")->check(CLI::Range(-540.0, 540.0));
    cmd->add_option("--alt", v.pose.altitudeM, "Eye altitude above the WGS84 ellipsoid (metres)")
        ->check(CLI::Range(-500.0, 100000.0));
    cmd->add_option("--heading", v.pose.headingDeg, "Heading, clockwise from north (degrees)")
        ->check(CLI::Range(-360.0, 720.0));
    cmd->add_option("--pitch", v.pose.pitchDeg, "Pitch, + nose up (degrees)")->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--roll", v.pose.rollDeg, "Roll, + right wing down (degrees)")->check(CLI::Range(-180.0, 180.0));
    CLI::Option* fov =
        cmd->add_option("--fov", v.fovYDeg, "Vertical field of view (degrees)")->check(CLI::Range(sky::kMinFovYDeg, sky::kMaxFovYDeg));
    // An off-centre frustum (a display wall's channel): the four half-angles together, instead of --fov.
    const struct
    {
        const char* name;
        double* deg;
        const char* help;
    } halfAngles[] = {
        {"--left", &v.frustum.leftDeg, "Off-centre frustum: angle from the view axis to the left edge (degrees)"},
        {"--right", &v.frustum.rightDeg, "Off-centre frustum: angle from the view axis to the right edge (degrees)"},
        {"--up", &v.frustum.upDeg, "Off-centre frustum: angle from the view axis to the upper edge (degrees)"},
        {"--down", &v.frustum.downDeg, "Off-centre frustum: angle from the view axis to the lower edge (degrees)"},
    };
    std::vector<CLI::Option*> angles;
    for (const auto& a : halfAngles)
    {
        double* deg = a.deg;
        angles.push_back(cmd->add_option_function<double>(
                                a.name,
                                [&v, deg](const double& value) {
                                    *deg = value;
                                    v.frustum.asymmetric = true;
                                },
                                a.help)
                             ->check(CLI::Range(-sky::kMaxFrustumHalfAngleDeg, sky::kMaxFrustumHalfAngleDeg))
                             ->excludes(fov));
    }
    for (CLI::Option* a : angles)
        for (CLI::Option* b : angles)
            if (a != b)
                a->needs(b);
    cmd->add_option("--width", v.width, "Image width (pixels)")->check(CLI::Range(8, 8192));
    cmd->add_option("--height", v.height, "Image height (pixels)")->check(CLI::Range(8, 8192));
    cmd->add_option("--time", render.time, "UTC time, ISO 8601 (e.g. 2026-06-21T12:00:00Z)");
    cmd->add_option("--weather", render.weather, "builtin, or a snapshot file written by sky-ingest");
    cmd->add_option("--out", render.out, "Output prefix: writes PREFIX.png, PREFIX.exr, PREFIX.json");
    cmd->add_flag("--no-detail", render.noDetail, "Skip detail erosion");
    cmd->add_flag("--no-high-cloud", render.noHighCloud, "Skip the cirrus layer");
    cmd->add_flag("--reference", render.reference,
                  "Path-trace the clouds (every order of scattering) instead of the real-time march");
    cmd->add_option("--spp", render.referenceSpp, "--reference: samples per pixel (default 64)")
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--phase", render.referencePhase,
                    "--reference: phase function: model (the two-lobe HG) or mie (HG + Draine, Jendersie & d'Eon)")
        ->check(CLI::IsMember({"model", "mie"}));
    cmd->add_option("--droplet-um", render.dropletDiameterUm, "--reference --phase mie: droplet diameter (um)")
        ->check(CLI::Range(1.5, 50.0));
    addShadowMapOptions(*cmd, v);
    return cmd;
}

CLI::App* addShowcaseCommand(CLI::App& app, ShowcaseOptions& showcase)
{
    CLI::App* cmd = app.add_subcommand("showcase", "Render the showcase views and a contact sheet");
    addCommonOptions(*cmd, showcase.common);
    cmd->add_option("--out", showcase.outDir, "Output folder");
    cmd->add_option("--width", showcase.width, "Image width (pixels)")->check(CLI::Range(8, 8192));
    cmd->add_option("--height", showcase.height, "Image height (pixels)")->check(CLI::Range(8, 8192));
    cmd->add_option("--reference-spp", showcase.referenceSpp,
                    "look-reference-pairs.png: samples per pixel of the path-traced reference (0: skip the pairs)")
        ->check(CLI::Range(0, 4096));
    return cmd;
}

#ifdef SKY_HAVE_SERVICE
void addDaemonOptions(CLI::App& app, DaemonOptions& d)
{
    app.add_option("--config", d.config, "Service config: [service] and renderer sections (see config/service.toml)");
    app.add_option("--socket", d.socket, "Control socket path (overrides service.socket_path)");
    app.add_option("--weather-dir", d.weatherDir, "Folder watched for *.skywx snapshots (overrides service.weather_dir)");
    app.add_option("--log-level", d.logLevel, "error | warn | info | debug (overrides service.log_level)");
    app.add_option("--device", d.device, "Vulkan device: index or part of its name (overrides service.device)");
    app.add_flag("--validate", d.validate, "Enable the Vulkan validation layers (any message: exit 1)");
    app.add_option("--cigi-port", d.cigiPort, "CIGI 3.3: UDP port the host sends to (overrides cigi.port)")
        ->check(CLI::Range(int64_t(1), int64_t(65534)));
    app.add_option("--cigi-host-port", d.cigiHostPort, "CIGI: port replies go to on the host (default: port + 1)")
        ->check(CLI::Range(int64_t(1), int64_t(65535)));
    app.add_option("--cigi-view-id", d.cigiViewId, "CIGI: the view (View Definition) this daemon renders")
        ->check(CLI::Range(int64_t(0), int64_t(65535)));
    app.add_option("--cigi-ownship", d.cigiOwnship, "CIGI: the entity whose pose drives the eye")
        ->check(CLI::Range(int64_t(0), int64_t(65535)));
}
#endif

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"skyservice: volumetric clouds on a WGS84 earth, rendered headless with Vulkan.\n"
                 "Without a subcommand it runs the service until SIGTERM/SIGINT (SIGHUP reloads --config).\n"
                 "Exit codes: 0 ok / clean shutdown, 1 runtime failure, 2 bad command line or config,\n"
                 "3 unreadable weather (render)."};
    RenderCommandOptions render;
    ShowcaseOptions showcase;
    CLI::App* renderCmd = addRenderCommand(app, render);
    CLI::App* showcaseCmd = addShowcaseCommand(app, showcase);
#ifdef SKY_HAVE_SERVICE
    app.require_subcommand(0, 1);
    DaemonOptions daemon;
    addDaemonOptions(app, daemon);
#else
    app.require_subcommand(1);
#endif
    try
    {
        app.parse(argc, argv);
    }
    catch (const CLI::ParseError& e)
    {
        int code = app.exit(e);
        return code == 0 ? kExitOk : kExitUsage;
    }
    if (renderCmd->parsed())
        return runRenderCommand(render);
    if (showcaseCmd->parsed())
        return runShowcaseCommand(showcase);
#ifdef SKY_HAVE_SERVICE
    return runDaemon(daemon);
#else
    return kExitUsage;
#endif
}
