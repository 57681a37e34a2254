// SPDX-License-Identifier: MIT
// libFuzzer target: the daemon's config reader must take any file to a config or an error naming the
// file, never crash; what it accepts must leave a config the cross-field check can judge.
#include "skyservice/app/commands.h"
#include "skyservice/app/config_file.h"
#include "skyservice/service/service_config.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace sky
{
// render_command.cpp's preset table needs the renderer; the fuzzer needs only the config file's part,
// which is the real applyConfigFile.
bool qualityFromOptions(const CommonRenderOptions& o, QualitySettings& q, std::string& error)
{
    q = QualitySettings{};
    return o.config.empty() || applyConfigFile(o.config, q, error);
}
}  // namespace sky

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    static const std::string path = "/tmp/sky-fuzz-config-" + std::to_string(getpid()) + ".toml";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f)
        return 0;
    if (size > 0)
        std::fwrite(data, 1, size, f);
    std::fclose(f);
    sky::ServiceConfig config = sky::defaultServiceConfig();
    config.socketPath = "/tmp/x.sock";
    std::string error;
    if (!sky::loadServiceConfig(path, config, error))
    {
        if (error.find(path) == std::string::npos)
            std::abort();  // a refusal names the file
        return 0;
    }
    (void)sky::checkServiceConfig(config, path, error);
    return 0;
}
