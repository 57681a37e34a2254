// SPDX-License-Identifier: MIT
#include "weather_ingest/grib_mapping.h"

#include "weather_ingest/ingest_error.h"
#include "weather_ingest/pressure_altitude.h"

#include <algorithm>
#include <cmath>

namespace sky
{
namespace
{

constexpr double kStandardGravity = 9.80665;  // m s^-2, WMO (ICAO Doc 7488/3)
constexpr float kSecondsPerHour = 3600.0f;

// ECMWF's cloud-cover bands (IFS documentation, Part IV "Physical processes": low/medium/high cloud cover
// are diagnosed below sigma 0.8, between 0.8 and 0.45, and above 0.45), taken here on pressure levels.
constexpr double kEcmwfLowTopPa = 80000.0;
constexpr double kEcmwfMiddleTopPa = 45000.0;
constexpr float kCloudyLevelFraction = 0.05f;  // a pressure level counts as cloudy from 5 % cover

struct CoverRecords;

class GribMapper
{
public:
    GribMapper(const std::vector<const GribRecord*>& records, const MappingOptions& options,
               std::vector<std::string>& warnings)
        : records_(records), check_(options, warnings, records.empty() ? std::string() : records[0]->file)
    {
    }

    WeatherSnapshot run();

private:
    const GribRecord* find(GribRole role) const
    {
        const GribRecord* best = nullptr;
        for (const GribRecord* r : records_)
            if (r->row.role == role && (!best || r->row.priority < best->row.priority))
                best = r;
        return best;
    }

    LevelStack stack(GribRole role, float scale)
    {
        LevelStack s;
        for (const GribRecord* r : records_)
        {
            if (r->row.role != role)
                continue;
            // Cloud cover on levels comes as a fraction (ECMWF cc) or in % (ICON CLC).
            const float unit =
                role == GribRole::LevelCloudCover && r->info.units.find('%') != std::string::npos ? 0.01f : 1.0f;
            if (scale * unit != 1.0f)
            {
                std::vector<float> v = r->field.values;
                for (float& x : v)
                    x *= scale * unit;
                s.addLevel(r->levelPa, std::move(v));
            }
            else // the record outlives the mapping: a view, not a copy of the field
            {
                s.addLevelView(r->levelPa, r->field.values.data(), r->field.values.size());
            }
            note(r);
        }
        return s;
    }

    /// Every record that is used has its undeclared NaN counted (an error unless lenient).
    void note(const GribRecord* r) { check_.invalidValues(r->field.invalidCount, r->info.label(), r->source); }

    std::vector<float> coverage(const GribRecord* r)
    {
        std::vector<float> v = r->field.values;
        const float scale = r->info.units.find('%') != std::string::npos ? 0.01f : 1.0f;
        check_.coverage(v, scale, r->info.label(), r->source, grid_);
        note(r);
        return v;
    }

    std::vector<float> values(const GribRecord* r, float lo, float hi)
    {
        std::vector<float> v = r->field.values;
        check_.range(v, lo, hi, r->info.label(), r->source, grid_);
        note(r);
        return v;
    }

    /// A rate in mm/h from a rate (kg m-2 s-1) or an accumulation (kg m-2 = mm, or m of water).
    std::vector<float> rateMmH(GribRole rateRole, GribRole accRole, std::string& source)
    {
        if (const GribRecord* r = find(rateRole))
        {
            std::vector<float> v = values(r, 0.0f, 1.0f);
            for (float& x : v)
                x *= kSecondsPerHour;
            source = r->source + " (kg m-2 s-1 x 3600)";
            return v;
        }
        const GribRecord* r = find(accRole);
        if (!r)
            return {};
        if (r->info.accumulationHours <= 0)
        {
            check_.warn(r->source + ": accumulation period unknown; not used as a rate");
            return {};
        }
        const float toMm = r->info.units == "m" ? 1000.0f : 1.0f;
        std::vector<float> v = values(r, 0.0f, r->info.units == "m" ? 10.0f : 10000.0f);
        const auto scale = static_cast<float>(double(toMm) / r->info.accumulationHours);
        for (float& x : v)
            x *= scale;
        source = r->source + " (accumulated over " + std::to_string(int(r->info.accumulationHours)) + " h)";
        return v;
    }

