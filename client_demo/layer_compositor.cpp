// SPDX-License-Identifier: MIT
#include "client_demo/layer_compositor.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <thread>
#include <vector>

namespace demo
{

glm::dvec3 compositeOverScene(const glm::dvec3& sky, const glm::dvec4& clouds, double cloudFrontM,
                              const SceneSample& scene)
{
    const glm::dvec3 cloudRgb(clouds.r, clouds.g, clouds.b);
    const double alpha = std::clamp(clouds.a, 0.0, 1.0);
    if (!scene.hit)
        return sky * (1.0 - alpha) + cloudRgb;
    // A cloud without a depth (a reprojected pixel filled from fresh neighbours that saw no cloud) is put in
    // front: dropping it cut dark notches into cloud edges over the terrain. A scene point nearer than the
    // cloud's front has (almost) no cloud before it: the weighted distance, deeper inside, would hide the
    // cloud in front of a hill that stands in the cloud's first hundreds of metres.
    if (alpha <= 0.0 || (cloudFrontM > 0.0 && scene.distanceM < cloudFrontM))
        return scene.radiance;
    return scene.radiance * (1.0 - alpha) + cloudRgb;
}

glm::dvec3 hazeTerrain(const glm::dvec3& terrain, const glm::dvec3& sky, double distanceM, double hazeM)
{
    const double seen = hazeM > 0.0 ? std::exp(-std::max(distanceM, 0.0) / hazeM) : 1.0;
    return terrain * seen + sky * (1.0 - seen);
}

glm::dvec3 tonemapAces(const glm::dvec3& x)
{
    constexpr double a = 2.51;
    constexpr double b = 0.03;
    constexpr double c = 2.43;
    constexpr double d = 0.59;
    constexpr double e = 0.14;
    glm::dvec3 y;
    for (int k = 0; k < 3; ++k)
    {
        const double v = std::max(x[k], 0.0);
        y[k] = std::clamp(v * (a * v + b) / (v * (c * v + d) + e), 0.0, 1.0);
    }
    return y;
}

double encodeSrgb(double c)
{
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

void toDisplayRgb8(const glm::dvec3& linear, uint8_t* rgb)
{
    const glm::dvec3 mapped = tonemapAces(linear);
    for (int k = 0; k < 3; ++k)
        rgb[k] = uint8_t(std::lround(encodeSrgb(mapped[k]) * 255.0));
}

TerrainLight terrainLightOf(const LatestFrame& frame)
{
    TerrainLight light;
    if (frame.shadowSize > 0)
    {
        light.elevationDeg = frame.shadow.sun_elevation_deg;
        light.azimuthDeg = frame.shadow.sun_azimuth_deg;
        light.isMoon = frame.shadow.light_is_moon != 0;
    }
    return light;
}

CloudLayerEstimate cloudLayerOf(const LatestFrame& frame, const GroundCamera& camera)
{
    std::vector<double> heights;
    for (uint32_t y = 0; y < frame.height; ++y)
        for (uint32_t x = 0; x < frame.width; ++x)
        {
            const size_t i = size_t(y) * frame.width + x;
            // The weighted distance (G): it lies inside the cloud, the front on its skin.
            const float weightedM = frame.depthM[2 * i + 1];
            if (frame.cloudsRgba[4 * i + 3] >= 0.5f && weightedM > 0.0f)
                heights.push_back(rayHeightM(camera, viewRay(camera, x + 0.5, y + 0.5), weightedM));
        }
    CloudLayerEstimate layer;
    if (heights.size() < 16)
        return layer;
    auto percentile = [&](double p) {
        auto at = heights.begin() + std::ptrdiff_t(p * double(heights.size() - 1));
        std::nth_element(heights.begin(), at, heights.end());
        return *at;
    };
    layer.valid = true;
    layer.baseM = percentile(0.05);
    layer.topM = percentile(0.95);
    const double widenM = std::max(0.0, 200.0 - (layer.topM - layer.baseM)) * 0.5;
    layer.baseM -= widenM;
    layer.topM += widenM;
    return layer;
}

double keyTransmittanceAt(double groundTransmittance, double heightM, const CloudLayerEstimate& layer)
{
    const double t = std::clamp(groundTransmittance, 0.0, 1.0);
    if (!layer.valid)
        return t;
    const double above = std::clamp((layer.topM - heightM) / (layer.topM - layer.baseM), 0.0, 1.0);
    return above > 0.0 ? std::pow(t, above) : 1.0;
}

namespace
{

// What one pixel's compositing needs besides the frame, made once per frame.
struct FrameScene
{
    GroundCamera camera;
    LocalTerrain terrain;
    TerrainLight light;
    CloudLayerEstimate cloudLayer;
    std::array<double, 2> eyeInMap{0.0, 0.0};
};

// Composites rows [y0, y1) into out, counting into stats.
void compositeRows(const LatestFrame& frame, const CompositeOptions& options, const FrameScene& scene, uint32_t y0,
                   uint32_t y1, sky::ImageRgba8& out, CompositeStats& stats)
{
    for (uint32_t y = y0; y < y1; ++y)
        for (uint32_t x = 0; x < frame.width; ++x)
        {
            const size_t i = size_t(y) * frame.width + x;
            const float* s = &frame.skyRgba[4 * i];
            const float* c = &frame.cloudsRgba[4 * i];
            const glm::dvec3 sky(s[0], s[1], s[2]);
            const glm::dvec4 clouds(c[0], c[1], c[2], c[3]);
            const double frontM = frame.depthM[2 * i];  // the depth layer's R: the cloud's front
            SceneSample sample;
            TerrainHit hit;
            if (options.ground &&
                intersectTerrain(scene.camera, scene.terrain, viewRay(scene.camera, x + 0.5, y + 0.5), hit))
            {
                const std::array<double, 2> footprint = shadowFootprintM(hit, scene.light);
                const double keyTransmittance = keyTransmittanceAt(
                    shadowTransmittanceAt(frame.shadowTransmittance, frame.shadowSize, frame.shadow.extent_m,
                                          scene.eyeInMap[0] + footprint[0], scene.eyeInMap[1] + footprint[1]),
                    hit.heightM, scene.cloudLayer);
                GroundHit at;
                at.eastM = hit.eastM;
                at.northM = hit.northM;
                const std::array<double, 2> latLon = groundLatLonDeg(scene.camera, at);
                const glm::dvec3 lit = shadeTerrainLinear(hit, latLon[0], latLon[1], scene.light, keyTransmittance);
                sample.hit = true;
                sample.distanceM = hit.distanceM;
                sample.radiance = hazeTerrain(lit, sky, hit.distanceM, options.hazeM);
                ++stats.terrainPixels;
                if (clouds.a > 0.0 && frontM > 0.0)
                    ++(hit.distanceM < frontM ? stats.terrainInFrontPixels : stats.terrainBehindCloudPixels);
            }
            toDisplayRgb8(compositeOverScene(sky, clouds, frontM, sample), out.pixel(x, y));
        }
}

}  // namespace

void compositeLayers(const LatestFrame& frame, const CompositeOptions& options, sky::ImageRgba8& out,
                     CompositeStats* stats)
{
    out.width = frame.width;
    out.height = frame.height;
    out.pixels.assign(size_t(frame.width) * frame.height * 4, 255);

    SkyShmView view = frame.view;
    view.width = frame.width;
    view.height = frame.height;
    FrameScene scene;
    scene.camera = makeGroundCamera(view);
    scene.terrain = localTerrain(options.terrain, scene.camera);
    scene.light = terrainLightOf(frame);
    if (frame.shadowSize > 0 && options.ground)
    {
        scene.cloudLayer = cloudLayerOf(frame, scene.camera);
        scene.eyeInMap = offsetFromShadowCentreM(view.lat_deg, view.lon_deg, frame.shadow);
    }

    // The terrain's ray march is too slow for one core at the display's rate: bands of rows
    // on the machine's cores. Each band writes its own rows and counts into its own stats.
    const uint32_t cores = std::max(1u, std::min(std::thread::hardware_concurrency(), 16u));
    const uint32_t bands = std::max(1u, std::min(cores, frame.height / 16));
    std::vector<CompositeStats> counted(bands);
    std::vector<std::thread> workers;
    for (uint32_t b = 1; b < bands; ++b)
        workers.emplace_back(compositeRows, std::cref(frame), std::cref(options), std::cref(scene),
                             frame.height * b / bands, frame.height * (b + 1) / bands, std::ref(out),
                             std::ref(counted[b]));
    compositeRows(frame, options, scene, 0, frame.height / bands, out, counted[0]);
    for (std::thread& w : workers)
        w.join();
    if (!stats)
        return;
    *stats = CompositeStats{};
    stats->mode = CompositeMode::Layers;
    for (const CompositeStats& c : counted)
    {
        stats->terrainPixels += c.terrainPixels;
        stats->terrainInFrontPixels += c.terrainInFrontPixels;
        stats->terrainBehindCloudPixels += c.terrainBehindCloudPixels;
    }
}

}  // namespace demo
