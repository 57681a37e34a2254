// SPDX-License-Identifier: MIT
// Writes a RenderResult as PREFIX.png, PREFIX.exr and PREFIX.json (each atomically).
#pragma once

#include "skyservice/render/render_types.h"

#include <nlohmann/json.hpp>
#include <string>

namespace sky
{

/// Extra facts for the JSON sidecar (inputs, device, weather source).
struct RenderFacts
{
    std::string weatherSource;   ///< "builtin" or the snapshot path
    std::string timeIso;         ///< the --time given, normalised
    std::string deviceName;
    std::string driver;
    std::string caption;         ///< what the view shows (showcase)
    nlohmann::json quality;      ///< the quality settings used
};

bool writeRenderFiles(const std::string& prefix, const ViewRequest& request, const RenderResult& result,
                      const RenderFacts& facts, std::string& error);

nlohmann::json qualityToJson(const QualitySettings& q);

}  // namespace sky
