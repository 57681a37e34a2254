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
    uint64_t weatherVersion = 0; ///< the service's weather version (status weather.version); 0: not written
    std::string timeIso;         ///< the --time given, normalised
    std::string deviceName;
    std::string driver;
    std::string caption;         ///< what the view shows (showcase)
    nlohmann::json quality;      ///< the quality settings used
};

/// PREFIX.exr only when the result has the linear frame (ViewRequest::linearOutput). Also writes the
/// shadow map files (writeShadowMapFiles) and its metadata under "shadowMap" when the result has one.
bool writeRenderFiles(const std::string& prefix, const ViewRequest& request, const RenderResult& result,
                      const RenderFacts& facts, std::string& error);

/// Writes PREFIX-shadow.exr (float channels Y = transmittance and opticalDepth; the metadata JSON in the
/// string attribute "skyShadowMap") and PREFIX-shadow.png (grey, 8-bit linear transmittance: 255 = clear,
/// not sRGB-encoded). Writes nothing and succeeds when result.shadowMapSize is 0.
bool writeShadowMapFiles(const std::string& prefix, const RenderResult& result, std::string& error);

nlohmann::json qualityToJson(const QualitySettings& q);

}  // namespace sky
