// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_weather.h"

#include "skyservice/service/cigi_weather_fade.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sky
{
namespace
{

using cigi::CigiState;
using cigi::EnvironmentalRegion;
using cigi::RegionState;
using cigi::WeatherLayer;

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kEarthRadiusM = 6371008.8; // mean radius: region shapes are local, tens of km
constexpr double kMetresPerDegreeLat = kEarthRadiusM * kDegToRad;

// A regional grid: cells no finer than 1 km or coarser than 5 km, at most this many cells from the centre
// to an edge (401 x 401 cells: 16 MB of fields for three layers), and never wider than the renderer's
// weather window (800 km).
constexpr double kMinRegionalSpacingM = 1000.0, kMaxRegionalSpacingM = 5000.0;
constexpr double kMaxRegionalCellsFromCentre = 200.0;
constexpr double kMaxRegionalHalfExtentM = 800000.0;

bool drawnType(uint8_t type)
{
    return type >= uint8_t(CloudType::Altocumulus) && type <= uint8_t(CloudType::Stratus);
}

bool highType(uint8_t type)
{
    return type == uint8_t(CloudType::Cirrocumulus) || type == uint8_t(CloudType::Cirrostratus) ||
           type == uint8_t(CloudType::Cirrus);
}

float lerp(float a, float b, float t)
{
    return a + (b - a) * t;
}

double wrapDeg(double deg)
{
    const double w = std::fmod(deg + 180.0, 360.0);
    return (w < 0 ? w + 360.0 : w) - 180.0;
}

} // namespace

bool cigiHighCloudType(uint8_t type)
{
    return highType(type);
}

CigiCloudAt cigiLayerFromHost(const WeatherLayer& l)
{
    CigiCloudAt c;
    c.layerId = l.layerId;
    c.set = true;
    const uint8_t type = static_cast<uint8_t>(l.cloudType);
    const bool drawn = l.enabled && drawnType(type) && l.thicknessM > 0 && l.coveragePct > 0;
    c.coverage = drawn ? std::min(1.0f, l.coveragePct / 100.0f) : 0.0f;
    c.baseMslM = l.baseElevationMslM;
    c.topMslM = l.baseElevationMslM + l.thicknessM;
    c.cloudType = type;
    cigiWindComponents(l.horizontalWindMps, l.windDirectionDeg, c.windEastMps, c.windNorthMps);
    c.verticalWindMps = l.verticalWindMps;
    c.humidityPct = l.humidityPct;
    c.aerosolGPerM3 = l.aerosolGPerM3;
    return c;
}

void cigiBlendLayer(CigiCloudAt& current, const CigiCloudAt& region, float t)
{
    if (t <= 0)
        return;
    const float coverage = lerp(current.set ? current.coverage : 0.0f, region.coverage, t);
    if (!current.set || current.coverage <= 0)
    {
        const float keep = current.coverage;
        current = region;
        current.coverage = region.coverage > 0 ? coverage : keep * (1 - t);
    }
    else if (region.coverage > 0)
    {
        current.baseMslM = lerp(current.baseMslM, region.baseMslM, t);
        current.topMslM = lerp(current.topMslM, region.topMslM, t);
        current.windEastMps = lerp(current.windEastMps, region.windEastMps, t);
        current.windNorthMps = lerp(current.windNorthMps, region.windNorthMps, t);
        current.verticalWindMps = lerp(current.verticalWindMps, region.verticalWindMps, t);
        current.humidityPct = lerp(current.humidityPct, region.humidityPct, t);
        current.aerosolGPerM3 = lerp(current.aerosolGPerM3, region.aerosolGPerM3, t);
        if (t >= 0.5f)
            current.cloudType = region.cloudType;
        current.coverage = coverage;
    }
    else
        current.coverage = coverage;
    current.set = true;
}

bool cigiSameDrawnLayer(const CigiCloudAt& a, const CigiCloudAt& b)
{
    return a.layerId == b.layerId && a.set == b.set && a.coverage == b.coverage && a.baseMslM == b.baseMslM &&
           a.topMslM == b.topMslM && a.cloudType == b.cloudType && a.windEastMps == b.windEastMps &&
           a.windNorthMps == b.windNorthMps;
}

bool cigiRegionDrawn(const EnvironmentalRegion& r)
{
    return r.defined && r.state == RegionState::Active && !r.layers.empty();
}

void cigiWindComponents(float speedMps, float fromDeg, float& eastMps, float& northMps)
{
    // The wind blows from `fromDeg`: towards fromDeg + 180.
    const double a = double(fromDeg) * kDegToRad;
    eastMps = float(-double(speedMps) * std::sin(a));
    northMps = float(-double(speedMps) * std::cos(a));
}

bool cigiHasCloudWeather(const CigiState& state)
{
    auto cloudLayer = [](const auto& entry) { return entry.first >= 1 && entry.first <= 3; };
    if (std::any_of(state.globalLayers.begin(), state.globalLayers.end(), cloudLayer))
        return true;
    return std::any_of(state.regions.begin(), state.regions.end(),
                       [&](const auto& r)
                       { return std::any_of(r.second.layers.begin(), r.second.layers.end(), cloudLayer); });
}

double cigiRegionWeight(const EnvironmentalRegion& r, double latDeg, double lonDeg)
{
    const double north = (latDeg - r.latDeg) * kMetresPerDegreeLat;
    const double east = wrapDeg(lonDeg - r.lonDeg) * kMetresPerDegreeLat * std::cos(r.latDeg * kDegToRad);
    const double rot = double(r.rotationDeg) * kDegToRad;
    const double x = north * std::cos(rot) + east * std::sin(rot);
    const double y = -north * std::sin(rot) + east * std::cos(rot);
    const double hx = 0.5 * double(r.sizeXM), hy = 0.5 * double(r.sizeYM);
    const double radius = std::clamp(double(r.cornerRadiusM), 0.0, std::min(hx, hy));
    // Signed distance to the rounded rectangle (negative inside).
    const double qx = std::fabs(x) - hx + radius, qy = std::fabs(y) - hy + radius;
    const double d = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) - radius;
    if (d <= 0)
        return 1;
    const double band = double(r.transitionPerimeterM);
    if (!(band > 0) || d >= band)
        return 0;
    const double t = d / band;
    return 1 - t * t * (3 - 2 * t);
}

