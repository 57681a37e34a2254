// SPDX-License-Identifier: MIT
// Reading one TOML file, shared by the renderer's config (config_file.cpp) and the daemon's
// (skyservice/service/service_config.cpp), which may be the same file.
#pragma once

#include <toml++/toml.h>

#include <string>

namespace sky
{

/// Parses `path` into `out`. On failure `error` is "PATH:LINE:COLUMN: what toml++ says" and `out` is
/// untouched.
bool parseTomlFile(const std::string& path, toml::table& out, std::string& error);

}  // namespace sky
