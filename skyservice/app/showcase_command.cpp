// SPDX-License-Identifier: MIT
// `skyservice showcase` (what `./sky run` runs): the views that show what the product does, rendered
// from the built-in weather, plus a captioned contact sheet.
#include "skyservice/app/commands.h"

#include "skyservice/app/render_files.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/output/image_files.h"
#include "skyservice/render/renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "skyservice/sky/ephemeris.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace sky
{
namespace
{

struct ShowcaseView
{
    const char* name;
    const char* caption;
    EyePose pose;
    double fovYDeg;
    const char* timeIso;
};

// Metres -> degrees of longitude at a latitude, for placing eyes relative to the built-in clouds.
double lonOffsetDeg(double metres, double latDeg) { return metres / (111320.0 * std::cos(latDeg * M_PI / 180.0)); }

std::vector<ShowcaseView> showcaseViews()
{
    const double cbLat = kBuiltinCumulonimbusLatDeg, cbLon = kBuiltinCumulonimbusLonDeg;
    return {
        {"cumulus-midday", "Scattered cumulus at midday from 600 m",
         {kBuiltinCumulusLatDeg - 0.35, kBuiltinCumulusLonDeg, 600.0, 10.0, 8.0, 0.0}, 60.0, "2026-06-21T11:30:00Z"},
        {"cumulonimbus-40km", "Cumulonimbus and anvil from 40 km",
         {cbLat, cbLon - lonOffsetDeg(40000.0, cbLat), 4500.0, 90.0, 6.0, 0.0}, 60.0, "2026-06-21T15:00:00Z"},
        {"deck-sunset", "Sunset over the stratocumulus deck",
         {kBuiltinDeckLatDeg, kBuiltinDeckLonDeg + 0.6, 2600.0, 300.0, 1.0, 0.0}, 60.0, "2026-06-21T19:15:00Z"},
        {"deck-above-11000m", "The deck from 11 000 m: the earth's curvature",
         {kBuiltinDeckLatDeg, kBuiltinDeckLonDeg + 1.0, 11000.0, 250.0, -8.0, 0.0}, 70.0, "2026-06-21T09:30:00Z"},
    };
}

}  // namespace

int runShowcaseCommand(const ShowcaseOptions& options)
{
    QualitySettings quality;
    std::string error;
    if (!qualityFromOptions(options.common, quality, error))
    {
        std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
        return kExitUsage;
    }
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec)
    {
        std::fprintf(stderr, "skyservice showcase: cannot create %s: %s\n", options.outDir.c_str(), ec.message().c_str());
        return kExitRuntime;
    }

    Renderer renderer;
    RendererOptions ro;
    ro.context.deviceSelector = options.common.device;
    ro.context.validation = options.common.validate;
    ro.noiseSeed = options.common.seed;
    SkyStatus status = createRenderer(renderer, ro);
    if (!status.ok())
    {
        std::fprintf(stderr, "skyservice showcase: %s\n", status.message.c_str());
        destroyRenderer(renderer);
        return kExitRuntime;
    }

    std::vector<ImageRgba8> tiles;
    std::vector<std::string> captions;
    int code = kExitOk;
    for (const ShowcaseView& view : showcaseViews())
    {
        ViewRequest request;
        request.pose = view.pose;
        request.fovYDeg = view.fovYDeg;
        request.width = options.width;
        request.height = options.height;
        parseIso8601Utc(view.timeIso, request.unixTimeS, error);
        setWeather(renderer, makeBuiltinWeather(request.unixTimeS));
        auto start = std::chrono::steady_clock::now();
        RenderResult result;
        status = renderView(renderer, request, quality, result);
        if (!status.ok())
        {
            std::fprintf(stderr, "skyservice showcase: %s: %s\n", view.name, status.message.c_str());
            code = kExitRuntime;
            break;
        }
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        RenderFacts facts;
        facts.weatherSource = "builtin";
        facts.timeIso = view.timeIso;
        facts.deviceName = renderer.ctx.deviceName;
        facts.driver = renderer.ctx.driverInfo;
        facts.caption = view.caption;
        facts.quality = qualityToJson(quality);
        std::string prefix = options.outDir + "/" + view.name;
        if (!writeRenderFiles(prefix, request, result, facts, error))
        {
            std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
            code = kExitRuntime;
            break;
        }
        std::printf("%-20s %s  (sun %.1f deg, %.1f s wall)\n", view.name, view.caption, result.sunElevationDeg, seconds);
        std::fflush(stdout);
        tiles.push_back({result.width, result.height, result.displayRgba8});
        captions.push_back(view.caption);
    }
    if (code == kExitOk)
    {
        ImageRgba8 sheet = makeContactSheet(tiles, captions, 2);
        if (!writePng(options.outDir + "/contact-sheet.png", sheet, error))
        {
            std::fprintf(stderr, "skyservice showcase: %s\n", error.c_str());
            code = kExitRuntime;
        }
        else
            std::printf("wrote %s/contact-sheet.png\n", options.outDir.c_str());
    }
    if (options.common.validate && renderer.ctx.validationMessages.load() > 0)
        code = kExitRuntime;
    destroyRenderer(renderer);
    return code;
}

}  // namespace sky