    // The steps of run(), in order.
    CoverRecords coverRecords() const;
    void requireOneGrid(const GribRecord& anyCover);  ///< sets grid_; every record must be on it
    void readLevelStacks(WeatherSnapshot& s);         ///< heights, winds, cloud cover per level; ground
    void layerCoverage(const CoverRecords& c, WeatherSnapshot& s);
    void surfaceAndTropopause(WeatherSnapshot& s);  ///< visibility, CAPE, tropopause altitude
    std::vector<float> precipitation(WeatherSnapshot& s);  ///< returns the convective rate (mm/h)
    void keepLevelFields(WeatherSnapshot& s);
    void heights(size_t layerIndex, LayerKind kind, GribRole bottomRole, GribRole topRole, WeatherSnapshot& s);
    void highLayer(WeatherSnapshot& s);
    bool ccBand(size_t cell, double pHighPa, double pLowPa, float& baseM, float& topM) const;

    const std::vector<const GribRecord*>& records_;
    ValueChecker check_;
    LatLonGrid grid_;
    LevelStack heightM_, windU_, windV_, cloudCover_;
    std::vector<float> ground_;  // ground altitude (m), for above-ground heights; may be empty
};

/// Base and top (m) of the cloudy pressure levels (cc >= 5 %) with pressure in [pHighPa, pLowPa).
bool GribMapper::ccBand(size_t cell, double pHighPa, double pLowPa, float& baseM, float& topM) const
{
    bool any = false;
    for (size_t k = 0; k < cloudCover_.levelCount(); ++k)
    {
        const double p = cloudCover_.pressurePa(k);
        if (p < pHighPa || p >= pLowPa || !(cloudCover_.level(k)[cell] >= kCloudyLevelFraction))
            continue;
        const float z = pressureToAltitudeM(heightM_, cell, p);
        baseM = any ? std::min(baseM, z) : z;
        topM = any ? std::max(topM, z) : z;
        any = true;
    }
    if (any && topM - baseM < 500.0f)
        topM = baseM + 500.0f;  // one cloudy level: give the cloud a minimal depth
    return any;
}

void GribMapper::heights(size_t layerIndex, LayerKind kind, GribRole bottomRole, GribRole topRole, WeatherSnapshot& s)
{
    CloudLayerFields& l = s.layers[layerIndex];
    const size_t n = grid_.cellCount();
    const GribRecord* bottom = find(bottomRole);
    const GribRecord* top = find(topRole);
    std::vector<float> pb, pt;
    if (bottom && top)
    {
        pb = values(bottom, 1.0f, 110000.0f);
        pt = values(top, 1.0f, 110000.0f);
        s.provenance["layers/" + std::to_string(layerIndex) + "/baseAltitudeM"] = bottom->source;
        s.provenance["layers/" + std::to_string(layerIndex) + "/topAltitudeM"] = top->source;
    }
    // The lowest cloud base (ECMWF cbh / ICON ceiling above ground, HRRR gh on cloudBase above sea level)
    // belongs to the low layer, or to the middle one where there is no low cloud.
    const GribRecord* cbh = kind != LayerKind::Convective ? find(GribRole::CloudBaseHeight) : nullptr;
    const GribRecord* baseMsl = kind != LayerKind::Convective ? find(GribRole::CloudBaseHeightMsl) : nullptr;
    const GribRecord* topMsl = kind == LayerKind::Low ? find(GribRole::CloudTopHeightMsl) : nullptr;
    std::vector<float> cbhM = cbh ? values(cbh, -1000.0f, 30000.0f) : std::vector<float>();
    const std::vector<float> baseMslM = baseMsl ? values(baseMsl, -1000.0f, 30000.0f) : std::vector<float>();
    const std::vector<float> topMslM = topMsl ? values(topMsl, -1000.0f, 30000.0f) : std::vector<float>();
    const std::vector<float>& lowCover = s.layers[kLowLayer].coverage;
    const std::vector<float>& middleCover = s.layers[kMiddleLayer].coverage;
    const auto lowest = [&](size_t i) { return kind == LayerKind::Low || !(lowCover[i] >= kMinCloudCoverage); };
    if (cbh && kind == LayerKind::Middle)
        s.provenance["layers/1/baseAltitudeM"] = cbh->source + " where no low cloud";
    if (baseMsl)
        s.provenance["layers/" + std::to_string(layerIndex) + "/baseAltitudeM"] =
            baseMsl->source + (kind == LayerKind::Middle ? " where no low cloud" : "");
    if (topMsl)
        s.provenance["layers/0/topAltitudeM"] = topMsl->source + " where there is no middle cloud";
    const LayerDefaults def = layerDefaults(kind);
    const double bandLow = kind == LayerKind::Low ? 1e9 : kEcmwfLowTopPa;
    const double bandHigh = kind == LayerKind::Low ? kEcmwfLowTopPa : kEcmwfMiddleTopPa;
    size_t defaulted = 0;
    const double defaultMidPa = std::sqrt(def.basePa * def.topPa);
    const AltitudeAtPressure defaultBaseM(heightM_, def.basePa), defaultTopM(heightM_, def.topPa);
    const LevelSampler defaultU(windU_, defaultMidPa, false), defaultV(windV_, defaultMidPa, false);
    for (size_t i = 0; i < n; ++i)
    {
        double midPa = defaultMidPa;
        bool atDefault = true;
        if (!pb.empty() && std::isfinite(pb[i]) && std::isfinite(pt[i]))
        {
            atDefault = false;
            l.baseAltitudeM[i] = pressureToAltitudeM(heightM_, i, pb[i]);
            l.topAltitudeM[i] = pressureToAltitudeM(heightM_, i, pt[i]);
            midPa = std::sqrt(double(pb[i]) * double(pt[i]));
        }
        else if (l.coverage[i] >= kMinCloudCoverage)
        {
            float baseM = NAN, topM = NAN;
            if (kind != LayerKind::Convective && !cloudCover_.empty() && ccBand(i, bandHigh, bandLow, baseM, topM))
            {
                l.baseAltitudeM[i] = baseM;
                l.topAltitudeM[i] = topM;
            }
            else
            {
                l.baseAltitudeM[i] = defaultBaseM(i);
                l.topAltitudeM[i] = defaultTopM(i);
                ++defaulted;
            }
            const float depthM = l.topAltitudeM[i] - l.baseAltitudeM[i];
            if (!cbhM.empty() && std::isfinite(cbhM[i]) && lowest(i))
            {
                const float groundM = ground_.empty() || !std::isfinite(ground_[i]) ? 0.0f : ground_[i];
                l.baseAltitudeM[i] = groundM + cbhM[i];
                l.topAltitudeM[i] = std::max(l.topAltitudeM[i], l.baseAltitudeM[i] + std::max(depthM, 300.0f));
            }
            else if (!baseMslM.empty() && std::isfinite(baseMslM[i]) && lowest(i))
            {
                l.baseAltitudeM[i] = baseMslM[i];
                l.topAltitudeM[i] = std::max(l.topAltitudeM[i], l.baseAltitudeM[i] + std::max(depthM, 300.0f));
            }
            if (!topMslM.empty() && std::isfinite(topMslM[i]) && topMslM[i] > l.baseAltitudeM[i] &&
                !(middleCover[i] >= kMinCloudCoverage))
                l.topAltitudeM[i] = topMslM[i];
        }
        if (!windU_.empty() && !windV_.empty())
        {
            const float u = atDefault ? defaultU(i) : windU_.at(i, midPa, false);
            const float v = atDefault ? defaultV(i) : windV_.at(i, midPa, false);
            l.windEastMS[i] = std::isfinite(u) ? u : 0.0f;
            l.windNorthMS[i] = std::isfinite(v) ? v : 0.0f;
        }
    }
    if (defaulted > 0)
        s.provenance["layers/" + std::to_string(layerIndex) + "/defaults"] =
            std::to_string(defaulted) + " cells without base/top: default " + std::to_string(int(def.basePa / 100)) +
            ".." + std::to_string(int(def.topPa / 100)) + " hPa";
    const std::string what = "pres/" + std::string(layerKindName(kind)) + " cloud bottom vs top";
    check_.baseBelowTop(l.baseAltitudeM, l.topAltitudeM, what, bottom ? bottom->source : "layer defaults", grid_);
}

void GribMapper::highLayer(WeatherSnapshot& s)
{
    const GribRecord* cover = find(GribRole::CoverHigh);
    if (!cover)
        return;
    const size_t n = grid_.cellCount();
    s.high.coverage = coverage(cover);
    s.provenance["high/coverage"] = cover->source;
    const GribRecord* bottom = find(GribRole::PresHighBottom);
    const GribRecord* top = find(GribRole::PresHighTop);
    std::vector<float> pb, pt;
    if (bottom && top)
    {
        pb = values(bottom, 1.0f, 110000.0f);
        pt = values(top, 1.0f, 110000.0f);
        s.provenance["high/altitudeM"] = bottom->source + " + " + top->source + " (mid-layer pressure)";
    }
    const LayerDefaults def = layerDefaults(LayerKind::High);
    s.high.altitudeM.assign(n, NAN);
    s.high.windEastMS.assign(n, 0.0f);
    s.high.windNorthMS.assign(n, 0.0f);
    const double defaultMidPa = std::sqrt(def.basePa * def.topPa);
    const AltitudeAtPressure defaultM(heightM_, defaultMidPa);
    const LevelSampler defaultU(windU_, defaultMidPa, false), defaultV(windV_, defaultMidPa, false);
    for (size_t i = 0; i < n; ++i)
    {
        double midPa = defaultMidPa;
        const bool atDefault = pb.empty() || !std::isfinite(pb[i]) || !std::isfinite(pt[i]);
        if (!atDefault)
            midPa = std::sqrt(double(pb[i]) * double(pt[i]));
        float baseM = NAN, topM = NAN;
        if (pb.empty() && !cloudCover_.empty() && ccBand(i, 1.0, kEcmwfMiddleTopPa, baseM, topM))
            s.high.altitudeM[i] = 0.5f * (baseM + topM);
        else
            s.high.altitudeM[i] = atDefault ? defaultM(i) : pressureToAltitudeM(heightM_, i, midPa);
        if (!windU_.empty() && !windV_.empty())
        {
            const float u = atDefault ? defaultU(i) : windU_.at(i, midPa, false);
            const float v = atDefault ? defaultV(i) : windV_.at(i, midPa, false);
            s.high.windEastMS[i] = std::isfinite(u) ? u : 0.0f;
            s.high.windNorthMS[i] = std::isfinite(v) ? v : 0.0f;
        }
    }
}

/// The records that give each cloud layer's cover (null where absent); any is the first that exists.
struct CoverRecords
{
    const GribRecord *low, *boundary, *middle, *convective, *high, *any;
};

CoverRecords GribMapper::coverRecords() const
{
    CoverRecords c{};
    c.low = find(GribRole::CoverLow);
    c.boundary = find(GribRole::CoverBoundaryLayer);
    c.middle = find(GribRole::CoverMiddle);
    c.convective = find(GribRole::CoverConvective);
    c.high = find(GribRole::CoverHigh);
    c.any = c.low ? c.low : c.boundary ? c.boundary : c.middle ? c.middle : c.convective ? c.convective : c.high;
    if (!c.any)
        throw IngestError(IngestErrorKind::MissingFields, records_.empty() ? "" : records_[0]->file, "", "",
                          "no cloud cover field: looked for tcc on the low/middle/high/convective/boundary-layer "
                          "cloud layers (GFS) and lcc/mcc/hcc (ECMWF)");
    return c;
}

void GribMapper::requireOneGrid(const GribRecord& anyCover)
{
    grid_ = anyCover.field.grid;
    for (const GribRecord* r : records_)
        if (!sameGrid(r->field.grid, grid_))
            throw IngestError(IngestErrorKind::UnsupportedGrid, r->file, "message " + std::to_string(r->info.number),
                              r->info.label(),
                              "on a " + std::to_string(r->field.grid.nLon) + " x " + std::to_string(r->field.grid.nLat) +
                                  " grid unlike " + anyCover.source + " (" + std::to_string(grid_.nLon) + " x " +
                                  std::to_string(grid_.nLat) + "); give one grid per conversion");
}

void GribMapper::readLevelStacks(WeatherSnapshot& s)
{
    heightM_ = stack(GribRole::LevelHeight, 1.0f);
    if (heightM_.empty())
        heightM_ = stack(GribRole::LevelGeopotential, float(1.0 / kStandardGravity));
    s.provenance["altitudes"] = heightM_.empty()
                                    ? "pressure -> altitude: ICAO standard atmosphere (no geopotential on levels)"
                                    : "pressure -> altitude: geopotential height on " +
                                          std::to_string(heightM_.levelCount()) +
                                          " pressure levels, log-pressure interpolation";
    windU_ = stack(GribRole::LevelU, 1.0f);
    windV_ = stack(GribRole::LevelV, 1.0f);
    cloudCover_ = stack(GribRole::LevelCloudCover, 1.0f);
    s.provenance["wind"] = windU_.empty() || windV_.empty()
                               ? "absent: 0 m/s"
                               : "u/v on " + std::to_string(windU_.levelCount()) +
                                     " pressure levels at each layer's mid-layer pressure";
    if (const GribRecord* orog = find(GribRole::Orography))
        ground_ = values(orog, -1000.0f, 9000.0f);
    else if (const GribRecord* z = find(GribRole::SurfaceGeopotential))
    {
        ground_ = values(z, -10000.0f, 90000.0f);
        for (float& g : ground_)
            g = static_cast<float>(double(g) / kStandardGravity);
    }
}

void GribMapper::layerCoverage(const CoverRecords& c, WeatherSnapshot& s)
{
    const size_t n = grid_.cellCount();
    if (c.low || c.boundary)
    {
        s.layers[kLowLayer].coverage = c.low ? coverage(c.low) : coverage(c.boundary);
        s.provenance["layers/0/coverage"] = c.low ? c.low->source : c.boundary->source;
        if (c.low && c.boundary)
        {
            const std::vector<float> bl = coverage(c.boundary);
            for (size_t i = 0; i < n; ++i)
                s.layers[kLowLayer].coverage[i] = std::fmax(s.layers[kLowLayer].coverage[i], bl[i]);
            s.provenance["layers/0/coverage"] += " max " + c.boundary->source;
        }
    }
    if (c.middle)
    {
        s.layers[kMiddleLayer].coverage = coverage(c.middle);
        s.provenance["layers/1/coverage"] = c.middle->source;
    }
    if (c.convective)
    {
        s.layers[kConvectiveLayer].coverage = coverage(c.convective);
        s.provenance["layers/2/coverage"] = c.convective->source;
    }
}

void GribMapper::surfaceAndTropopause(WeatherSnapshot& s)
{
    const size_t n = grid_.cellCount();
    if (const GribRecord* vis = find(GribRole::Visibility))
        s.provenance["visibility"] = vis->source + " (read, not rendered yet)";
    if (const GribRecord* cape = find(GribRole::Cape))
    {
        s.capeJKg = values(cape, 0.0f, 20000.0f);
        s.provenance["capeJKg"] = cape->source;
    }
    if (const GribRecord* tropo = find(GribRole::TropopauseHeight))
    {
        s.tropopauseAltitudeM = values(tropo, 0.0f, 30000.0f);
        s.provenance["tropopauseAltitudeM"] = tropo->source;
    }
    else if (const GribRecord* trpp = find(GribRole::TropopausePressure))
    {
        const std::vector<float> p = values(trpp, 1.0f, 110000.0f);
        s.tropopauseAltitudeM.resize(n);
        for (size_t i = 0; i < n; ++i)
            s.tropopauseAltitudeM[i] = pressureToAltitudeM(heightM_, i, p[i]);
        s.provenance["tropopauseAltitudeM"] = trpp->source + " (pressure -> altitude)";
    }
}

std::vector<float> GribMapper::precipitation(WeatherSnapshot& s)
{
    const size_t n = grid_.cellCount();
    std::string convSource, totalSource, largeSource;
    std::vector<float> conv = rateMmH(GribRole::ConvPrecipRate, GribRole::ConvPrecipAcc, convSource);
    std::vector<float> total = rateMmH(GribRole::PrecipRate, GribRole::TotalPrecipAcc, totalSource);
    std::vector<float> large;
    if (!total.empty())
    {
        large = total;
        for (size_t i = 0; i < n && !conv.empty(); ++i)
            large[i] = std::max(0.0f, large[i] - (std::isfinite(conv[i]) ? conv[i] : 0.0f));
        largeSource = totalSource + (conv.empty() ? "" : " minus convective");
    }
    else
    {
        large = rateMmH(GribRole::Count, GribRole::LargeScalePrecipAcc, largeSource);
    }
    attributePrecipitation(s, conv, large);
    s.provenance["precipitation/convective"] = conv.empty() ? "absent" : convSource;
    s.provenance["precipitation/largeScale"] = large.empty() ? "absent" : largeSource;
    return conv;
}

void GribMapper::keepLevelFields(WeatherSnapshot& s)
{
    const std::pair<GribRole, const char*> kept[] = {{GribRole::LevelCloudMixingRatio, "cloudMixingRatio"},
                                                     {GribRole::LevelCloudCover, "cloudCover"},
                                                     {GribRole::LevelCloudLiquid, "cloudLiquidWater"},
                                                     {GribRole::LevelCloudIce, "cloudIceWater"}};
    for (const auto& [role, name] : kept)
    {
        LevelStack st = stack(role, 1.0f);
        if (st.empty())
            continue;
        PressureLevelField f;
        f.name = name;
        f.units = role == GribRole::LevelCloudCover ? "1" : "kg/kg";
        for (size_t k = 0; k < st.levelCount(); ++k)
            f.pressurePa.push_back(static_cast<float>(st.pressurePa(k)));
        f.values = st.concatenated();
        s.provenance["levelFields/" + std::string(name)] = find(role)->source + " and other levels";
        s.levelFields.push_back(std::move(f));
    }
}

WeatherSnapshot GribMapper::run()
{
    const CoverRecords cover = coverRecords();
    requireOneGrid(*cover.any);

    WeatherSnapshot s;
    s.grid = grid_;
    s.validTimeUnixS = cover.any->info.validTimeUnixS;
    s.layers = makeEmptyLayers(grid_.cellCount());

    readLevelStacks(s);
    layerCoverage(cover, s);
    heights(kLowLayer, LayerKind::Low, GribRole::PresLowBottom, GribRole::PresLowTop, s);
    heights(kMiddleLayer, LayerKind::Middle, GribRole::PresMiddleBottom, GribRole::PresMiddleTop, s);
    heights(kConvectiveLayer, LayerKind::Convective, GribRole::PresConvBottom, GribRole::PresConvTop, s);
    highLayer(s);
    surfaceAndTropopause(s);
    const std::vector<float> conv = precipitation(s);
    if (check_.options().keepLevelFields)
        keepLevelFields(s);
    assignCloudTypes(s, conv);
    s.provenance["types"] = "cloud-type rule table (README \"Cloud types\")";
    return s;
}

}  // namespace

WeatherSnapshot mapGribRecords(const std::vector<const GribRecord*>& records, const MappingOptions& options,
                               std::vector<std::string>& warnings)
{
    GribMapper mapper(records, options, warnings);
    return mapper.run();
}

}  // namespace sky
