// SPDX-License-Identifier: MIT
#include "skyservice/output/cloud_luminance.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>

namespace sky
{

std::vector<CloudPixel> cloudPixels(const RenderResult& r)
{
    std::vector<CloudPixel> cloud;
    const size_t n = size_t(r.width) * r.height;
    if (r.cloudRgbaHalf.size() < n * 4)
        return cloud;
    for (size_t i = 0; i < n; ++i)
    {
        const double a = double(glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + 3]));
        if (a <= 0.5)
            continue;
        double rgb[3];
        for (size_t c = 0; c < 3; ++c)
            rgb[c] = double(glm::unpackHalf1x16(r.cloudRgbaHalf[i * 4 + c])) / a;
        cloud.push_back({i, 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]});
    }
    return cloud;
}

double medianOf(std::vector<double> values)
{
    if (values.empty())
        return 0.0;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(values.size() / 2), values.end());
    return values[values.size() / 2];
}

double medianCloudLuminance(const RenderResult& r)
{
    std::vector<double> luminance;
    for (const CloudPixel& p : cloudPixels(r))
        luminance.push_back(p.luminance);
    return medianOf(std::move(luminance));
}

}  // namespace sky
