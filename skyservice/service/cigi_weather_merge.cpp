// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_weather_merge.h"

#include "skyservice/weather/snapshot_regrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sky
{
namespace
{

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kMetresPerDegree = 111195.0;
/// A gridded layer's altitude is measured within this distance of the ownship (its heights vary across a
/// continent; the host's layers are meant for where the ownship flies).
constexpr double kMatchRadiusM = 1000000.0;
/// Cells with less coverage do not count in a layer's altitude.
constexpr float kMatchMinCoverage = 0.02f;

/// A layer's altitude range (coverage-weighted mean base and top); `any` false: no cloud.
struct Extent
{
    bool any = false;
    float baseM = 0, topM = 0;
    float mid() const { return 0.5f * (baseM + topM); }
};

bool cellHasCloud(const CloudLayerFields& l, size_t cell)
{
    const float c = l.coverage[cell];
    return !std::isnan(c) && c > 0 && !std::isnan(l.baseAltitudeM[cell]) && !std::isnan(l.topAltitudeM[cell]);
}

bool complete(const CloudLayerFields& l, size_t cells)
{
    return l.coverage.size() == cells && l.baseAltitudeM.size() == cells && l.topAltitudeM.size() == cells;
}

Extent griddedExtent(const WeatherSnapshot& w, const CloudLayerFields& l, double ownLatDeg, double ownLonDeg)
{
    const size_t cells = w.grid.cellCount();
    if (!complete(l, cells))
        return {};
    const double cosLat = std::max(std::cos(ownLatDeg * kDegToRad), 0.05);
    double near[3] = {0, 0, 0}, all[3] = {0, 0, 0}; // weight, weighted base, weighted top
    for (uint32_t iLat = 0; iLat < w.grid.nLat; ++iLat)
    {
        const double lat = w.grid.lat0Deg + iLat * w.grid.dLatDeg;
        const bool latNear = std::fabs(lat - ownLatDeg) * kMetresPerDegree <= kMatchRadiusM;
        for (uint32_t iLon = 0; iLon < w.grid.nLon; ++iLon)
        {
            const size_t cell = w.grid.index(iLat, iLon);
            if (!cellHasCloud(l, cell) || l.coverage[cell] < kMatchMinCoverage)
                continue;
            const double c = std::min(double(l.coverage[cell]), 1.0);
            const double dLon = std::fmod(w.grid.lon0Deg + iLon * w.grid.dLonDeg - ownLonDeg + 540.0, 360.0) - 180.0;
            double* sum = latNear && std::fabs(dLon) * cosLat * kMetresPerDegree <= kMatchRadiusM ? near : all;
            sum[0] += c;
            sum[1] += c * double(l.baseAltitudeM[cell]);
            sum[2] += c * double(l.topAltitudeM[cell]);
        }
    }
    if (near[0] <= 0)
        std::swap(near, all); // nothing near the ownship: the layer's range anywhere
    if (near[0] <= 0)
        return {};
    return {true, float(near[1] / near[0]), float(near[2] / near[0])};
}

CigiCloudAt unset(uint8_t layerId)
{
    CigiCloudAt c;
    c.layerId = layerId;
    return c;
}

/// The gridded layer at a cell as a host layer would be (set = false where it has no cloud).
CigiCloudAt griddedAt(const CloudLayerFields& l, size_t cell, uint8_t layerId)
{
    CigiCloudAt c = unset(layerId);
    if (!cellHasCloud(l, cell))
        return c;
    c.set = true;
    c.coverage = std::min(l.coverage[cell], 1.0f);
    c.baseMslM = l.baseAltitudeM[cell]; // above the ellipsoid: cloudsOver raises the host's to match
    c.topMslM = l.topAltitudeM[cell];
    c.cloudType = l.type.size() > cell ? l.type[cell] : uint8_t(CloudType::None);
    auto finite = [](const std::vector<float>& f, size_t i)
    { return f.size() > i && std::isfinite(f[i]) ? f[i] : 0.0f; };
    c.windEastMps = finite(l.windEastMS, cell);
    c.windNorthMps = finite(l.windNorthMS, cell);
    return c;
}

/// A layer of no cloud on `cells` cells (a slot the host's layer opens).
CloudLayerFields emptyLayer(size_t cells, const std::string& name)
{
    CloudLayerFields l;
    l.name = name;
    for (std::vector<float>* f : {&l.coverage, &l.baseAltitudeM, &l.topAltitudeM, &l.precipitationMmH, &l.windEastMS,
                                  &l.windNorthMS})
        f->assign(cells, 0.0f);
    l.type.assign(cells, uint8_t(CloudType::None));
    return l;
}

/// Every vector of a layer with one value per cell (a gridded file may leave optional ones out).
void fillOut(CloudLayerFields& l, size_t cells)
{
    for (std::vector<float>* f : {&l.precipitationMmH, &l.windEastMS, &l.windNorthMS})
        if (f->size() != cells)
            f->assign(cells, 0.0f);
    if (l.type.size() != cells)
        l.type.assign(cells, uint8_t(CloudType::None));
}

void ensureHigh(HighCloudFields& h, size_t cells)
{
    if (h.coverage.size() == cells && h.altitudeM.size() == cells && h.type.size() == cells &&
        h.windEastMS.size() == cells && h.windNorthMS.size() == cells)
        return;
    h = HighCloudFields{};
    for (std::vector<float>* f : {&h.coverage, &h.altitudeM, &h.windEastMS, &h.windNorthMS})
        f->assign(cells, 0.0f);
    h.type.assign(cells, uint8_t(CloudType::None));
}

} // namespace

std::array<int, 3> cigiMatchLayerSlots(const WeatherSnapshot& gridded, const CigiWeatherFade& fade, double ownLatDeg,
                                       double ownLonDeg)
{
    std::array<int, 3> slot{-1, -1, -1};
    std::array<CigiCloudAt, 3> host;
    std::array<bool, 3> wanted{};
    for (uint8_t i = 0; i < 3; ++i)
        wanted[i] = fade.layerExtent(uint8_t(i + 1), host[i]) && !cigiHighCloudType(host[i].cloudType);
    std::vector<Extent> extents;
    for (const CloudLayerFields& l : gridded.layers)
        extents.push_back(griddedExtent(gridded, l, ownLatDeg, ownLonDeg));
    size_t slots = std::min(extents.size(), size_t(kMaxCloudLayers));
    extents.resize(size_t(kMaxCloudLayers)); // a slot opened for a host layer has no gridded cloud
    std::vector<bool> claimed(size_t(kMaxCloudLayers), false);
    std::array<size_t, 3> order{0, 1, 2}; // lowest host layer first
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b)
                     { return host[a].baseMslM + host[a].topMslM < host[b].baseMslM + host[b].topMslM; });
    for (size_t i : order)
    {
        if (!wanted[i])
            continue;
        const float base = host[i].baseMslM, top = host[i].topMslM, mid = 0.5f * (base + top);
        int best = -1;
        float bestOverlap = 0;
        for (size_t k = 0; k < slots; ++k) // the gridded layer its altitudes overlap most
        {
            if (claimed[k] || !extents[k].any)
                continue;
            const float overlap = std::min(top, extents[k].topM) - std::max(base, extents[k].baseM);
            if (overlap > bestOverlap)
                bestOverlap = overlap, best = int(k);
        }
        for (size_t k = 0; k < slots && best < 0; ++k) // a slot with no cloud near the ownship
            if (!claimed[k] && !extents[k].any)
                best = int(k);
        if (best < 0 && slots < size_t(kMaxCloudLayers)) // a slot of its own
            best = int(slots++);
        float nearest = std::numeric_limits<float>::infinity();
        const bool full = best < 0;
        for (size_t k = 0; k < slots && full; ++k) // all four hold cloud: the nearest by mid altitude
            if (!claimed[k] && std::fabs(extents[k].mid() - mid) < nearest)
                nearest = std::fabs(extents[k].mid() - mid), best = int(k);
        if (best < 0)
            continue;
        claimed[size_t(best)] = true;
        slot[i] = best;
    }
    return slot;
}

