// SPDX-License-Identifier: MIT
// `--config FILE`: a TOML file that overrides QualitySettings (config/default.toml documents every key).
#pragma once

#include "skyservice/render/render_types.h"

#include <string>

namespace sky
{

/// Reads `path` and overrides the keys it sets in `quality`. Unknown keys, wrong types and values out
/// of range are refused with a message naming the file, the key and the allowed range; `quality` is
/// then unchanged.
bool applyConfigFile(const std::string& path, QualitySettings& quality, std::string& error);

}  // namespace sky
