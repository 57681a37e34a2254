// SPDX-License-Identifier: MIT
#include "weather_ingest/cloud_type_rules.h"

#include <cmath>
#include <limits>

namespace sky
{
namespace
{

constexpr float kInf = std::numeric_limits<float>::infinity();
using L = LayerKind;
using S = ConvectiveSignal;
using T = CloudType;

// Thickness and coverage thresholds follow the WMO International Cloud Atlas descriptions of the genera
// (stratus: a low uniform sheet a few hundred metres deep; nimbostratus: thick enough to hide the sun and
// to rain continuously; cumulonimbus: towers reaching the upper troposphere, typically > 5 km deep).
const std::vector<CloudTypeRule> kRules = {
    {L::Convective, 5000.0f, kInf, 0.0f, 2.0f, 0.0f, S::Strong, T::Cumulonimbus,
     "deep (>= 5 km) convective cloud with strong signals"},
    {L::Convective, -kInf, kInf, 0.0f, 2.0f, 0.0f, S::Any, T::Cumulus, "any other convective cloud"},
    {L::Low, 5000.0f, kInf, 0.0f, 2.0f, 0.0f, S::Strong, T::Cumulonimbus,
     "low cloud >= 5 km deep with strong signals (models without a convective layer)"},
    {L::Low, 1500.0f, kInf, 0.0f, 2.0f, 0.5f, S::Any, T::Nimbostratus, ">= 1.5 km deep, raining >= 0.5 mm/h"},
    {L::Low, -kInf, kInf, 0.0f, 0.7f, 0.0f, S::Weak, T::Cumulus, "broken (< 70 %) with weak convective signals"},
    {L::Low, -kInf, 1000.0f, 0.8f, 2.0f, 0.0f, S::Any, T::Stratus, "overcast (>= 80 %) and < 1 km deep"},
    {L::Low, -kInf, kInf, 0.0f, 2.0f, 0.0f, S::Any, T::Stratocumulus, "any other low cloud"},
    {L::Middle, 1500.0f, kInf, 0.0f, 2.0f, 0.5f, S::Any, T::Nimbostratus, ">= 1.5 km deep, raining >= 0.5 mm/h"},
    {L::Middle, -kInf, kInf, 0.7f, 2.0f, 0.0f, S::Any, T::Altostratus, "a sheet (>= 70 %)"},
    {L::Middle, -kInf, kInf, 0.0f, 2.0f, 0.0f, S::Any, T::Altocumulus, "any other middle cloud"},
    {L::High, -kInf, kInf, 0.7f, 2.0f, 0.0f, S::Any, T::Cirrostratus, "a veil (>= 70 %)"},
    {L::High, -kInf, kInf, 0.0f, 0.5f, 0.0f, S::Weak, T::Cirrocumulus, "patchy (< 50 %) with weak convective signals"},
    {L::High, -kInf, kInf, 0.0f, 2.0f, 0.0f, S::Any, T::Cirrus, "any other high cloud"},
};

bool signalHolds(ConvectiveSignal s, float capeJKg, float convPrecipMmH)
{
    const float cape = std::isfinite(capeJKg) ? capeJKg : 0.0f;
    const float conv = std::isfinite(convPrecipMmH) ? convPrecipMmH : 0.0f;
    switch (s)
    {
    case S::Any: return true;
    case S::Weak: return cape >= kWeakCapeJKg || conv >= kWeakConvPrecipMmH;
    case S::Strong: return cape >= kStrongCapeJKg || conv >= kStrongConvPrecipMmH;
    }
    return false;
}

std::string number(float v)
{
    if (std::isinf(v))
        return "";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", double(v));
    return buf;
}

}  // namespace

const std::vector<CloudTypeRule>& cloudTypeRules() { return kRules; }

CloudType classifyCloud(const CloudTypeInputs& in)
{
    if (!(in.coverage >= kMinCloudCoverage))
        return CloudType::None;
    const float precip = std::isfinite(in.precipMmH) ? in.precipMmH : 0.0f;
    for (const CloudTypeRule& r : kRules)
    {
        if (r.layer != in.layer)
            continue;
        const bool needsThickness = std::isfinite(r.minThicknessM) || std::isfinite(r.maxThicknessM);
        if (needsThickness && !(in.thicknessM >= r.minThicknessM && in.thicknessM < r.maxThicknessM))
            continue;
        if (!(in.coverage >= r.minCoverage && in.coverage < r.maxCoverage) || precip < r.minPrecipMmH)
            continue;
        if (!signalHolds(r.signal, in.capeJKg, in.convPrecipMmH))
            continue;
        return r.type;
    }
    return CloudType::None;
}

std::string cloudTypeRulesMarkdown()
{
    std::string s = "| # | layer | thickness (m) | coverage | precipitation (mm/h) | convective signal | type | why |\n"
                    "|---|---|---|---|---|---|---|---|\n";
    int i = 1;
    for (const CloudTypeRule& r : kRules)
    {
        std::string thick = std::isfinite(r.minThicknessM) ? ">= " + number(r.minThicknessM) : "";
        if (std::isfinite(r.maxThicknessM))
            thick += (thick.empty() ? "< " : ", < ") + number(r.maxThicknessM);
        std::string cover = r.minCoverage > 0 ? ">= " + number(r.minCoverage * 100) + " %" : "";
        if (r.maxCoverage <= 1)
            cover += (cover.empty() ? "< " : ", < ") + number(r.maxCoverage * 100) + " %";
        const char* signal = r.signal == S::Strong ? "strong" : r.signal == S::Weak ? "weak" : "";
        s += "| " + std::to_string(i++) + " | " + layerKindName(r.layer) + " | " + thick + " | " + cover + " | " +
             (r.minPrecipMmH > 0 ? ">= " + number(r.minPrecipMmH) : "") + " | " + signal + " | " +
             cloudTypeName(r.type) + " | " + r.why + " |\n";
    }
    return s;
}

const char* cloudTypeName(CloudType type)
{
    static const char* const kNames[] = {"None",         "Altocumulus", "Altostratus", "Cirrocumulus",
                                         "Cirrostratus", "Cirrus",      "Cumulonimbus", "Cumulus",
                                         "Nimbostratus", "Stratocumulus", "Stratus"};
    const auto i = size_t(type);
    return i < std::size(kNames) ? kNames[i] : "?";
}

const char* layerKindName(LayerKind layer)
{
    switch (layer)
    {
    case L::Low: return "low";
    case L::Middle: return "middle";
    case L::Convective: return "convective";
    case L::High: return "high";
    }
    return "?";
}

}  // namespace sky
