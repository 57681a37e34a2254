// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_weather_fade.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

using cigi::CigiState;
using cigi::EnvironmentalRegion;

CigiCloudAt unset(uint8_t layerId)
{
    CigiCloudAt c;
    c.layerId = layerId;
    return c;
}

/// The host's layer `layerId` in `layers` (set = false when it is not there).
CigiCloudAt target(const std::map<uint8_t, cigi::WeatherLayer>& layers, uint8_t layerId)
{
    auto it = layers.find(layerId);
    return it == layers.end() ? unset(layerId) : cigiLayerFromHost(it->second);
}

bool sameShape(const EnvironmentalRegion& a, const EnvironmentalRegion& b)
{
    return a.latDeg == b.latDeg && a.lonDeg == b.lonDeg && a.sizeXM == b.sizeXM && a.sizeYM == b.sizeYM &&
           a.cornerRadiusM == b.cornerRadiusM && a.rotationDeg == b.rotationDeg &&
           a.transitionPerimeterM == b.transitionPerimeterM && a.mergeWeather == b.mergeWeather;
}

/// Points `layer` at the host's `to`. The mix drawn now becomes `from`: the weighted mean of the old `from`
/// (weight fromWeight x (1 - f)) and the old `to` (weight f), whose weight is their sum. Blending a layer in
/// at weight w is (to first order) under + w (layer - under), so this is what was drawn, as one layer.
bool retarget(CigiFadingLayer& layer, const CigiCloudAt& to, double nowS, bool instant)
{
    if (cigiSameDrawnLayer(layer.to, to))
        return false;
    if (instant)
    {
        layer = CigiFadingLayer{unset(to.layerId), 0.0f, to, -std::numeric_limits<double>::infinity()};
        return true;
    }
    const float f = cigiFadeFraction(layer.startS, nowS);
    const float fromWeight = layer.from.set ? layer.fromWeight * (1 - f) : 0.0f;
    const float toWeight = layer.to.set ? f : 0.0f;
    CigiCloudAt mix = fromWeight > 0 ? layer.from : unset(to.layerId);
    if (toWeight > 0)
    {
        if (mix.set)
            cigiBlendLayer(mix, layer.to, toWeight / (fromWeight + toWeight));
        else
            mix = layer.to;
    }
    layer = CigiFadingLayer{mix, fromWeight + toWeight, to, nowS};
    return true;
}

CigiCloudAt raised(CigiCloudAt c, float undulationM)
{
    c.baseMslM += undulationM;
    c.topMslM += undulationM;
    return c;
}

/// A host layer blends in: it is set, and over a gridded weather a global layer without cloud is no layer.
bool blends(const CigiCloudAt& c, bool emptyIsNone)
{
    return c.set && !(emptyIsNone && c.coverage <= 0);
}

/// The layer drawn over `under` with weight w (1 for the global layers, the region's weight for a region);
/// the host's altitudes raised by undulationM (cloudsOver).
CigiCloudAt drawn(const CigiFadingLayer& layer, const CigiCloudAt& under, float w, double nowS,
                  bool emptyIsNone = false, float undulationM = 0.0f)
{
    CigiCloudAt from = under;
    if (blends(layer.from, emptyIsNone))
        cigiBlendLayer(from, raised(layer.from, undulationM), w * layer.fromWeight);
    const float f = cigiFadeFraction(layer.startS, nowS);
    if (f <= 0)
        return from;
    CigiCloudAt to = under;
    if (blends(layer.to, emptyIsNone))
        cigiBlendLayer(to, raised(layer.to, undulationM), w);
    if (f >= 1)
        return to;
    if (!to.set) // nothing under and nothing set: what was drawn fades out
    {
        from.coverage *= 1 - f;
        return from;
    }
    cigiBlendLayer(from, to, f);
    return from;
}

bool layerDone(const CigiFadingLayer& l, double nowS)
{
    return cigiFadeFraction(l.startS, nowS) >= 1;
}

} // namespace

float cigiFadeFraction(double startS, double nowS)
{
    const double t = (nowS - startS) / kCigiFadeS;
    if (!(t < 1))
        return 1; // also startS = -inf
    if (t <= 0)
        return 0;
    return float(t * t * (3 - 2 * t));
}

float CigiRamp::at(double nowS) const
{
    return from + (to - from) * cigiFadeFraction(startS, nowS);
}

