// SPDX-License-Identifier: MIT
#include "weather_ingest/snapshot_blend.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sky
{
namespace
{

/// out = a*(1-w) + b*w with the NaN rule of the header; an empty input counts as all-NaN, or as all
/// `missingAs` when that is finite (coverage of a layer that exists on one side only fades).
void blend(const std::vector<float>& a, const std::vector<float>& b, const BlendWeight& w, size_t n, float missingAs,
           std::vector<float>& out)
{
    if (a.empty() && b.empty() && !std::isfinite(missingAs))
    {
        out.clear();
        return;
    }
    out.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
        const float wb = w.at(i);
        const float va = a.empty() ? missingAs : a[i];
        const float vb = b.empty() ? missingAs : b[i];
        const bool fa = std::isfinite(va);
        const bool fb = std::isfinite(vb);
        out[i] = fa && fb ? va * (1.0f - wb) + vb * wb : (fa ? va : vb);
    }
}

void pickTypes(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, const BlendWeight& w, size_t n,
               std::vector<uint8_t>& out)
{
    if (a.empty() && b.empty())
    {
        out.clear();
        return;
    }
    out.resize(n);
    for (size_t i = 0; i < n; ++i)
    {
        const bool preferB = w.at(i) >= 0.5f;
        const uint8_t ta = a.empty() ? 0 : a[i];
        const uint8_t tb = b.empty() ? 0 : b[i];
        const uint8_t nearer = preferB ? tb : ta;
        out[i] = nearer != 0 ? nearer : (preferB ? ta : tb);
    }
}

void blendLayer(const CloudLayerFields* a, const CloudLayerFields* b, const BlendWeight& w, size_t n,
                CloudLayerFields& out)
{
    static const CloudLayerFields kEmpty;
    const CloudLayerFields& la = a ? *a : kEmpty;
    const CloudLayerFields& lb = b ? *b : kEmpty;
    out.name = a ? a->name : b->name;
    blend(la.coverage, lb.coverage, w, n, 0.0f, out.coverage);
    const float nan = NAN;
    blend(la.baseAltitudeM, lb.baseAltitudeM, w, n, nan, out.baseAltitudeM);
    blend(la.topAltitudeM, lb.topAltitudeM, w, n, nan, out.topAltitudeM);
    pickTypes(la.type, lb.type, w, n, out.type);
    blend(la.precipitationMmH, lb.precipitationMmH, w, n, nan, out.precipitationMmH);
    blend(la.windEastMS, lb.windEastMS, w, n, nan, out.windEastMS);
    blend(la.windNorthMS, lb.windNorthMS, w, n, nan, out.windNorthMS);
}

const CloudLayerFields* findLayer(const WeatherSnapshot& s, const std::string& name)
{
    for (const CloudLayerFields& l : s.layers)
        if (l.name == name)
            return &l;
    return nullptr;
}

} // namespace

void blendSnapshotFields(const WeatherSnapshot& a, const WeatherSnapshot& b, const BlendWeight& w, WeatherSnapshot& out)
{
    const size_t n = a.grid.cellCount();
    const float nan = NAN;
    std::vector<std::string> names;
    for (const CloudLayerFields& l : a.layers)
        names.push_back(l.name);
    for (const CloudLayerFields& l : b.layers)
        if (std::find(names.begin(), names.end(), l.name) == names.end())
            names.push_back(l.name);
    names.resize(std::min(names.size(), size_t(kMaxCloudLayers)));
    out.layers.resize(names.size());
    for (size_t i = 0; i < names.size(); ++i)
        blendLayer(findLayer(a, names[i]), findLayer(b, names[i]), w, n, out.layers[i]);

    blend(a.high.coverage, b.high.coverage, w, n, a.high.coverage.empty() || b.high.coverage.empty() ? 0.0f : nan,
          out.high.coverage);
    blend(a.high.altitudeM, b.high.altitudeM, w, n, nan, out.high.altitudeM);
    pickTypes(a.high.type, b.high.type, w, n, out.high.type);
    blend(a.high.windEastMS, b.high.windEastMS, w, n, nan, out.high.windEastMS);
    blend(a.high.windNorthMS, b.high.windNorthMS, w, n, nan, out.high.windNorthMS);
    if (a.high.coverage.empty() && b.high.coverage.empty())
        out.high.coverage.clear();
    blend(a.capeJKg, b.capeJKg, w, n, nan, out.capeJKg);
    blend(a.tropopauseAltitudeM, b.tropopauseAltitudeM, w, n, nan, out.tropopauseAltitudeM);
    if (a.dataWeight.empty() && b.dataWeight.empty())
        out.dataWeight.clear();
    else
        blend(a.dataWeight, b.dataWeight, w, n, 1.0f, out.dataWeight);

    out.levelFields.clear();
    for (const PressureLevelField& fa : a.levelFields)
    {
        const PressureLevelField* fb = nullptr;
        for (const PressureLevelField& f : b.levelFields)
            if (f.name == fa.name && f.pressurePa == fa.pressurePa)
                fb = &f;
        PressureLevelField f = fa;
        if (fb)
        {
            // Level-major values: the per-cell weight repeats for every level.
            for (size_t k = 0; k < fa.pressurePa.size(); ++k)
                for (size_t i = 0; i < n; ++i)
                {
                    const float va = fa.values[k * n + i], vb = fb->values[k * n + i], wb = w.at(i);
                    f.values[k * n + i] = std::isfinite(va) && std::isfinite(vb) ? va * (1 - wb) + vb * wb
                                          : std::isfinite(va)                    ? va
                                                                                 : vb;
                }
        }
        out.levelFields.push_back(std::move(f));
    }
}

} // namespace sky
