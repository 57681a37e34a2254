// SPDX-License-Identifier: MIT
#include "client_demo/compositor.h"

#include "client_demo/ground_shading.h"
#include "client_demo/layer_compositor.h"

#include <algorithm>
#include <cmath>

namespace demo
{
namespace
{

// Rec. 709 luma of sRGB-encoded bytes (display space is fine for a brightness comparison).
double lumaOf(const uint8_t* p) { return (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0; }

double smoothstep(double e0, double e1, double x)
{
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

}  // namespace

GroundLight groundLightOf(const LatestFrame& frame)
{
    GroundLight light;
    if (frame.shadowSize > 0)
    {
        light.sunElevationDeg = frame.shadow.sun_elevation_deg;
        light.isMoon = frame.shadow.light_is_moon != 0;
    }
    return light;
}

void compositeFrame(const LatestFrame& frame, const CompositeOptions& options, sky::ImageRgba8& out,
                    CompositeStats* stats)
{
    if (options.mode == CompositeMode::Layers && frame.hasLayers())
    {
        compositeLayers(frame, options, out, stats);
        return;
    }
    if (stats)
        *stats = CompositeStats{};
    out.width = frame.width;
    out.height = frame.height;
    out.pixels = frame.rgba;
    out.pixels.resize(size_t(frame.width) * frame.height * 4, 0);
    if (!options.ground || frame.width == 0 || frame.height == 0)
        return;

    SkyShmView view = frame.view;
    view.width = frame.width;
    view.height = frame.height;
    const GroundCamera camera = makeGroundCamera(view);
    const GroundLight light = groundLightOf(frame);
    const std::array<double, 2> eyeInMap = frame.shadowSize > 0
                                               ? offsetFromShadowCentreM(view.lat_deg, view.lon_deg, frame.shadow)
                                               : std::array<double, 2>{0.0, 0.0};

    // Pass 1: which pixels are ground, and the frame's mean brightness there (the reference for "this
    // pixel is much brighter than ground: a cloud below the eye").
    std::vector<GroundHit> hits(size_t(frame.width) * frame.height);
    std::vector<uint8_t> isGround(hits.size(), 0);
    double lumaSum = 0.0;
    size_t groundCount = 0;
    for (uint32_t y = 0; y < frame.height; ++y)
        for (uint32_t x = 0; x < frame.width; ++x)
        {
            const size_t i = size_t(y) * frame.width + x;
            if (!intersectGround(camera, viewRay(camera, x + 0.5, y + 0.5), hits[i]))
                continue;
            isGround[i] = 1;
            lumaSum += lumaOf(out.pixel(x, y));
            ++groundCount;
        }
    if (groundCount == 0)
        return;
    const double meanGroundLuma = lumaSum / double(groundCount);

    for (uint32_t y = 0; y < frame.height; ++y)
        for (uint32_t x = 0; x < frame.width; ++x)
        {
            const size_t i = size_t(y) * frame.width + x;
            if (!isGround[i])
                continue;
            const GroundHit& hit = hits[i];
            const std::array<double, 2> latLon = groundLatLonDeg(camera, hit);
            const double shadow = shadowTransmittanceAt(frame.shadowTransmittance, frame.shadowSize,
                                                        frame.shadow.extent_m, eyeInMap[0] + hit.eastM,
                                                        eyeInMap[1] + hit.northM);
            const glm::dvec3 ground = shadeGround(latLon[0], latLon[1], light, shadow);
            uint8_t* p = out.pixel(x, y);
            const double cloudLike = smoothstep(meanGroundLuma + 0.08, meanGroundLuma + 0.25, lumaOf(p));
            const double w = options.groundOpacity * std::exp(-hit.distanceM / options.groundFadeM) * (1.0 - cloudLike);
            for (int k = 0; k < 3; ++k)
            {
                const double mixed = (1.0 - w) * p[k] / 255.0 + w * ground[k];
                p[k] = uint8_t(std::lround(std::clamp(mixed, 0.0, 1.0) * 255.0));
            }
        }
}

}  // namespace demo