bool CigiWeatherFade::setTarget(const CigiState& state, double nowS)
{
    if (!started_ && !cigiHasCloudWeather(state))
        return false; // the configured weather stays until the host sets a cloud layer
    const bool instant = !started_;
    started_ = true;
    bool changed = false;
    for (uint8_t i = 0; i < 3; ++i)
        changed |= retarget(global_[i], target(state.globalLayers, uint8_t(i + 1)), nowS, instant);

    for (auto& [id, f] : regions_)
        if (!state.regions.count(id) && f.presence.to > 0) // forgotten by the host: fades out
        {
            f.presence = CigiRamp{f.presence.at(nowS), 0.0f, nowS};
            changed = true;
        }
    for (const auto& [id, r] : state.regions)
    {
        const bool known = regions_.count(id) != 0;
        CigiFadingRegion& f = regions_[id];
        if (!known || !sameShape(f.shape, r))
        {
            f.shape = r;
            f.shape.layers.clear();
            changed |= known;
        }
        const float presence = cigiRegionDrawn(r) ? 1.0f : 0.0f;
        const float now = f.presence.at(nowS);
        if (presence != f.presence.to)
        {
            f.presence = instant ? CigiRamp{presence, presence} : CigiRamp{now, presence, nowS};
            changed = true;
        }
        // A region not drawn yet takes its layers at once: its presence is what fades in.
        const bool layersInstant = instant || now <= 0;
        for (uint8_t i = 0; i < 3; ++i)
            changed |= retarget(f.layers[i], target(r.layers, uint8_t(i + 1)), nowS, layersInstant);
    }
    std::erase_if(regions_,
                  [nowS](const auto& entry)
                  {
                      const CigiRamp& p = entry.second.presence;
                      return p.to <= 0 && p.at(nowS) <= 0;
                  });
    return changed;
}

bool CigiWeatherFade::fading(double nowS) const
{
    auto layersDone = [nowS](const std::array<CigiFadingLayer, 3>& layers) {
        return std::all_of(layers.begin(), layers.end(),
                           [nowS](const CigiFadingLayer& l) { return layerDone(l, nowS); });
    };
    if (!layersDone(global_))
        return true;
    return std::any_of(regions_.begin(), regions_.end(),
                       [&](const auto& entry)
                       {
                           const CigiFadingRegion& r = entry.second;
                           return cigiFadeFraction(r.presence.startS, nowS) < 1 || !layersDone(r.layers);
                       });
}

namespace
{

/// Calls apply(region, weight) for each region drawn at the point at nowS, in id order; weight is the
/// region's weight there (its perimeter's blend) times its presence (fading in or out), > 0.
template <class Apply>
void forEachRegionAt(const std::map<uint16_t, CigiFadingRegion>& regions, double latDeg, double lonDeg, double nowS,
                     Apply apply)
{
    for (const auto& [id, r] : regions)
    {
        const float presence = r.presence.at(nowS);
        if (presence <= 0)
            continue;
        const double w = cigiRegionWeight(r.shape, latDeg, lonDeg);
        if (w > 0)
            apply(r, float(w) * presence);
    }
}

} // namespace

CigiCloudsAt CigiWeatherFade::cloudsAt(double latDeg, double lonDeg, double nowS) const
{
    CigiCloudsAt out;
    for (uint8_t i = 0; i < 3; ++i)
        out[i] = drawn(global_[i], unset(uint8_t(i + 1)), 1.0f, nowS);
    bool covered = false; // an earlier region reaches this point
    forEachRegionAt(regions_, latDeg, lonDeg, nowS, [&](const CigiFadingRegion& r, float weight) {
        const float t = weight * (r.shape.mergeWeather && covered ? 0.5f : 1.0f);
        for (size_t i = 0; i < 3; ++i)
            out[i] = drawn(r.layers[i], out[i], t, nowS);
        covered = true;
    });
    return out;
}

CigiCloudsAt CigiWeatherFade::cloudsOver(const CigiCloudsAt& under, double latDeg, double lonDeg, double nowS,
                                         float undulationM) const
{
    CigiCloudsAt out;
    for (uint8_t i = 0; i < 3; ++i)
        out[i] = drawn(global_[i], under[i], 1.0f, nowS, true, undulationM);
    forEachRegionAt(regions_, latDeg, lonDeg, nowS, [&](const CigiFadingRegion& r, float weight) {
        // The gridded weather is always beneath: Merge Weather averages with it (or with what is over it).
        const float t = weight * (r.shape.mergeWeather ? 0.5f : 1.0f);
        for (size_t i = 0; i < 3; ++i)
            out[i] = drawn(r.layers[i], out[i], t, nowS, false, undulationM);
    });
    return out;
}

bool CigiWeatherFade::layerExtent(uint8_t layerId, CigiCloudAt& out) const
{
    if (layerId < 1 || layerId > 3)
        return false;
    auto pick = [&out](const CigiFadingLayer& l, bool needCloud)
    {
        for (const CigiCloudAt* c : {&l.to, &l.from})
            if (c->set && (!needCloud || c->coverage > 0))
            {
                out = *c;
                return true;
            }
        return false;
    };
    if (pick(global_[layerId - 1], true))
        return true;
    for (const auto& [id, r] : regions_)
        if (pick(r.layers[layerId - 1], false))
            return true;
    return false;
}

} // namespace sky
