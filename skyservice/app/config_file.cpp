// SPDX-License-Identifier: MIT
#include "skyservice/app/config_file.h"

#include "skyservice/app/toml_file.h"
#include "skyservice/render/frame_setup.h"

#include <functional>
#include <map>

namespace sky
{
namespace
{

struct Key
{
    double lo, hi;
    std::function<void(QualitySettings&, double)> set;
    bool integer = false;
    bool boolean = false;
};

std::map<std::string, Key> keys()
{
    auto u32 = [](uint32_t QualitySettings::*field, double lo, double hi) {
        return Key{lo, hi, [field](QualitySettings& q, double v) { q.*field = uint32_t(v); }, true};
    };
    auto real = [](double QualitySettings::*field, double lo, double hi) {
        return Key{lo, hi, [field](QualitySettings& q, double v) { q.*field = v; }};
    };
    auto flag = [](bool QualitySettings::*field) {
        return Key{0, 1, [field](QualitySettings& q, double v) { q.*field = v != 0.0; }, false, true};
    };
    return {
        {"march.max_view_steps", u32(&QualitySettings::maxViewSteps, 8, 4096)},
        {"march.light_samples", u32(&QualitySettings::lightSamples, 1, 6)},
        {"march.accumulation_frames", u32(&QualitySettings::accumulationFrames, 1, 64)},
        {"march.max_distance_m", real(&QualitySettings::maxDistanceM, 1000, 2000000)},
        {"march.reprojected", flag(&QualitySettings::reprojected)},
        {"lighting.octaves", u32(&QualitySettings::octaves, 1, 8)},
        {"lighting.octave_attenuation", real(&QualitySettings::octaveAttenuation, 0, 1)},
        {"lighting.octave_contribution", real(&QualitySettings::octaveContribution, 0, 1)},
        {"lighting.octave_eccentricity", real(&QualitySettings::octaveEccentricity, 0, 1)},
        {"lighting.powder_strength", real(&QualitySettings::powderStrength, 0, 1)},
        {"lighting.phase_forward_g", real(&QualitySettings::phaseForwardG, 0, 0.99)},
        {"lighting.phase_back_g", real(&QualitySettings::phaseBackG, -0.99, 0)},
        {"lighting.phase_forward_weight", real(&QualitySettings::phaseForwardWeight, 0, 1)},
        {"lighting.cone_step_m", real(&QualitySettings::coneStepM, 1, 2000)},
        {"lighting.full_cone_samples", u32(&QualitySettings::fullConeSamples, 0, 6)},
        {"lighting.light_volume_texel_m", real(&QualitySettings::lightVolumeTexelM, 0, 5000)},
        {"lighting.light_volume_min_rays", u32(&QualitySettings::lightVolumeMinRays, 0, 4294967295.0)},
        {"lighting.ambient_strength", real(&QualitySettings::ambientStrength, 0, 10)},
        {"shape.extinction_per_m", real(&QualitySettings::extinctionPerM, 1e-4, 1)},
        {"shape.detail_erosion", real(&QualitySettings::detailErosion, 0, 1)},
        {"shape.detail", flag(&QualitySettings::detail)},
        {"shape.high_cloud", flag(&QualitySettings::highCloud)},
        {"noise.seed", u32(&QualitySettings::noiseSeed, 0, 4294967295.0)},
        {"noise.base_period_m", real(&QualitySettings::baseNoisePeriodM, 100, 100000)},
        {"noise.detail_period_m", real(&QualitySettings::detailNoisePeriodM, 10, 100000)},
        {"noise.curl_period_m", real(&QualitySettings::curlNoisePeriodM, 10, 100000)},
        {"noise.high_period_m", real(&QualitySettings::highNoisePeriodM, 100, 1000000)},
        {"window.half_extent_m", real(&QualitySettings::windowHalfExtentM, 10000, 3000000)},
        {"window.warp_radius_m", real(&QualitySettings::windowWarpRadiusM, 0, 3000000)},
    };
}

// Keys of earlier versions that now belong to the experiments (skyservice/render/render_tuning.h): a
// file that still sets one is refused like an unknown key, with the reason, so that nobody believes a
// setting took effect.
const std::map<std::string, const char*>& removedKeys()
{
    static const std::map<std::string, const char*> removed = {
        {"march.empty_space_skipping", "--no-skipping"},
        {"march.cost_ordered_rows", "--no-cost-order"},
        {"lighting.cone_tail_reuse_m", "--cone-tail-reuse"},
        {"lighting.cone_tail_reuse_beyond_m", "--cone-tail-reuse-beyond"},
        {"lighting.deep_light_reuse_m", "--deep-light-reuse"},
        {"lighting.cone_near_merge_beyond_m", "--cone-near-merge-beyond"},
        {"march.max_step_optical_depth", "--max-step-optical-depth"},
        {"march.deep_step_factor", "--deep-step-factor"},
        {"march.inside_cloud_block_px", "--inside-cloud-block"},
        {"shape.detail_min_transmittance", "--detail-min-transmittance"},
    };
    return removed;
}

}  // namespace

bool applyConfigFile(const std::string& path, QualitySettings& quality, std::string& error)
{
    toml::table table;
    if (!parseTomlFile(path, table, error))
        return false;
    QualitySettings q = quality;
    const std::map<std::string, Key> known = keys();
    std::string bad;
    table.for_each([&](const toml::key& section, auto&& node) {
        // [service] and [cigi] belong to the daemon (skyservice/service/service_config.h), read from the same file.
        if (!bad.empty() || section.str() == "service" || section.str() == "cigi")
            return;
        if constexpr (!toml::is_table<decltype(node)>)
        {
            bad = path + ": '" + std::string(section.str()) + "' must be a section such as [march]";
        }
        else
        {
            node.for_each([&](const toml::key& name, auto&& value) {
                if (!bad.empty())
                    return;
                std::string full = std::string(section.str()) + "." + std::string(name.str());
                auto it = known.find(full);
                if (auto removed = removedKeys().find(full); removed != removedKeys().end())
                {
                    bad = path + ": key '" + full + "' was removed: it is an experiment's knob, not a setting " +
                          "(sky-bench " + removed->second + " sets it for measurements)";
                    return;
                }
                if (it == known.end())
                {
                    bad = path + ": unknown key '" + full + "' (config/default.toml lists every key)";
                    return;
                }
                const Key& k = it->second;
                double v = 0;
                if constexpr (toml::is_boolean<decltype(value)>)
                {
                    if (!k.boolean)
                    {
                        bad = path + ": '" + full + "' must be a number";
                        return;
                    }
                    v = value.get() ? 1.0 : 0.0;
                }
                else if constexpr (toml::is_number<decltype(value)>)
                {
                    v = double(value.get());
                    if (k.boolean || (k.integer && v != double(int64_t(v))))
                    {
                        bad = path + ": '" + full + "' must be " + (k.boolean ? "true or false" : "an integer");
                        return;
                    }
                }
                else
                {
                    bad = path + ": '" + full + "' must be " + (k.boolean ? "true or false" : "a number");
                    return;
                }
                if (!(v >= k.lo && v <= k.hi))
                {
                    bad = path + ": '" + full + "' = " + std::to_string(v) + " is outside [" + std::to_string(k.lo) +
                          ", " + std::to_string(k.hi) + "]";
                    return;
                }
                k.set(q, v);
            });
        }
    });
    if (!bad.empty())
    {
        error = bad;
        return false;
    }
    if (!validateNoisePeriods(q, error))
    {
        error = path + ": " + error;
        return false;
    }
    quality = q;
    return true;
}

}  // namespace sky
