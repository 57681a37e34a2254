// SPDX-License-Identifier: MIT
#include "tests/gpu/sharpness.h"

#include <algorithm>
#include <cmath>

namespace sky::testscenes
{
namespace
{

double luma(const RenderResult& image, uint32_t x, uint32_t y)
{
    const uint8_t* p = &image.displayRgba8[(size_t(y) * image.width + x) * 4];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

}  // namespace

double displaySharpness(const RenderResult& image, ColumnBand band)
{
    if (image.width < 2 || image.height < 2 || image.displayRgba8.size() < size_t(image.width) * image.height * 4)
        return 0.0;
    const uint32_t x1 = std::min(band.x1, image.width - 1), y1 = std::min(band.y1, image.height - 1);
    double sum = 0.0;
    size_t count = 0;
    for (uint32_t y = band.y0; y < y1; ++y)
        for (uint32_t x = band.x0; x < x1; ++x)
        {
            const double l = luma(image, x, y);
            sum += std::fabs(luma(image, x + 1, y) - l) + std::fabs(luma(image, x, y + 1) - l);
            ++count;
        }
    return count > 0 ? sum / double(count) : 0.0;
}

double sharpnessRatio(const RenderResult& test, const RenderResult& reference, ColumnBand band)
{
    const double t = displaySharpness(test, band), r = displaySharpness(reference, band);
    if (r <= 0.0)
        return t <= 0.0 ? 1.0 : 1e9;
    return t / r;
}

}  // namespace sky::testscenes
