// SPDX-License-Identifier: MIT
#include "skyservice/app/toml_file.h"

namespace sky
{

bool parseTomlFile(const std::string& path, toml::table& out, std::string& error)
{
    try
    {
        out = toml::parse_file(path);
        return true;
    }
    catch (const toml::parse_error& e)
    {
        const auto& where = e.source().begin;
        error = path + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": " +
                std::string(e.description());
        return false;
    }
}

}  // namespace sky
