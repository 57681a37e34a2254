// SPDX-License-Identifier: MIT
#include "weather_ingest/layer_builder.h"

#include "weather_ingest/ingest_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sky
{

LayerDefaults layerDefaults(LayerKind layer)
{
    // Standard-atmosphere altitudes in brackets.
    switch (layer)
    {
    case LayerKind::Low: return {95000.0, 80000.0};          // 540 m .. 1950 m
    case LayerKind::Middle: return {70000.0, 50000.0};       // 3010 m .. 5570 m
    case LayerKind::Convective: return {90000.0, 30000.0};   // 990 m .. 9160 m
    case LayerKind::High: return {35000.0, 25000.0};         // 8110 m .. 10360 m
    }
    return {95000.0, 80000.0};
}

std::string cellName(const LatLonGrid& grid, size_t cell)
{
    char buf[64];
    const size_t iLat = cell / grid.nLon;
    const size_t iLon = cell % grid.nLon;
    std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", grid.lat0Deg + double(iLat) * grid.dLatDeg,
                  grid.lon0Deg + double(iLon) * grid.dLonDeg);
    return buf;
}

void ValueChecker::fail(const std::string& field, const std::string& source, const std::string& detail) const
{
    throw IngestError(IngestErrorKind::BadValues, file_, source, field,
                      detail + " (sky-ingest convert --lenient repairs this with a warning)");
}

void ValueChecker::invalidValues(size_t count, const std::string& field, const std::string& source) const
{
    if (count == 0)
        return;
    const std::string text = std::to_string(count) + " NaN/infinite values that are not flagged as missing";
    if (!options_.lenient)
        fail(field, source, text);
    warn(source + ": " + text + "; treated as missing");
}

void ValueChecker::coverage(std::vector<float>& values, float scale, const std::string& field,
                            const std::string& source, const LatLonGrid& grid) const
{
    size_t bad = 0, firstBad = 0;
    float worst = 0;
    for (size_t i = 0; i < values.size(); ++i)
    {
        float& v = values[i];
        if (std::isnan(v))
            continue;
        v *= scale;
        if (v < -0.005f || v > 1.005f)
        {
            if (bad++ == 0)
            {
                firstBad = i;
                worst = v;
            }
        }
        v = std::clamp(v, 0.0f, 1.0f);
    }
    if (bad == 0)
        return;
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu coverage values outside [0, 100] %%, e.g. %g %% at %s", bad,
                  double(worst) * 100.0, cellName(grid, firstBad).c_str());
    if (!options_.lenient)
        fail(field, source, buf);
    warn(source + ": " + buf + "; clamped");
}

void ValueChecker::baseBelowTop(std::vector<float>& base, std::vector<float>& top, const std::string& field,
                                const std::string& source, const LatLonGrid& grid) const
{
    size_t bad = 0, firstBad = 0;
    for (size_t i = 0; i < base.size(); ++i)
    {
        if (base[i] > top[i] + 1.0f)  // false when either is NaN
        {
            if (bad++ == 0)
                firstBad = i;
            std::swap(base[i], top[i]);
        }
    }
    if (bad == 0)
        return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "cloud base above cloud top in %zu cells, e.g. base %.0f m, top %.0f m at %s", bad,
                  double(top[firstBad]), double(base[firstBad]), cellName(grid, firstBad).c_str());
    if (!options_.lenient)
        fail(field, source, buf);
    warn(source + ": " + buf + "; swapped");
}

void ValueChecker::range(std::vector<float>& values, float lo, float hi, const std::string& field,
                         const std::string& source, const LatLonGrid& grid) const
{
    size_t bad = 0, firstBad = 0;
    for (size_t i = 0; i < values.size(); ++i)
    {
        if (!std::isnan(values[i]) && !(values[i] >= lo && values[i] <= hi))
        {
            if (bad++ == 0)
                firstBad = i;
        }
    }
    if (bad == 0)
        return;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%zu values outside [%g, %g], e.g. %g at %s", bad, double(lo), double(hi),
                  double(values[firstBad]), cellName(grid, firstBad).c_str());
    if (!options_.lenient)
        fail(field, source, buf);
    for (float& v : values)
        if (!std::isnan(v) && !(v >= lo && v <= hi))
            v = NAN;
    warn(source + ": " + buf + "; treated as missing");
}

