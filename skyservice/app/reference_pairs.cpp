// SPDX-License-Identifier: MIT
#include "skyservice/app/reference_pairs.h"

#include "skyservice/output/cloud_luminance.h"
#include "skyservice/output/contact_sheet.h"
#include "skyservice/sky/builtin_weather.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace sky
{

const char* const kReferencePairViews[4] = {"look-under-cumulus", "look-among-cumulus", "look-cumulus-above",
                                            "look-sunset-cumulus"};

namespace
{

/// Tiles are enlarged to about this width (pixels): 64 characters of caption at the font's scale 1.
constexpr uint32_t kPairTileWidthPx = 400;

ImageRgba8 displayOf(const RenderResult& r, uint32_t factor)
{
    return enlargeImage({r.width, r.height, r.displayRgba8}, factor);
}

}  // namespace

std::string lookTitle(const LookView& view)
{
    return view.caption.substr(0, view.caption.find(':'));
}

SkyStatus renderReferencePair(Renderer& r, ReferenceRenderer& ref, const ViewRequest& view,
                              const QualitySettings& quality, const ReferenceSettings& settings, ReferencePair& pair)
{
    SKY_TRY(renderView(r, view, quality, pair.realTime));
    SKY_TRY(renderReference(r, ref, view, quality, settings, pair.reference));
    pair.stats = ref.last;
    return SkyStatus::success();
}

ImageRgba8 makeReferencePairSheet(const std::vector<ReferencePair>& pairs, uint32_t samplesPerPixel)
{
    std::vector<ImageRgba8> tiles;
    std::vector<std::string> captions;
    char text[160];
    for (const ReferencePair& p : pairs)
    {
        const uint32_t factor = std::max(1u, kPairTileWidthPx / std::max(p.realTime.width, 1u));
        tiles.push_back(displayOf(p.realTime, factor));
        tiles.push_back(displayOf(p.reference, factor));
        std::snprintf(text, sizeof text, "%s - real time, median %.3f", p.title.c_str(),
                      medianCloudLuminance(p.realTime));
        captions.push_back(text);
        std::snprintf(text, sizeof text, "reference %u spp, median %.3f", samplesPerPixel,
                      medianCloudLuminance(p.reference));
        captions.push_back(text);
    }
    return makeContactSheet(tiles, captions, 2);
}

SkyStatus writeLookReferencePairs(Renderer& r, const QualitySettings& quality, uint32_t width, uint32_t height,
                                  uint32_t samplesPerPixel, const std::string& pngPath)
{
    ReferenceRenderer ref;
    SkyStatus status = createReferenceRenderer(r, ref);
    ReferenceSettings settings;
    settings.samplesPerPixel = samplesPerPixel;
    const std::vector<LookView> views = lookViews();
    std::vector<ReferencePair> pairs;
    for (const char* name : kReferencePairViews)
    {
        if (!status.ok())
            break;
        const LookView* view = findLookView(views, name);
        if (!view)
        {
            status = SkyStatus::failure(std::string("no look view ") + name);
            break;
        }
        const ViewRequest request = lookViewRequest(*view, width, height);
        setWeather(r, makeBuiltinWeather(request.unixTimeS));
        ReferencePair pair;
        pair.title = lookTitle(*view);
        const auto start = std::chrono::steady_clock::now();
        status = renderReferencePair(r, ref, request, quality, settings, pair);
        if (!status.ok())
        {
            status.message = std::string(name) + ": " + status.message;
            break;
        }
        std::printf("%-20s reference pair %ux%u, %u spp: median cloud luminance %.3f real time, %.3f reference "
                    "(%.1f s wall; %u dispatches, %llu samples cut)\n",
                    name, width, height, samplesPerPixel, medianCloudLuminance(pair.realTime),
                    medianCloudLuminance(pair.reference),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                    pair.stats.dispatches, static_cast<unsigned long long>(pair.stats.pathsCut));
        std::fflush(stdout);
        pairs.push_back(std::move(pair));
    }
    destroyReferenceRenderer(r, ref);
    std::string error;
    if (status.ok() && !writePng(pngPath, makeReferencePairSheet(pairs, samplesPerPixel), error))
        status = SkyStatus::failure(error);
    return status;
}

}  // namespace sky
