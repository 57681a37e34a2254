// SPDX-License-Identifier: MIT
#include "skyservice/app/commands.h"

#include "skyservice/app/config_file.h"
#include "skyservice/app/render_files.h"
#include "skyservice/app/weather_source.h"
#include "skyservice/render/reference_renderer.h"
#include "skyservice/render/renderer.h"
#include "skyservice/render/view_validation.h"
#include "skyservice/sky/ephemeris.h"

#include <CLI/CLI.hpp>
#include <cstdio>

namespace sky
{

void addCommonOptions(CLI::App& app, CommonRenderOptions& o)
{
    app.add_option("--device", o.device, "Vulkan device: index or part of its name (default: best GPU, else CPU)");
    app.add_flag("--validate", o.validate, "Enable the Vulkan validation layers");
    app.add_option("--quality", o.quality, "Preset: high | medium | test")->check(CLI::IsMember({"high", "medium", "test"}));
    app.add_option("--seed", o.seed, "Noise seed (same seed, same clouds)");
    app.add_option("--steps", o.steps, "Maximum view samples per ray (overrides the preset)")->check(CLI::Range(8, 4096));
    app.add_option("--config", o.config, "TOML file overriding the model settings (see config/default.toml)");
    app.add_option("--accumulate", o.accumulate, "Frames averaged per picture, each with new jitter (overrides the preset)")
        ->check(CLI::Range(1, 64));
}

void addShadowMapOptions(CLI::App& app, ViewRequest& request)
{
    app.add_flag("--shadow-map", request.shadowMap,
                 "Also write the cloud shadow map: PREFIX-shadow.exr, PREFIX-shadow.png, \"shadowMap\" in PREFIX.json");
    app.add_option("--shadow-size", request.shadowMapSize, "Shadow map texels per side (default 1024)")
        ->check(CLI::Range(8, 8192));
    app.add_option("--shadow-extent", request.shadowMapExtentM,
                   "Shadow map edge length on the ground (metres, default 150000)")
        ->check(CLI::Range(100.0, 1600000.0));
}

bool qualityFromOptions(const CommonRenderOptions& o, QualitySettings& q, std::string& error)
{
    q = QualitySettings{};
    if (o.quality == "medium")
    {
        q.maxViewSteps = 96;
        q.lightSamples = 5;
    }
    else if (o.quality == "test")
    {
        // Small and fast for lavapipe tests: fewer samples, same model.
        q.maxViewSteps = 64;
        q.lightSamples = 4;
        q.octaves = 2;
    }
    else if (o.quality != "high")
    {
        error = "--quality " + o.quality + ": expected high, medium or test";
        return false;
    }
    if (o.quality == "high")
        q.accumulationFrames = 4;
    if (!o.config.empty() && !applyConfigFile(o.config, q, error))
        return false;
    if (o.steps > 0)
        q.maxViewSteps = uint32_t(o.steps);
    if (o.accumulate > 0)
        q.accumulationFrames = uint32_t(o.accumulate);
    if (o.seed)
        q.noiseSeed = *o.seed;
    return true;
}

bool startRenderer(const CommonRenderOptions& o, uint32_t noiseSeed, Renderer& renderer, const char* command)
{
    RendererOptions ro;
    ro.context.deviceSelector = o.device;
    ro.context.validation = o.validate;
    ro.noiseSeed = noiseSeed;
    SkyStatus status = createRenderer(renderer, ro);
    if (status.ok())
        return true;
    std::fprintf(stderr, "skyservice %s: %s\n", command, status.message.c_str());
    destroyRenderer(renderer);
    return false;
}

namespace
{

// The request's time, the view and the quality from the command line; kExitOk, or kExitUsage with the
// message printed. All of it is refused before the device starts.
int readRenderRequest(const RenderCommandOptions& options, ViewRequest& request, QualitySettings& quality)
{
    std::string error;
    if (!parseIso8601Utc(options.time, request.unixTimeS, error))
    {
        std::fprintf(stderr, "skyservice render: --time %s: %s\n", options.time.c_str(), error.c_str());
        return kExitUsage;
    }
    if (!validateView(request, error))  // refused before the device starts, as a usage error
    {
        std::fprintf(stderr, "skyservice render: %s\n", error.c_str());
        return kExitUsage;
    }
    if (!qualityFromOptions(options.common, quality, error))
    {
        std::fprintf(stderr, "skyservice render: %s\n", error.c_str());
        return kExitUsage;
    }
    if (options.noDetail)
        quality.detail = false;
    if (options.noHighCloud)
        quality.highCloud = false;
    return kExitOk;
}

ReferenceSettings referenceSettingsOf(const RenderCommandOptions& options)
{
    ReferenceSettings referenceSettings;
    referenceSettings.samplesPerPixel = options.referenceSpp;
    referenceSettings.phase = options.referencePhase == "mie" ? ReferencePhase::HgDraine : ReferencePhase::Model;
    referenceSettings.dropletDiameterUm = options.dropletDiameterUm;
    return referenceSettings;
}

// The JSON sidecar's facts; with --reference, the path tracer's settings and counters under
// quality.reference.
RenderFacts renderFactsOf(const Renderer& renderer, const ReferenceRenderer& reference,
                          const RenderCommandOptions& options, const ViewRequest& request,
                          const QualitySettings& quality, const ReferenceSettings& referenceSettings)
{
    RenderFacts facts;
    facts.weatherSource = options.weather;
    facts.timeIso = formatIso8601Utc(request.unixTimeS);
    facts.deviceName = renderer.ctx.deviceName;
    facts.driver = renderer.ctx.driverInfo;
    facts.quality = qualityToJson(quality);
    if (options.reference)
        facts.quality["reference"] = {
            {"samplesPerPixel", referenceSettings.samplesPerPixel},
            {"phase", options.referencePhase},
            {"dropletDiameterUm", referenceSettings.dropletDiameterUm},
            {"maxScatteringEvents", referenceSettings.maxEvents},
            {"pathsTruncated", reference.last.pathsTruncated},
            {"majorantExceeded", reference.last.majorantExceeded},
            {"pathsCut", reference.last.pathsCut},
            {"paths", reference.last.paths},
            {"steps", reference.last.steps},
            {"stretchesSkipped", reference.last.stretchesSkipped},
            {"dispatches", reference.last.dispatches},
            {"maxDispatches", reference.last.maxDispatches},
            {"seconds", reference.last.seconds}};
    return facts;
}

// Writes PREFIX.png/.exr/.json (and the shadow map's files) and says what it wrote; the exit code.
int writeRenderOutputs(const RenderCommandOptions& options, const ViewRequest& request, const RenderResult& result,
                       const RenderFacts& facts)
{
    std::string error;
    if (!writeRenderFiles(options.out, request, result, facts, error))
    {
        std::fprintf(stderr, "skyservice render: %s\n", error.c_str());
        return kExitRuntime;
    }
    const char* timing = options.reference ? "reference" : "total";
    std::printf("wrote %s.png %s.exr %s.json (%s %.1f ms)\n", options.out.c_str(), options.out.c_str(),
                options.out.c_str(), options.reference ? "path tracing" : "GPU",
                result.gpuMs.count(timing) ? result.gpuMs.at(timing) : 0.0);
    if (result.shadowMapSize > 0)
        std::printf("wrote %s-shadow.exr %s-shadow.png (GPU %.1f ms)\n", options.out.c_str(),
                    options.out.c_str(), result.gpuMs.count("shadowMap") ? result.gpuMs.at("shadowMap") : 0.0);
    return kExitOk;
}

}  // namespace

int runRenderCommand(const RenderCommandOptions& options)
{
    ViewRequest request = options.request;
    QualitySettings quality;
    if (const int code = readRenderRequest(options, request, quality); code != kExitOk)
        return code;

    WeatherSnapshot weather;
    std::string error;
    if (!loadWeatherSource(options.weather, request.unixTimeS, weather, error))
    {
        std::fprintf(stderr, "skyservice render: --weather %s: %s\n", options.weather.c_str(), error.c_str());
        return kExitWeather;
    }

    Renderer renderer;
    if (!startRenderer(options.common, quality.noiseSeed, renderer, "render"))
        return kExitRuntime;
    setWeather(renderer, weather);
    RenderResult result;
    ReferenceRenderer reference;
    const ReferenceSettings referenceSettings = referenceSettingsOf(options);
    SkyStatus status = options.reference ? createReferenceRenderer(renderer, reference) : SkyStatus::success();
    if (status.ok())
        status = options.reference
                     ? renderReference(renderer, reference, request, quality, referenceSettings, result)
                     : renderView(renderer, request, quality, result);
    int code = kExitOk;
    if (!status.ok())
    {
        std::fprintf(stderr, "skyservice render: %s\n", status.message.c_str());
        code = status.result == VK_ERROR_INITIALIZATION_FAILED ? kExitUsage : kExitRuntime;
    }
    else
        code = writeRenderOutputs(options, request, result,
                                  renderFactsOf(renderer, reference, options, request, quality, referenceSettings));
    if (options.common.validate && renderer.ctx.validationMessages.load() > 0)
    {
        std::fprintf(stderr, "skyservice render: %u validation messages\n", renderer.ctx.validationMessages.load());
        code = kExitRuntime;
    }
    if (options.reference)
        destroyReferenceRenderer(renderer, reference);
    destroyRenderer(renderer);
    return code;
}

}  // namespace sky
