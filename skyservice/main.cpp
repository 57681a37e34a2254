// SPDX-License-Identifier: MIT
// skyservice: the sky service's command line. Subcommands:
//   render    one view to PREFIX.png / .exr / .json
//   showcase  the views of `./sky run` into a folder, plus a contact sheet
// Exit codes: 0 ok, 1 runtime failure, 2 bad command line or values, 3 unreadable weather.
#include "skyservice/app/commands.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv)
{
    using namespace sky;
    CLI::App app{"skyservice: volumetric clouds on a WGS84 earth, rendered headless with Vulkan"};
    app.require_subcommand(1);

    RenderCommandOptions render;
    CLI::App* renderCmd = app.add_subcommand("render", "Render one view to PREFIX.png, PREFIX.exr and PREFIX.json");
    addCommonOptions(*renderCmd, render.common);
    ViewRequest& v = render.request;
    v.pose.altitudeM = 1500.0;
    v.pose.latDeg = 44.3;
    v.pose.lonDeg = 7.5;
    renderCmd->add_option("--lat", v.pose.latDeg, "Eye latitude (degrees)")->check(CLI::Range(-90.0, 90.0));
    renderCmd->add_option("--lon", v.pose.lonDeg, "Eye longitude (degrees)")->check(CLI::Range(-540.0, 540.0));
    renderCmd->add_option("--alt", v.pose.altitudeM, "Eye altitude above the WGS84 ellipsoid (metres)")
        ->check(CLI::Range(-500.0, 100000.0));
    renderCmd->add_option("--heading", v.pose.headingDeg, "Heading, clockwise from north (degrees)")
        ->check(CLI::Range(-360.0, 720.0));
    renderCmd->add_option("--pitch", v.pose.pitchDeg, "Pitch, + nose up (degrees)")->check(CLI::Range(-90.0, 90.0));
    renderCmd->add_option("--roll", v.pose.rollDeg, "Roll, + right wing down (degrees)")->check(CLI::Range(-180.0, 180.0));
    renderCmd->add_option("--fov", v.fovYDeg, "Vertical field of view (degrees)")->check(CLI::Range(1.0, 170.0));
    renderCmd->add_option("--width", v.width, "Image width (pixels)")->check(CLI::Range(8, 8192));
    renderCmd->add_option("--height", v.height, "Image height (pixels)")->check(CLI::Range(8, 8192));
    renderCmd->add_option("--time", render.time, "UTC time, ISO 8601 (e.g. 2026-06-21T12:00:00Z)");
    renderCmd->add_option("--weather", render.weather, "builtin, or a snapshot file written by sky-ingest");
    renderCmd->add_option("--out", render.out, "Output prefix: writes PREFIX.png, PREFIX.exr, PREFIX.json");
    renderCmd->add_flag("--no-detail", render.noDetail, "Skip detail erosion");
    renderCmd->add_flag("--no-high-cloud", render.noHighCloud, "Skip the cirrus layer");
    addShadowMapOptions(*renderCmd, v);

    ShowcaseOptions showcase;
    CLI::App* showcaseCmd = app.add_subcommand("showcase", "Render the showcase views and a contact sheet");
    addCommonOptions(*showcaseCmd, showcase.common);
    showcaseCmd->add_option("--out", showcase.outDir, "Output folder");
    showcaseCmd->add_option("--width", showcase.width, "Image width (pixels)")->check(CLI::Range(8, 8192));
    showcaseCmd->add_option("--height", showcase.height, "Image height (pixels)")->check(CLI::Range(8, 8192));

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
    return runShowcaseCommand(showcase);
}
