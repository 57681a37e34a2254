// SPDX-License-Identifier: MIT
#include "skyservice/weather/window_analysis.h"

#include "shaders/shared/weather_window.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

size_t texelIndex(const WeatherWindow& w, int slice, uint32_t i, uint32_t j)
{
    return (size_t(slice) * w.sizeTexels + j) * w.sizeTexels + i;
}

// Anvil geometry (Häggström 2018 describes the shape; these sizes are ours): a mature Cb anvil spans
// tens of kilometres, more with stronger instability, and drifts with the upper wind.
constexpr double kAnvilBaseRadiusM = 8000.0;
constexpr double kAnvilRadiusPerCapeM = 12000.0 / 3000.0;
constexpr double kAnvilDriftS = 300.0;
constexpr float kAnvilBaseFraction = 0.72f;

}  // namespace

void computeAnvils(WeatherWindow& window)
{
    const uint32_t n = window.sizeTexels;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
            window.texels[texelIndex(window, WEATHER_WINDOW_ANVIL_SLICE, i, j)] = glm::vec4(0.0f);
    for (int k = 0; k < MAX_CLOUD_LAYERS; ++k)
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i)
            {
                const glm::vec4 cell = window.texels[texelIndex(window, 2 * k, i, j)];
                if (cell.x < 0.3f || int(std::lround(cell.w)) != CLOUD_TYPE_CUMULONIMBUS || cell.z <= cell.y)
                    continue;
                const glm::vec4 aux = window.texels[texelIndex(window, 2 * k + 1, i, j)];
                const glm::vec4 upper = window.texels[texelIndex(window, WEATHER_WINDOW_HIGH_SLICE + 1, i, j)];
                double cape = std::isfinite(aux.w) ? double(std::max(0.0f, aux.w)) : 0.0;
                double radius = kAnvilBaseRadiusM + kAnvilRadiusPerCapeM * std::min(cape, 5000.0);
                glm::dvec2 centre = window.texelPositionM(i, j) + glm::dvec2(upper.x, upper.y) * kAnvilDriftS;
                // Search a box of the (warped) window plane that holds the anvil: the warp magnifies
                // distances around a point at |p| by at most (E + r0) / (|p| + r0).
                glm::dvec2 q = windowWarpM(centre, window.halfExtentM, window.warpRadiusM);
                double magnify = window.warpRadiusM > 0
                                     ? (window.halfExtentM + window.warpRadiusM) /
                                           (std::max(0.0, glm::length(centre) - radius) + window.warpRadiusM)
                                     : 1.0;
                int reach = int(std::ceil(radius * magnify / window.texelSizeM)) + 1;
                int ci = int(std::floor(q.x / window.texelSizeM + 0.5 * n));
                int cj = int(std::floor(q.y / window.texelSizeM + 0.5 * n));
                float top = cell.z;
                float base = cell.y + (cell.z - cell.y) * kAnvilBaseFraction;
                for (int tj = std::max(0, cj - reach); tj <= std::min(int(n) - 1, cj + reach); ++tj)
                    for (int ti = std::max(0, ci - reach); ti <= std::min(int(n) - 1, ci + reach); ++ti)
                    {
                        double r = glm::length(window.texelPositionM(uint32_t(ti), uint32_t(tj)) - centre) / radius;
                        if (r >= 1.0)
                            continue;
                        float cov = cell.x * float(1.0 - r * r * (3.0 - 2.0 * r));  // smooth falloff
                        glm::vec4& a = window.texels[texelIndex(window, WEATHER_WINDOW_ANVIL_SLICE, uint32_t(ti), uint32_t(tj))];
                        if (cov > a.x)
                            a = glm::vec4(cov, a.x > 0.0f ? std::min(a.y, base) : base, std::max(a.z, top), 0.0f);
                    }
            }
}

WindowSummary summarizeWindow(const WeatherWindow& window)
{
    WindowSummary s;
    const uint32_t n = window.sizeTexels;
    auto scanLayer = [&](int coverageSlice, int windSlice, LayerSummary& out) {
        out.minBaseM = 1e9f;
        out.maxTopM = -1e9f;
        double weight = 0;
        bool cumulonimbus = false;
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i)
            {
                const glm::vec4 c = window.texels[texelIndex(window, coverageSlice, i, j)];
                if (!(c.x > 0.01f) || !(c.z > c.y))
                    continue;
                out.minBaseM = std::min(out.minBaseM, c.y);
                out.maxTopM = std::max(out.maxTopM, c.z);
                if (int(std::lround(c.w)) == CLOUD_TYPE_CUMULONIMBUS)
                    cumulonimbus = true;
                if (windSlice >= 0)
                {
                    const glm::vec4 wv = window.texels[texelIndex(window, windSlice, i, j)];
                    if (std::isfinite(wv.x) && std::isfinite(wv.y))
                    {
                        out.meanWindEnuMS += glm::dvec2(wv.x, wv.y) * double(c.x);
                        weight += double(c.x);
                    }
                }
            }
        if (weight > 0)
            out.meanWindEnuMS /= weight;
        out.anvilAmount = cumulonimbus ? 0.8f : 0.0f;
    };
    for (int k = 0; k < MAX_CLOUD_LAYERS; ++k)
        scanLayer(2 * k, 2 * k + 1, s.layers[size_t(k)]);
    scanLayer(WEATHER_WINDOW_ANVIL_SLICE, -1, s.anvil);

    double weight = 0;
    double altitude = 0;
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
        {
            const glm::vec4 h = window.texels[texelIndex(window, WEATHER_WINDOW_HIGH_SLICE, i, j)];
            const glm::vec4 wv = window.texels[texelIndex(window, WEATHER_WINDOW_HIGH_SLICE + 1, i, j)];
            if (std::isfinite(wv.x) && std::isfinite(wv.y))
                s.upperWindEnuMS += glm::dvec2(wv.x, wv.y);
            if (h.x > 0.01f && std::isfinite(h.y))
            {
                altitude += double(h.y) * double(h.x);
                weight += double(h.x);
            }
        }
    s.upperWindEnuMS /= double(n) * double(n);
    s.highAltitudeM = weight > 0 ? float(altitude / weight) : 0.0f;
    s.anvil.meanWindEnuMS = s.upperWindEnuMS;
    return s;
}

}  // namespace sky