std::vector<CloudLayerFields> makeEmptyLayers(size_t n)
{
    std::vector<CloudLayerFields> layers(3);
    const char* names[] = {"low", "middle", "convective"};
    for (size_t i = 0; i < 3; ++i)
    {
        CloudLayerFields& l = layers[i];
        l.name = names[i];
        l.coverage.assign(n, 0.0f);
        l.baseAltitudeM.assign(n, NAN);
        l.topAltitudeM.assign(n, NAN);
        l.type.assign(n, 0);
        l.precipitationMmH.assign(n, 0.0f);
        l.windEastMS.assign(n, 0.0f);
        l.windNorthMS.assign(n, 0.0f);
    }
    return layers;
}

void attributePrecipitation(WeatherSnapshot& s, const std::vector<float>& convectiveMmH,
                            const std::vector<float>& largeScaleMmH)
{
    CloudLayerFields& low = s.layers[kLowLayer];
    CloudLayerFields& mid = s.layers[kMiddleLayer];
    CloudLayerFields& conv = s.layers[kConvectiveLayer];
    const size_t n = s.grid.cellCount();
    for (size_t i = 0; i < n; ++i)
    {
        const float c = convectiveMmH.empty() || !std::isfinite(convectiveMmH[i]) ? 0.0f : convectiveMmH[i];
        const float l = largeScaleMmH.empty() || !std::isfinite(largeScaleMmH[i]) ? 0.0f : largeScaleMmH[i];
        (conv.coverage[i] >= kMinCloudCoverage ? conv : low).precipitationMmH[i] += c;
        const float midCover = std::isfinite(mid.coverage[i]) ? mid.coverage[i] : 0.0f;
        const float lowCover = std::isfinite(low.coverage[i]) ? low.coverage[i] : 0.0f;
        (midCover > lowCover ? mid : low).precipitationMmH[i] += l;
    }
}

void assignCloudTypes(WeatherSnapshot& s, const std::vector<float>& convectiveMmH)
{
    const size_t n = s.grid.cellCount();
    const LayerKind kinds[] = {LayerKind::Low, LayerKind::Middle, LayerKind::Convective};
    for (size_t li = 0; li < s.layers.size() && li < 3; ++li)
    {
        CloudLayerFields& l = s.layers[li];
        l.type.assign(n, 0);
        for (size_t i = 0; i < n; ++i)
        {
            CloudTypeInputs in;
            in.layer = kinds[li];
            in.coverage = l.coverage[i];
            in.thicknessM = l.topAltitudeM[i] - l.baseAltitudeM[i];
            in.precipMmH = l.precipitationMmH[i];
            in.capeJKg = s.capeJKg.empty() ? NAN : s.capeJKg[i];
            in.convPrecipMmH = convectiveMmH.empty() ? 0.0f : convectiveMmH[i];
            l.type[i] = static_cast<uint8_t>(classifyCloud(in));
        }
    }
    if (s.high.coverage.empty())
        return;
    s.high.type.assign(n, 0);
    for (size_t i = 0; i < n; ++i)
    {
        CloudTypeInputs in;
        in.layer = LayerKind::High;
        in.coverage = s.high.coverage[i];
        in.capeJKg = s.capeJKg.empty() ? NAN : s.capeJKg[i];
        in.convPrecipMmH = convectiveMmH.empty() ? 0.0f : convectiveMmH[i];
        s.high.type[i] = static_cast<uint8_t>(classifyCloud(in));
    }
}

}  // namespace sky