WeatherSnapshot cigiMergeWeather(const WeatherSnapshot& gridded, const CigiWeatherFade& fade, double nowS,
                                 const CigiWeatherGrid& grid, const cigi::GeoidGrid& geoid, double ownLatDeg,
                                 double ownLonDeg)
{
    WeatherSnapshot w = grid.regional ? regridSnapshot(gridded, grid.grid) : gridded;
    foldDataWeight(w);
    w.levelFields.clear(); // not drawn; and on a regional grid they would no longer fit
    w.provenance["clouds"] = (gridded.provenance.count("clouds") ? gridded.provenance.at("clouds") + " + " : "") +
                             "CIGI host: Weather Control / Environmental Region Control (merged)";
    if (w.layers.size() > size_t(kMaxCloudLayers))
        w.layers.resize(size_t(kMaxCloudLayers));
    const size_t cells = w.grid.cellCount();
    for (CloudLayerFields& l : w.layers)
        if (complete(l, cells))
            fillOut(l, cells);
        else
            l = emptyLayer(cells, l.name); // a layer the renderer would not draw
    const std::array<int, 3> slot = cigiMatchLayerSlots(w, fade, ownLatDeg, ownLonDeg);
    for (int k = int(w.layers.size()); k <= *std::max_element(slot.begin(), slot.end()); ++k)
    {
        const auto owner = std::find(slot.begin(), slot.end(), k);
        w.layers.push_back(emptyLayer(cells, "cigi layer " + std::to_string(owner - slot.begin() + 1)));
    }
    bool highMade = false;
    for (uint32_t iLat = 0; iLat < w.grid.nLat; ++iLat)
    {
        const double lat = std::clamp(w.grid.lat0Deg + iLat * w.grid.dLatDeg, -90.0, 90.0);
        for (uint32_t iLon = 0; iLon < w.grid.nLon; ++iLon)
        {
            const double lon = w.grid.lon0Deg + iLon * w.grid.dLonDeg;
            const size_t cell = w.grid.index(iLat, iLon);
            CigiCloudsAt under;
            for (size_t i = 0; i < 3; ++i)
                under[i] = slot[i] >= 0 ? griddedAt(w.layers[size_t(slot[i])], cell, uint8_t(i + 1))
                                        : unset(uint8_t(i + 1));
            const double nM = geoid.undulationM(lat, lon);
            const CigiCloudsAt clouds = fade.cloudsOver(under, lat, lon, nowS, std::isfinite(nM) ? float(nM) : 0.0f);
            for (size_t i = 0; i < 3; ++i)
            {
                const CigiCloudAt& c = clouds[i];
                if (cigiSameDrawnLayer(c, under[i]))
                    continue; // the host changes nothing here: the gridded values stay exactly
                CloudLayerFields* l = slot[i] >= 0 ? &w.layers[size_t(slot[i])] : nullptr;
                if (c.coverage > 0 && cigiHighCloudType(c.cloudType))
                {
                    if (l)
                        l->coverage[cell] = 0.0f; // the host's layer is a cirrus here: its slot is clear
                    if (!highMade)
                        ensureHigh(w.high, cells), highMade = true;
                    if (c.coverage <= w.high.coverage[cell])
                        continue; // one high layer per cell: the densest
                    w.high.coverage[cell] = c.coverage;
                    w.high.altitudeM[cell] = 0.5f * (c.baseMslM + c.topMslM);
                    w.high.type[cell] = c.cloudType;
                    w.high.windEastMS[cell] = c.windEastMps;
                    w.high.windNorthMS[cell] = c.windNorthMps;
                    continue;
                }
                if (!l)
                    continue; // a volumetric cloud of a layer matched as cirrus: no slot to draw it in
                // Precipitation falls from the gridded cloud: it thins with it and stops where it is gone.
                const float kept = under[i].set && under[i].coverage > 0
                                       ? std::clamp(c.coverage / under[i].coverage, 0.0f, 1.0f)
                                       : 0.0f;
                float& rain = l->precipitationMmH[cell];
                rain = std::isfinite(rain) ? rain * kept : 0.0f;
                l->coverage[cell] = c.coverage;
                l->baseAltitudeM[cell] = c.baseMslM;
                l->topAltitudeM[cell] = c.topMslM;
                l->type[cell] = c.cloudType;
                l->windEastMS[cell] = c.windEastMps;
                l->windNorthMS[cell] = c.windNorthMps;
            }
        }
    }
    // Lowest first, as the snapshot's convention says: by each layer's altitude near the ownship.
    std::vector<Extent> extents;
    for (const CloudLayerFields& l : w.layers)
        extents.push_back(griddedExtent(w, l, ownLatDeg, ownLonDeg));
    std::vector<size_t> order(w.layers.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b)
                     {
                         const float ba = extents[a].any ? extents[a].baseM : std::numeric_limits<float>::infinity();
                         const float bb = extents[b].any ? extents[b].baseM : std::numeric_limits<float>::infinity();
                         return ba < bb;
                     });
    std::vector<CloudLayerFields> sorted;
    for (size_t k : order)
        sorted.push_back(std::move(w.layers[k]));
    w.layers = std::move(sorted);
    return w;
}

} // namespace sky
