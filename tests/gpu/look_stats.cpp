// SPDX-License-Identifier: MIT
#include "tests/gpu/look_stats.h"

#include "skyservice/output/cloud_luminance.h"
#include "tests/gpu/scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

namespace sky::testscenes
{

LookStats measureLook(const ViewRequest& view, const RenderResult& r)
{
    const CameraFrame camera = computeCameraFrame(view.pose);
    const double radiusM = 6371000.0;
    struct Pixel
    {
        double luminance, altitudeM;
    };
    std::vector<Pixel> cloud;
    for (const CloudPixel& p : cloudPixels(r))
    {
        const size_t x = p.index % r.width, y = p.index / r.width;
        const glm::dvec3 dir = pixelRayEnu(camera, view, double(x) + 0.5, double(y) + 0.5);
        const double t = double(r.cloudDepthM[p.index]);
        const double altitude = view.pose.altitudeM + t * dir.z + t * t * (1.0 - dir.z * dir.z) / (2.0 * radiusM);
        cloud.push_back({p.luminance, altitude});
    }
    LookStats s;
    s.cloudPixels = cloud.size();
    std::vector<double> lum;
    for (const Pixel& p : cloud)
    {
        lum.push_back(p.luminance);
        s.meanLuminance += p.luminance / double(cloud.size());
    }
    s.medianLuminance = medianOf(lum);
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
        s.undersideLuminance = medianOf(low);
        s.topLuminance = medianOf(high);
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
