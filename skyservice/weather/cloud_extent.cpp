// SPDX-License-Identifier: MIT
#include "skyservice/weather/cloud_extent.h"

#include "shaders/shared/prelude.h"
#include "shaders/shared/weather_window.h"

#include <algorithm>
#include <array>
#include <cmath>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wfloat-conversion"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wunused-function"  // the shape terms this file does not need
namespace  // internal linkage: tests compile the same shader functions into their own namespace glsl
{
namespace glsl
{
using namespace glm;
#include "shaders/lib/cloud_shape.glsl"
#include "shaders/lib/cloud_extent.glsl"
}  // namespace glsl
}  // namespace
#pragma GCC diagnostic pop

namespace sky
{
namespace
{

// Coverage steps of the tables (a coverage is rounded up to the next step) and height-fraction steps of
// the scan. A range is widened by one height step on each side: the conditions are smooth in the height
// (the steepest, a Cb's base ramp, changes by under 0.04 a step), so a stretch of cloud narrower than a
// step cannot hide between two steps that rule it out.
constexpr int kCoverageSteps = 256;
constexpr int kHeightSteps = 1024;
// The Cb's anvil exponent falls with the window's anvil amount (at most 1, skyservice/render/
// window_analysis.cpp); the shape bound is largest for the largest amount.
constexpr float kLargestAnvilAmount = 1.0f;
// Genera the shaders tell apart (CLOUD_TYPE_NONE .. CLOUD_TYPE_STRATUS); others take NONE's default profile.
constexpr int kTypes = CLOUD_TYPE_STRATUS + 1;

using Table = std::array<HeightFractionRange, kCoverageSteps + 1>;

template <class MayHold>
Table tabulate(MayHold mayHold)
{
    Table t{};
    for (int c = 0; c <= kCoverageSteps; ++c)
    {
        const float coverage = float(c) / float(kCoverageSteps);
        int first = -1, last = -1;
        for (int i = 0; i <= kHeightSteps; ++i)
            if (mayHold(float(i) / float(kHeightSteps), coverage))
            {
                first = first < 0 ? i : first;
                last = i;
            }
        if (first < 0)
            t[size_t(c)] = {1.0f, 0.0f};  // empty
        else
            t[size_t(c)] = {float(std::max(first - 1, 0)) / float(kHeightSteps),
                            float(std::min(last + 1, kHeightSteps)) / float(kHeightSteps)};
    }
    return t;
}

const std::array<Table, kTypes>& layerTables()
{
    static const std::array<Table, kTypes> tables = [] {
        std::array<Table, kTypes> t;
        for (int type = 0; type < kTypes; ++type)
            t[size_t(type)] = tabulate([type](float h, float c) {
                return glsl::layerMayHoldCloud(type, h, c, kLargestAnvilAmount);
            });
        return t;
    }();
    return tables;
}

HeightFractionRange lookUp(const Table& t, float maxCoverage)
{
    if (!(maxCoverage <= 1.0f))
        return {};  // NaN, or beyond the tables (a coverage above 1 only lowers the threshold further)
    const float steps = std::ceil(std::max(maxCoverage, 0.0f) * float(kCoverageSteps));
    return t[size_t(std::clamp(int(steps), 0, kCoverageSteps))];
}

}  // namespace

HeightFractionRange layerCloudRange(int cloudType, float maxCoverage)
{
    const int type = cloudType >= 0 && cloudType < kTypes ? cloudType : CLOUD_TYPE_NONE;
    return lookUp(layerTables()[size_t(type)], maxCoverage);
}

}  // namespace sky
