// SPDX-License-Identifier: MIT
// sky-reference-looks: the look views of the showcase's reference pairs (skyservice/app/reference_pairs.h)
// rendered in real time and by the reference path tracer, side by side in OUT/reference-looks.png, with the
// statistics the real-time lighting is to match printed per view (tests/gpu/look_stats.h says what they are).
// A measurement, not a test: minutes on lavapipe at its default size and samples.
//
//   sky-reference-looks [OUT_DIR] [SAMPLES_PER_PIXEL] [WIDTH HEIGHT] [--config FILE] [--cache DIR] [--views LIST]
//     defaults: out 64 160 90. --config: a quality file (docs/config.md keys) over the test quality, for
//     tuning the real-time lighting; the reference takes the same file (its phase function is the model's).
//     --cache: the path-traced cloud layers are kept in DIR per view, size and samples and read back when
//     there (the reference depends only on the view, the model and the samples, not on the real-time light).
//     --views: the views to render, each by a part of its name, comma-separated (under, among, above, sunset;
//     default all): the view from above is by far the slowest to path-trace.
#include "skyservice/app/config_file.h"
#include "skyservice/app/reference_pairs.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/look_stats.h"
#include "tests/gpu/scenes.h"

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

using namespace sky;

int main(int argc, char** argv)
{
    std::vector<std::string> positional;
    std::string configPath, cacheDir, views = "under,among,above,sunset";
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
    // The look views of the showcase's reference pairs (skyservice/app/look_views.h), each with the built-in
    // weather at its time; --views picks them by a part of their names.
    const std::vector<LookView> looks = lookViews();
    std::vector<ReferencePair> pairs;
    std::printf("%-30s %6s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %9s %6s\n", "view", "pixels", "median RT",
                "median ref", "u/top RT", "u/top ref", "under RT", "under ref", "top RT", "top ref", "mean RT",
                "mean ref", "u/t m RT", "u/t m ref", "ref s");
    for (const char* name : kReferencePairViews)
    {
        const LookView& look = *findLookView(looks, name);
        bool wanted = false;
        std::istringstream list(views);
        for (std::string part; std::getline(list, part, ',');)
            wanted = wanted || (!part.empty() && look.name.find(part) != std::string::npos);
        if (!wanted)
            continue;
        const ViewRequest view = lookViewRequest(look, width, height);
        setWeather(renderer, makeBuiltinWeather(view.unixTimeS));
        ReferencePair pair;
        pair.title = lookTitle(look);
        pair.reference.width = width;
        pair.reference.height = height;
        const std::string cachePath = cacheDir.empty() ? std::string()
                                                       : cacheDir + "/" + look.name + "-" + std::to_string(width) +
                                                             "x" + std::to_string(height) + "-" +
                                                             std::to_string(settings.samplesPerPixel) + "spp.bin";
        double referenceS = 0.0;
        status = renderView(renderer, view, quality, pair.realTime);
        if (status.ok() && (cachePath.empty() || !testscenes::loadCloudLayers(cachePath, pair.reference)))
        {
            status = renderReference(renderer, reference, view, quality, settings, pair.reference);
            referenceS = reference.last.seconds;
            if (status.ok() && !cachePath.empty() && !testscenes::saveCloudLayers(cachePath, pair.reference))
                std::fprintf(stderr, "sky-reference-looks: cannot write %s\n", cachePath.c_str());
        }
        if (!status.ok())
        {
            std::fprintf(stderr, "sky-reference-looks: %s: %s\n", look.name.c_str(), status.message.c_str());
            break;
        }
        const testscenes::LookStats a = testscenes::measureLook(view, pair.realTime);
        const testscenes::LookStats b = testscenes::measureLook(view, pair.reference);
        std::printf("%-30s %6zu %9.4f %9.4f %9.3f %9.3f %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f %9.3f %9.3f %6.1f\n",
                    pair.title.c_str(), b.cloudPixels, a.medianLuminance, b.medianLuminance, a.undersideOverTop,
                    b.undersideOverTop, a.undersideLuminance, b.undersideLuminance, a.topLuminance, b.topLuminance,
                    a.meanLuminance, b.meanLuminance, a.undersideOverTopOfMeans, b.undersideOverTopOfMeans, referenceS);
        std::fflush(stdout);
        pairs.push_back(std::move(pair));
    }
    const std::string path = outDir + "/reference-looks.png";
    if (!status.ok() || !writePng(path, makeReferencePairSheet(pairs, settings.samplesPerPixel), error))
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
