// SPDX-License-Identifier: MIT
#include "skyservice/weather/column_bounds.h"

#include "shaders/shared/column_bounds.h"
#include "skyservice/weather/cloud_extent.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sky
{
namespace
{

constexpr uint8_t kEmptyBase = 255;  // with kEmptyTop: no cloud in the column
constexpr uint8_t kEmptyTop = 0;

uint8_t encodeBase(float baseM)
{
    if (!std::isfinite(baseM))
        return 0;  // unknown: no lower bound
    double units = std::floor(double(baseM) / double(COLUMN_BOUNDS_UNIT_M)) - 1.0;
    return uint8_t(std::clamp(units, 0.0, 255.0));
}

uint8_t encodeTop(float topM)
{
    if (!std::isfinite(topM))
        return 255;  // unknown: no upper bound
    double units = std::ceil(double(topM) / double(COLUMN_BOUNDS_UNIT_M)) + 1.0;
    return uint8_t(std::clamp(units, 1.0, 255.0));
}

constexpr float kInf = std::numeric_limits<float>::infinity();

// The texels of the 3x3 neighbourhood of texel (i, j) that lie inside the window (inclusive ranges).
struct Neighbourhood
{
    uint32_t aLo, aHi, bLo, bHi;
};

Neighbourhood neighbourhoodOf(uint32_t i, uint32_t j, uint32_t n)
{
    return {i > 0 ? i - 1 : 0, std::min(i + 1, n - 1), j > 0 ? j - 1 : 0, std::min(j + 1, n - 1)};
}

// Whether any texel of the neighbourhood reaches CLOUD_COVERAGE_MIN in this slice, and its largest coverage.
bool neighbourhoodCovered(const WeatherWindow& window, uint32_t slice, const Neighbourhood& nb, float& maxCoverage)
{
    bool covered = false;
    maxCoverage = 0.0f;
    for (uint32_t b = nb.bLo; b <= nb.bHi; ++b)
        for (uint32_t a = nb.aLo; a <= nb.aHi; ++a)
        {
            const float c = window.at(slice, a, b).x;
            // NaN coverage counts as covered, and as any coverage: the bound must never hide a cloud.
            covered = covered || !(c < CLOUD_COVERAGE_MIN);
            maxCoverage = std::isnan(c) ? c : std::max(maxCoverage, c);
        }
    return covered;
}

// The height fractions the neighbourhood's genera (the shaders take a texel's own, nearest) may fill;
// an unreadable genus, the whole layer.
HeightFractionRange neighbourhoodCloudRange(const WeatherWindow& window, uint32_t slice, const Neighbourhood& nb,
                                            bool anvil, float maxCoverage)
{
    HeightFractionRange range{1.0f, 0.0f};
    for (uint32_t b = nb.bLo; b <= nb.bHi; ++b)
        for (uint32_t a = nb.aLo; a <= nb.aHi; ++a)
        {
            const float type = window.at(slice, a, b).w;
            // The anvil slab keeps its whole layer: bounded by anvilSlabCloudRange, its thin
            // edge emptied columns beside the Cb's tower, and the search's jumps there moved
            // the tower's samples (gpu.GpuRender.EmptySpaceSkippingDrawsTheSameClouds).
            // cloudDensity still skips the noise there.
            HeightFractionRange r;  // the whole layer
            if (!anvil && std::isfinite(type))
                r = layerCloudRange(int(type + 0.5f), maxCoverage);
            range = {std::min(range.lo, r.lo), std::max(range.hi, r.hi)};
        }
    return range;
}

// The lowest and highest altitude (m) at which the neighbourhood's layer holds the height fractions
// `range`.
void neighbourhoodHeights(const WeatherWindow& window, uint32_t slice, const Neighbourhood& nb,
                          const HeightFractionRange& range, float& lo, float& hi)
{
    lo = kInf;
    hi = -kInf;
    for (uint32_t b = nb.bLo; b <= nb.bHi; ++b)
        for (uint32_t a = nb.aLo; a <= nb.aHi; ++a)
        {
            const glm::vec4& t = window.at(slice, a, b);
            if (!std::isfinite(t.y) || !std::isfinite(t.z))
            {
                // Unknown altitude: unbounded on its side; the known end still bounds its own.
                lo = std::isfinite(t.y) ? std::min(lo, t.y) : -kInf;
                hi = std::isfinite(t.z) ? std::max(hi, t.z) : kInf;
                continue;
            }
            for (float f : {range.lo, range.hi})
            {
                const float h = t.y + f * (t.z - t.y);
                lo = std::min(lo, h);
                hi = std::max(hi, h);
            }
        }
}

// Level 0: per texel, over the layers (and the anvil slab) that reach CLOUD_COVERAGE_MIN anywhere in
// the 3x3 neighbourhood: a bilinear lookup inside the texel's cell mixes only those texels
// (shaders/shared/column_bounds.h). Within a layer cloud lies only between the height fractions where
// the genus may hold it at the neighbourhood's largest coverage (cloud_extent.h: a cumulus's domes
// leave the top of the layer empty), and a point at height fraction f of the interpolated layer lies
// at the same mix of the texels' base + f (top - base): between the least and the largest of those.
void boundTexels(const WeatherWindow& window, std::vector<uint8_t>& base, std::vector<uint8_t>& top)
{
    const uint32_t n = window.sizeTexels;
    for (int k = 0; k <= MAX_CLOUD_LAYERS; ++k)
    {
        const bool anvil = k == MAX_CLOUD_LAYERS;
        const uint32_t slice = anvil ? uint32_t(WEATHER_WINDOW_ANVIL_SLICE) : uint32_t(2 * k);
        for (uint32_t j = 0; j < n; ++j)
            for (uint32_t i = 0; i < n; ++i)
            {
                const Neighbourhood nb = neighbourhoodOf(i, j, n);
                float maxCoverage = 0.0f;
                if (!neighbourhoodCovered(window, slice, nb, maxCoverage))
                    continue;
                const HeightFractionRange range = neighbourhoodCloudRange(window, slice, nb, anvil, maxCoverage);
                if (range.empty())
                    continue;
                float lo = kInf, hi = -kInf;
                neighbourhoodHeights(window, slice, nb, range, lo, hi);
                const size_t c = size_t(j) * n + i;
                base[c] = std::min(base[c], encodeBase(lo));
                top[c] = std::max(top[c], encodeTop(hi));
            }
    }
}

// Writes the encoded bound of texel (i, j) of `level` into the atlas of a window n texels a side.
void storeBound(std::vector<uint8_t>& atlas, uint32_t n, int level, uint32_t i, uint32_t j, uint8_t b, uint8_t t)
{
    const ivec2 o = columnBoundsLevelOrigin(level, int(n));
    const size_t at = (size_t(uint32_t(o.y) + j) * columnBoundsWidth(n) + uint32_t(o.x) + i) * 2;
    atlas[at] = b;
    atlas[at + 1] = t;
}

// Levels 1..: min of the bases, max of the tops of each 2x2 of the level below, starting from level 0's
// `base` and `top` (consumed).
void storeCoarserLevels(std::vector<uint8_t>& atlas, uint32_t n, std::vector<uint8_t> base, std::vector<uint8_t> top)
{
    uint32_t side = n;
    for (int level = 1; side > 1; ++level)
    {
        const uint32_t half = side / 2;
        std::vector<uint8_t> b2(size_t(half) * half), t2(size_t(half) * half);
        for (uint32_t j = 0; j < half; ++j)
            for (uint32_t i = 0; i < half; ++i)
            {
                uint8_t b = kEmptyBase, t = kEmptyTop;
                for (uint32_t dj = 0; dj < 2; ++dj)
                    for (uint32_t di = 0; di < 2; ++di)
                    {
                        const size_t c = size_t(2 * j + dj) * side + 2 * i + di;
                        b = std::min(b, base[c]);
                        t = std::max(t, top[c]);
                    }
                b2[size_t(j) * half + i] = b;
                t2[size_t(j) * half + i] = t;
                storeBound(atlas, n, level, i, j, b, t);
            }
        base = std::move(b2);
        top = std::move(t2);
        side = half;
    }
}

}  // namespace

std::vector<uint8_t> buildColumnBounds(const WeatherWindow& window)
{
    const uint32_t n = window.sizeTexels;
    std::vector<uint8_t> atlas(size_t(columnBoundsWidth(n)) * n * 2, 0);
    std::vector<uint8_t> base(size_t(n) * n, kEmptyBase), top(size_t(n) * n, kEmptyTop);
    boundTexels(window, base, top);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i)
            storeBound(atlas, n, 0, i, j, base[size_t(j) * n + i], top[size_t(j) * n + i]);
    storeCoarserLevels(atlas, n, std::move(base), std::move(top));
    return atlas;
}

ColumnBound columnBoundAt(const std::vector<uint8_t>& atlas, uint32_t size, int level, uint32_t i, uint32_t j)
{
    const ivec2 o = columnBoundsLevelOrigin(level, int(size));
    const size_t at = (size_t(uint32_t(o.y) + j) * columnBoundsWidth(size) + uint32_t(o.x) + i) * 2;
    // The shaders' decoding, with "no bound" as an infinity.
    auto unbounded = [](float m) {
        return std::abs(m) >= COLUMN_BOUNDS_NONE_M ? std::copysign(std::numeric_limits<float>::infinity(), m) : m;
    };
    return {unbounded(columnBoundsBaseM(atlas[at])), unbounded(columnBoundsTopM(atlas[at + 1]))};
}

}  // namespace sky
