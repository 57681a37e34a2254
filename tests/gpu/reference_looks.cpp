// SPDX-License-Identifier: MIT
// sky-reference-looks: the look views of issue 22 rendered in real time and by the reference path tracer
// (skyservice/render/reference_renderer.h), side by side in OUT/reference-looks.png, with the statistics
// the real-time lighting is to match printed per view. A measurement, not a test: minutes on lavapipe.
//
//   sky-reference-looks [OUT_DIR] [SAMPLES_PER_PIXEL] [WIDTH HEIGHT]     (defaults: out 64 160 90)
//
// Statistics over the cloud pixels (alpha > 0.5 in each render's own cloud image), luminance of the cloud
// radiance / alpha (Rec. 709 weights, pre-exposed like the EXR files, the same exposure in both):
//  - median: the median luminance;
//  - underside/top: the median luminance of the cloud pixels whose first-collision altitude (eye altitude
//    + depth along the ray, on the sphere) lies in the lowest fifth of those pixels' altitudes, over that of
//    the highest fifth. From below that compares the bases with the sunlit towers; it is a stand-in for the
//    issue's underside / sunlit-side ratio that needs no cloud segmentation.
#include "skyservice/output/contact_sheet.h"
#include "skyservice/render/reference_renderer.h"
#include "skyservice/sky/builtin_weather.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace sky;

namespace
{

struct LookStats
{
    size_t cloudPixels = 0;
    double medianLuminance = 0;
    double undersideOverTop = 0;
};

double median(std::vector<double> v)
{
    if (v.empty())
        return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

LookStats measure(const ViewRequest& view, const RenderResult& r)
{
    const CameraFrame camera = computeCameraFrame(view.pose);
    const double radiusM = 6371000.0;
    struct Pixel
    {
        double luminance, altitudeM;
    };
    std::vector<Pixel> cloud;
    for (uint32_t y = 0; y < r.height; ++y)
        for (uint32_t x = 0; x < r.width; ++x)
        {
            const size_t i = size_t(y) * r.width + x;
            const double a = double(glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + 3]));
            if (a <= 0.5)
                continue;
            double rgb[3];
            for (int c = 0; c < 3; ++c)
                rgb[c] = double(glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + size_t(c)])) / a;
            const glm::dvec3 dir = testscenes::pixelRayEnu(camera, view, x + 0.5, y + 0.5);
            const double t = double(r.cloudDepthM[i]);
            const double altitude = view.pose.altitudeM + t * dir.z + t * t * (1.0 - dir.z * dir.z) / (2.0 * radiusM);
            cloud.push_back({0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2], altitude});
        }
    LookStats s;
    s.cloudPixels = cloud.size();
    std::vector<double> lum;
    for (const Pixel& p : cloud)
        lum.push_back(p.luminance);
    s.medianLuminance = median(lum);
    std::sort(cloud.begin(), cloud.end(), [](const Pixel& a, const Pixel& b) { return a.altitudeM < b.altitudeM; });
    const size_t fifth = cloud.size() / 5;
    if (fifth > 0)
    {
        std::vector<double> low, high;
        for (size_t k = 0; k < fifth; ++k)
        {
            low.push_back(cloud[k].luminance);
            high.push_back(cloud[cloud.size() - 1 - k].luminance);
        }
        const double top = median(high);
        s.undersideOverTop = top > 0 ? median(low) / top : 0.0;
    }
    return s;
}

struct Look
{
    const char* name;
    double altM, pitchDeg, headingDeg;
};

}  // namespace

int main(int argc, char** argv)
{
    const std::string outDir = argc > 1 ? argv[1] : "out";
    ReferenceSettings settings;
    settings.samplesPerPixel = argc > 2 ? uint32_t(std::stoul(argv[2])) : 64u;
    const uint32_t width = argc > 4 ? uint32_t(std::stoul(argv[3])) : 160u;
    const uint32_t height = argc > 4 ? uint32_t(std::stoul(argv[4])) : 90u;

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
        {"under cumulus, 500 m, pitch 10", 500.0, 10.0, 0.0},
        {"among cumulus, 1500 m", 1500.0, 0.0, 0.0},
        {"cumulus from above, 4000 m", 4000.0, -15.0, 0.0},
    };
    std::vector<ImageRgba8> tiles;
    std::vector<std::string> captions;
    QualitySettings quality = testscenes::testQuality();
    std::printf("%-34s %8s %10s %10s %12s %12s %8s\n", "view", "pixels", "median RT", "median ref", "under/top RT",
                "under/top ref", "ref s");
    for (const Look& look : looks)
    {
        ViewRequest view = testscenes::lookUp(44.3, 7.5, look.altM, look.pitchDeg, "2026-06-21T12:00:00Z");
        view.pose.headingDeg = look.headingDeg;
        view.width = width;
        view.height = height;
        RenderResult realTime, path;
        status = renderView(renderer, view, quality, realTime);
        if (status.ok())
            status = renderReference(renderer, reference, view, quality, settings, path);
        if (!status.ok())
        {
            std::fprintf(stderr, "sky-reference-looks: %s: %s\n", look.name, status.message.c_str());
            break;
        }
        const LookStats a = measure(view, realTime);
        const LookStats b = measure(view, path);
        std::printf("%-34s %8zu %10.4f %10.4f %12.3f %12.3f %8.1f\n", look.name, b.cloudPixels, a.medianLuminance,
                    b.medianLuminance, a.undersideOverTop, b.undersideOverTop, reference.last.seconds);
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
    std::string error;
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
