// SPDX-License-Identifier: MIT
// sky-reference-looks: the look views of issue 22 rendered in real time and by the reference path tracer
// (skyservice/render/reference_renderer.h), side by side in OUT/reference-looks.png, with the statistics
// the real-time lighting is to match printed per view (tests/gpu/look_stats.h says what they are). A
// measurement, not a test: minutes on lavapipe.
//
//   sky-reference-looks [OUT_DIR] [SAMPLES_PER_PIXEL] [WIDTH HEIGHT] [--config FILE] [--cache DIR] [--views LIST]
//     defaults: out 64 160 90. --config: a quality file (docs/config.md keys) over the test quality, for
//     tuning the real-time lighting; the reference takes the same file (its phase function is the model's).
//     --cache: the path-traced cloud layers are kept in DIR per view, size and samples and read back when
//     there (the reference depends only on the view, the model and the samples, not on the real-time light).
//     --views: the views to render, by key, comma-separated (under, among, above; default all): the view from
//     above is by far the slowest to path-trace.
#include "skyservice/app/config_file.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/render/reference_renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/look_stats.h"
#include "tests/gpu/scenes.h"

#include <cstdio>
#include <string>
#include <vector>

using namespace sky;

namespace
{

struct Look
{
    const char* name;
    const char* key;  // the cache file's name
    double altM, pitchDeg, headingDeg;
};

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> positional;
    std::string configPath, cacheDir, views = "under,among,above";
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if ((arg == "--config" || arg == "--cache" || arg == "--views") && i + 1 < argc)
            (arg == "--config" ? configPath : arg == "--cache" ? cacheDir : views) = argv[++i];
        else
            positional.push_back(arg);
    }
    const std::string outDir = positional.size() > 0 ? positional[0] : "out";
    ReferenceSettings settings;
    settings.samplesPerPixel = positional.size() > 1 ? uint32_t(std::stoul(positional[1])) : 64u;
    const uint32_t width = positional.size() > 3 ? uint32_t(std::stoul(positional[2])) : 160u;
    const uint32_t height = positional.size() > 3 ? uint32_t(std::stoul(positional[3])) : 90u;
    QualitySettings quality = testscenes::testQuality();
    std::string error;
    if (!configPath.empty() && !applyConfigFile(configPath, quality, error))
    {
        std::fprintf(stderr, "sky-reference-looks: %s\n", error.c_str());
        return 2;
    }

    Renderer renderer;
    RendererOptions options;
    options.context.quiet = true;
    SkyStatus status = createRenderer(renderer, options);
    ReferenceRenderer reference;
    if (status.ok())
        status = createReferenceRenderer(renderer, reference);
    if (!status.ok())
    {
        std::fprintf(stderr, "sky-reference-looks: %s\n", status.message.c_str());
        return 1;
    }
    setWeather(renderer, makeBuiltinWeather(0));
    // The views of issue 22 at 44.3 N 7.5 E (the built-in cumulus, base 1200 m), 2026-06-21 noon UTC.
    const Look looks[] = {
        {"under cumulus, 500 m, pitch 10", "under", 500.0, 10.0, 0.0},
        {"among cumulus, 1500 m", "among", 1500.0, 0.0, 0.0},
        {"cumulus from above, 4000 m", "above", 4000.0, -15.0, 0.0},
    };
    std::vector<ImageRgba8> tiles;
    std::vector<std::string> captions;
    std::printf("%-30s %6s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %6s\n", "view", "pixels", "median RT",
                "median ref", "u/top RT", "u/top ref", "under RT", "under ref", "top RT", "top ref", "mean RT",
                "mean ref", "u/t m RT", "u/t m ref", "ref s");
    for (const Look& look : looks)
    {
        if (("," + views + ",").find(std::string(",") + look.key + ",") == std::string::npos)
            continue;
        ViewRequest view = testscenes::lookUp(44.3, 7.5, look.altM, look.pitchDeg, "2026-06-21T12:00:00Z");
        view.pose.headingDeg = look.headingDeg;
        view.width = width;
        view.height = height;
        RenderResult realTime, path;
        path.width = width;
        path.height = height;
        const std::string cachePath = cacheDir.empty() ? std::string()
                                                       : cacheDir + "/" + look.key + "-" + std::to_string(width) + "x" +
                                                             std::to_string(height) + "-" +
                                                             std::to_string(settings.samplesPerPixel) + "spp.bin";
        double referenceS = 0.0;
        status = renderView(renderer, view, quality, realTime);
        if (status.ok() && (cachePath.empty() || !testscenes::loadCloudLayers(cachePath, path)))
        {
            status = renderReference(renderer, reference, view, quality, settings, path);
            referenceS = reference.last.seconds;
            if (status.ok() && !cachePath.empty() && !testscenes::saveCloudLayers(cachePath, path))
                std::fprintf(stderr, "sky-reference-looks: cannot write %s\n", cachePath.c_str());
        }
        if (!status.ok())
        {
            std::fprintf(stderr, "sky-reference-looks: %s: %s\n", look.name, status.message.c_str());
            break;
        }
        const testscenes::LookStats a = testscenes::measureLook(view, realTime);
        const testscenes::LookStats b = testscenes::measureLook(view, path);
        std::printf("%-30s %6zu %9.4f %9.4f %9.3f %9.3f %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f %9.3f %9.3f %6.1f\n",
                    look.name, b.cloudPixels, a.medianLuminance, b.medianLuminance, a.undersideOverTop,
                    b.undersideOverTop, a.undersideLuminance, b.undersideLuminance, a.topLuminance, b.topLuminance,
                    a.meanLuminance, b.meanLuminance, a.undersideOverTopOfMeans, b.undersideOverTopOfMeans, referenceS);
        std::fflush(stdout);
        for (const RenderResult* r : {&realTime, &path})
        {
            ImageRgba8 tile;
            tile.width = r->width;
            tile.height = r->height;
            tile.pixels = r->displayRgba8;
            tiles.push_back(tile);
        }
        captions.push_back(std::string(look.name) + ": real time");
        captions.push_back("reference " + std::to_string(settings.samplesPerPixel) + " spp");
    }
    const std::string path = outDir + "/reference-looks.png";
    if (!status.ok() || !writePng(path, makeContactSheet(tiles, captions, 2), error))
    {
        std::fprintf(stderr, "sky-reference-looks: %s\n", error.c_str());
        destroyReferenceRenderer(renderer, reference);
        destroyRenderer(renderer);
        return 1;
    }
    std::printf("wrote %s\n", path.c_str());
    destroyReferenceRenderer(renderer, reference);
    destroyRenderer(renderer);
    return 0;
}
