// SPDX-License-Identifier: MIT
#include "tests/gpu/image_compare.h"

#include "skyservice/output/contact_sheet.h"
#include "skyservice/output/image_files.h"
#include "tests/gpu/scenes.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace sky::testscenes
{
namespace
{

float half(const RenderResult& r, size_t i) { return glm::unpackHalf1x16(r.cloudRgbaHalf[i]); }

double referencePeak(const RenderResult& reference)
{
    double peak = 0.0;
    for (size_t i = 0; i < reference.cloudRgbaHalf.size(); ++i)
        peak = std::max(peak, double(half(reference, i)));
    return peak;
}

double toPsnr(double peak, double se, double count)
{
    if (count <= 0.0)
        return 0.0;
    double mse = se / count;
    return mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : 200.0;
}

// Calls f(pixelIndex) for every pixel of `band`.
template <class F> void forBand(const RenderResult& r, ColumnBand band, F f)
{
    uint32_t x1 = std::min(band.x1, r.width), y1 = std::min(band.y1, r.height);
    for (uint32_t y = band.y0; y < y1; ++y)
        for (uint32_t x = band.x0; x < x1; ++x)
            f(size_t(y) * r.width + x);
}

}  // namespace

double psnrCloud(const RenderResult& test, const RenderResult& reference, ColumnBand band)
{
    double se = 0.0, count = 0.0;
    forBand(reference, band, [&](size_t p) {
        for (size_t c = 0; c < 4; ++c)
        {
            double d = double(half(test, p * 4 + c)) - double(half(reference, p * 4 + c));
            se += d * d;
            count += 1.0;
        }
    });
    return toPsnr(referencePeak(reference), se, count);
}

double radianceScale(const RenderResult& reference)
{
    std::vector<double> brightest;
    for (size_t p = 0; p < reference.cloudRgbaHalf.size() / 4; ++p)
        if (half(reference, p * 4 + 3) >= 0.5f)
            brightest.push_back(
                double(std::max({half(reference, p * 4), half(reference, p * 4 + 1), half(reference, p * 4 + 2)})));
    if (brightest.empty())
        return 1.0;
    auto at = brightest.begin() + std::ptrdiff_t(0.99 * double(brightest.size() - 1));
    std::nth_element(brightest.begin(), at, brightest.end());
    return *at > 0.0 ? *at : 1.0;
}

double psnrCloudScaled(const RenderResult& test, const RenderResult& reference, ColumnBand band, double rgbScale)
{
    const double scale = rgbScale > 0.0 ? rgbScale : radianceScale(reference);
    double se = 0.0, count = 0.0;
    forBand(reference, band, [&](size_t p) {
        for (size_t c = 0; c < 4; ++c)
        {
            double d = double(half(test, p * 4 + c)) - double(half(reference, p * 4 + c));
            d /= c < 3 ? scale : 1.0;
            se += d * d;
            count += 1.0;
        }
    });
    return toPsnr(1.0, se, count);
}

double psnrDisplay(const RenderResult& test, const RenderResult& reference, ColumnBand band)
{
    double se = 0.0, count = 0.0;
    forBand(reference, band, [&](size_t p) {
        for (size_t c = 0; c < 4; ++c)
        {
            double d = double(test.displayRgba8[p * 4 + c]) - double(reference.displayRgba8[p * 4 + c]);
            se += d * d;
            count += 1.0;
        }
    });
    return toPsnr(255.0, se, count);
}

double meanAbsCloudError(const RenderResult& test, const RenderResult& reference, ColumnBand band)
{
    double sum = 0.0, count = 0.0;
    forBand(reference, band, [&](size_t p) {
        for (size_t c = 0; c < 4; ++c)
        {
            sum += std::fabs(double(half(test, p * 4 + c)) - double(half(reference, p * 4 + c)));
            count += 1.0;
        }
    });
    double peak = referencePeak(reference);
    return count > 0.0 && peak > 0.0 ? sum / count / peak : 0.0;
}

Resampled resampleCloud(const RenderResult& source, const ViewRequest& sourceView, const ViewRequest& targetView)
{
    CameraFrame src = computeCameraFrame(sourceView.pose), dst = computeCameraFrame(targetView.pose);
    double tanHalf = std::tan(sourceView.fovYDeg * M_PI / 360.0);
    double aspect = double(sourceView.width) / double(sourceView.height);
    Resampled out;
    size_t n = size_t(targetView.width) * targetView.height;
    out.cloudRgba.assign(n * 4, 0.0f);
    out.valid.assign(n, 0);
    auto at = [&](int x, int y, int c) {
        x = std::clamp(x, 0, int(source.width) - 1);
        y = std::clamp(y, 0, int(source.height) - 1);
        return double(half(source, (size_t(y) * source.width + size_t(x)) * 4 + size_t(c)));
    };
    for (uint32_t y = 0; y < targetView.height; ++y)
        for (uint32_t x = 0; x < targetView.width; ++x)
        {
            glm::dvec3 d = pixelRayEnu(dst, targetView, x + 0.5, y + 0.5);
            double z = glm::dot(d, src.forwardEnu);
            if (z <= 0.0)
                continue;
            double nx = glm::dot(d, src.rightEnu) / (z * tanHalf * aspect);
            double ny = -glm::dot(d, src.upEnu) / (z * tanHalf);
            double qx = (nx + 1.0) * 0.5 * source.width, qy = (ny + 1.0) * 0.5 * source.height;
            if (qx < 0.5 || qy < 0.5 || qx > source.width - 0.5 || qy > source.height - 0.5)
                continue;
            double tx = qx - 0.5, ty = qy - 0.5;
            int ix = int(std::floor(tx)), iy = int(std::floor(ty));
            double fx = tx - ix, fy = ty - iy;
            size_t p = size_t(y) * targetView.width + x;
            out.valid[p] = 1;
            for (int c = 0; c < 4; ++c)
            {
                double top = at(ix, iy, c) * (1 - fx) + at(ix + 1, iy, c) * fx;
                double bottom = at(ix, iy + 1, c) * (1 - fx) + at(ix + 1, iy + 1, c) * fx;
                out.cloudRgba[p * 4 + size_t(c)] = float(top * (1 - fy) + bottom * fy);
            }
        }
    return out;
}

double psnrResampled(const Resampled& test, const RenderResult& reference)
{
    double se = 0.0, count = 0.0;
    for (size_t p = 0; p < test.valid.size(); ++p)
        if (test.valid[p])
            for (size_t c = 0; c < 4; ++c)
            {
                double d = double(test.cloudRgba[p * 4 + c]) - double(half(reference, p * 4 + c));
                se += d * d;
                count += 1.0;
            }
    return toPsnr(referencePeak(reference), se, count);
}

void writeDisplayPng(const RenderResult& r, const std::string& path, uint32_t scale)
{
    ImageRgba8 display;
    display.width = r.width;
    display.height = r.height;
    display.pixels = r.displayRgba8;
    std::string error;
    if (!writePng(path, enlargeImage(display, scale), error))
        std::printf("could not write %s: %s\n", path.c_str(), error.c_str());
}

}  // namespace sky::testscenes
