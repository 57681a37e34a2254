// SPDX-License-Identifier: MIT
#include "tests/gpu/look_stats.h"

#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

namespace sky::testscenes
{

namespace
{

double median(std::vector<double> v)
{
    if (v.empty())
        return 0.0;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

}  // namespace

LookStats measureLook(const ViewRequest& view, const RenderResult& r)
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
            const glm::dvec3 dir = pixelRayEnu(camera, view, x + 0.5, y + 0.5);
            const double t = double(r.cloudDepthM[i]);
            const double altitude = view.pose.altitudeM + t * dir.z + t * t * (1.0 - dir.z * dir.z) / (2.0 * radiusM);
            cloud.push_back({0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2], altitude});
        }
    LookStats s;
    s.cloudPixels = cloud.size();
    std::vector<double> lum;
    for (const Pixel& p : cloud)
    {
        lum.push_back(p.luminance);
        s.meanLuminance += p.luminance / double(cloud.size());
    }
    s.medianLuminance = median(lum);
    std::sort(cloud.begin(), cloud.end(), [](const Pixel& a, const Pixel& b) { return a.altitudeM < b.altitudeM; });
    const size_t fifth = cloud.size() / 5;
    if (fifth > 0)
    {
        std::vector<double> low, high;
        double lowSum = 0.0, highSum = 0.0;
        for (size_t k = 0; k < fifth; ++k)
        {
            low.push_back(cloud[k].luminance);
            high.push_back(cloud[cloud.size() - 1 - k].luminance);
            lowSum += low.back();
            highSum += high.back();
        }
        s.undersideOverTopOfMeans = highSum > 0 ? lowSum / highSum : 0.0;
        s.undersideLuminance = median(low);
        s.topLuminance = median(high);
        s.undersideOverTop = s.topLuminance > 0 ? s.undersideLuminance / s.topLuminance : 0.0;
    }
    return s;
}

bool saveCloudLayers(const std::string& path, const RenderResult& r)
{
    std::ofstream f(path, std::ios::binary);
    const uint32_t size[2] = {r.width, r.height};
    f.write(reinterpret_cast<const char*>(size), sizeof(size));
    f.write(reinterpret_cast<const char*>(r.cloudRgbaHalf.data()), std::streamsize(r.cloudRgbaHalf.size() * 2));
    f.write(reinterpret_cast<const char*>(r.cloudDepthM.data()), std::streamsize(r.cloudDepthM.size() * 4));
    f.write(reinterpret_cast<const char*>(r.displayRgba8.data()), std::streamsize(r.displayRgba8.size()));
    return bool(f);
}

bool loadCloudLayers(const std::string& path, RenderResult& r)
{
    std::ifstream f(path, std::ios::binary);
    uint32_t size[2] = {0, 0};
    if (!f.read(reinterpret_cast<char*>(size), sizeof(size)) || size[0] != r.width || size[1] != r.height)
        return false;
    std::vector<uint16_t> rgba(size_t(size[0]) * size[1] * 4);
    std::vector<float> depth(size_t(size[0]) * size[1]);
    std::vector<uint8_t> display(size_t(size[0]) * size[1] * 4);
    f.read(reinterpret_cast<char*>(rgba.data()), std::streamsize(rgba.size() * 2));
    f.read(reinterpret_cast<char*>(depth.data()), std::streamsize(depth.size() * 4));
    f.read(reinterpret_cast<char*>(display.data()), std::streamsize(display.size()));
    if (!f)
        return false;
    r.cloudRgbaHalf = std::move(rgba);
    r.cloudDepthM = std::move(depth);
    r.displayRgba8 = std::move(display);
    return true;
}

}  // namespace sky::testscenes