CigiCloudsAt cigiCloudsAt(const CigiState& state, double latDeg, double lonDeg)
{
    CigiWeatherFade asSet; // the first target is drawn at once: no fade
    asSet.setTarget(state, 0);
    return asSet.cloudsAt(latDeg, lonDeg, 0);
}

CigiWeatherGrid cigiWeatherGrid(const CigiState& state, double ownLatDeg, double ownLonDeg)
{
    CigiWeatherFade asSet;
    asSet.setTarget(state, 0);
    return cigiWeatherGrid(asSet, ownLatDeg, ownLonDeg);
}

CigiWeatherGrid cigiWeatherGrid(const CigiWeatherFade& fade, double ownLatDeg, double ownLonDeg, bool overGridded)
{
    CigiWeatherGrid g;
    double spacingM = std::numeric_limits<double>::infinity();
    for (const auto& [id, f] : fade.regions())
    {
        const EnvironmentalRegion& r = f.shape;
        double feature = std::min(double(r.sizeXM), double(r.sizeYM));
        if (r.transitionPerimeterM > 0)
            feature = std::min(feature, double(r.transitionPerimeterM));
        spacingM = std::min(spacingM, feature / 3.0);
    }
    if (!std::isfinite(spacingM))
    {
        g.grid = LatLonGrid{-90.0, -180.0, 1.0, 1.0, 181, 360};
        return g;
    }
    if (overGridded)
        spacingM = std::max(spacingM, kMaxRegionalHalfExtentM / kMaxRegionalCellsFromCentre);
    spacingM = std::clamp(spacingM, kMinRegionalSpacingM, kMaxRegionalSpacingM);
    const double cells = std::floor(std::min(kMaxRegionalCellsFromCentre, kMaxRegionalHalfExtentM / spacingM));
    g.regional = true;
    g.centreLatDeg = ownLatDeg;
    g.centreLonDeg = ownLonDeg;
    g.halfExtentM = cells * spacingM;
    const double dLat = spacingM / kMetresPerDegreeLat;
    const double dLon = dLat / std::max(std::cos(std::min(std::fabs(ownLatDeg), 85.0) * kDegToRad), 0.087);
    const double south = std::max(-90.0, ownLatDeg - cells * dLat);
    const double north = std::min(90.0, ownLatDeg + cells * dLat);
    g.grid.lat0Deg = south;
    g.grid.dLatDeg = dLat;
    g.grid.nLat = uint32_t(std::floor((north - south) / dLat)) + 1;
    g.grid.lon0Deg = ownLonDeg - cells * dLon;
    g.grid.dLonDeg = dLon;
    g.grid.nLon = uint32_t(std::min(2.0 * cells + 1.0, std::floor(360.0 / dLon)));
    return g;
}

WeatherSnapshot cigiWeatherSnapshot(const CigiState& state, const CigiWeatherGrid& where, const cigi::GeoidGrid& geoid,
                                    int64_t validTimeUnixS)
{
    CigiWeatherFade asSet;
    asSet.setTarget(state, 0);
    return cigiWeatherSnapshot(asSet, 0, where, geoid, validTimeUnixS);
}

WeatherSnapshot cigiWeatherSnapshot(const CigiWeatherFade& fade, double nowS, const CigiWeatherGrid& where,
                                    const cigi::GeoidGrid& geoid, int64_t validTimeUnixS)
{
    WeatherSnapshot w;
    w.grid = where.grid;
    w.validTimeUnixS = validTimeUnixS;
    w.provenance["clouds"] = "CIGI host: Weather Control / Environmental Region Control";
    const size_t n = w.grid.cellCount();
    std::array<CloudLayerFields, 3> layers;
    for (size_t i = 0; i < 3; ++i)
    {
        CloudLayerFields& l = layers[i];
        l.name = "cigi layer " + std::to_string(i + 1);
        l.coverage.assign(n, 0.0f);
        l.baseAltitudeM.assign(n, 0.0f);
        l.topAltitudeM.assign(n, 0.0f);
        l.type.assign(n, uint8_t(CloudType::None));
        l.precipitationMmH.assign(n, 0.0f); // rain and snow layers are not drawn
        l.windEastMS.assign(n, 0.0f);
        l.windNorthMS.assign(n, 0.0f);
    }
    HighCloudFields high;
    high.coverage.assign(n, 0.0f);
    high.altitudeM.assign(n, 0.0f);
    high.type.assign(n, uint8_t(CloudType::None));
    high.windEastMS.assign(n, 0.0f);
    high.windNorthMS.assign(n, 0.0f);
    std::array<bool, 3> used{};
    bool anyHigh = false;
    std::array<float, 3> lowestBase;
    lowestBase.fill(std::numeric_limits<float>::infinity());
    for (uint32_t iLat = 0; iLat < w.grid.nLat; ++iLat)
    {
        const double lat = std::clamp(w.grid.lat0Deg + iLat * w.grid.dLatDeg, -90.0, 90.0);
        for (uint32_t iLon = 0; iLon < w.grid.nLon; ++iLon)
        {
            const double lon = w.grid.lon0Deg + iLon * w.grid.dLonDeg;
            const size_t cell = w.grid.index(iLat, iLon);
            const CigiCloudsAt clouds = fade.cloudsAt(lat, lon, nowS);
            const double nM = geoid.undulationM(lat, lon);
            const float undulationM = std::isfinite(nM) ? float(nM) : 0.0f;
            for (size_t i = 0; i < 3; ++i)
            {
                const CigiCloudAt& c = clouds[i];
                if (c.coverage <= 0)
                    continue;
                if (highType(c.cloudType))
                {
                    if (c.coverage <= high.coverage[cell])
                        continue; // one high layer per cell: the densest
                    high.coverage[cell] = c.coverage;
                    high.altitudeM[cell] = 0.5f * (c.baseMslM + c.topMslM) + undulationM;
                    high.type[cell] = c.cloudType;
                    high.windEastMS[cell] = c.windEastMps;
                    high.windNorthMS[cell] = c.windNorthMps;
                    anyHigh = true;
                    continue;
                }
                CloudLayerFields& l = layers[i];
                l.coverage[cell] = c.coverage;
                l.baseAltitudeM[cell] = c.baseMslM + undulationM;
                l.topAltitudeM[cell] = c.topMslM + undulationM;
                l.type[cell] = c.cloudType;
                l.windEastMS[cell] = c.windEastMps;
                l.windNorthMS[cell] = c.windNorthMps;
                used[i] = true;
                lowestBase[i] = std::min(lowestBase[i], c.baseMslM);
            }
        }
    }
    std::array<size_t, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lowestBase[a] < lowestBase[b]; });
    for (size_t i : order)
        if (used[i])
            w.layers.push_back(std::move(layers[i])); // lowest first, as the snapshot's convention says
    if (anyHigh)
        w.high = std::move(high);
    return w;
}

} // namespace sky
