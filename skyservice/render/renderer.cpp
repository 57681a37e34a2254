// SPDX-License-Identifier: MIT
#include "skyservice/render/renderer.h"

#include <algorithm>

namespace sky
{

SkyStatus createRenderer(Renderer& r, const RendererOptions& options)
{
    SKY_TRY(createContext(r.ctx, options.context));
    SKY_TRY(createSamplers(r.ctx, r.samplers));

    for (uint32_t i = 0; i < kFramesInFlight; ++i)
        SKY_TRY(createFrameContext(r.ctx, r.memory, r.frames[i], i));

    SKY_TRY(createMarchPass(r.ctx, r.memory, r.march));
    SKY_TRY(createReconstructPass(r.ctx, r.reconstruct));
    SKY_TRY(createCompositePass(r.ctx, r.composite));
    SKY_TRY(createStandInImages(r.ctx, r.memory, r.standIns));
    SKY_TRY(createShadowMapPass(r.ctx, r.shadowPass));

    SKY_TRY(createWeatherImages(r.ctx, r.memory, r.weather));

    SKY_TRY(createAtmospherePass(r.ctx, r.memory, r.atmosphere));
    SKY_TRY(createLightVolumePass(r.ctx, r.memory, r.lightVolume));
    return createNoiseTextures(r.ctx, r.memory, r.noise, options.noiseSeed, recording(r).timestamps);
}

void destroyRenderer(Renderer& r)
{
    if (!r.ctx.device)
    {
        destroyContext(r.ctx);
        return;
    }
    vkDeviceWaitIdle(r.ctx.device);  // shutdown only
    for (FrameContext& frame : r.frames)
        destroyFrameContext(r.ctx, r.memory, frame);
    destroyWeatherImages(r.ctx, r.memory, r.weather);
    destroyNoiseTextures(r.ctx, r.memory, r.noise);
    destroyAtmospherePass(r.ctx, r.memory, r.atmosphere);
    destroyLightVolumePass(r.ctx, r.memory, r.lightVolume);
    destroyMarchPass(r.ctx, r.memory, r.march);
    destroyReconstructPass(r.ctx, r.memory, r.reconstruct);
    destroyCompositePass(r.ctx, r.memory, r.composite);
    destroyStandInImages(r.ctx, r.memory, r.standIns);
    destroyShadowMapPass(r.ctx, r.memory, r.shadowPass);
    destroySamplers(r.ctx, r.samplers);
    destroyContext(r.ctx);
}

namespace
{

/// `version`, or one newer than any given so far (kNewWeatherVersion).
uint64_t takeVersion(RendererWeather& w, uint64_t version)
{
    if (version == kNewWeatherVersion)
        version = w.newestVersion + 1;
    w.newestVersion = std::max(w.newestVersion, version);
    return version;
}

}  // namespace

void setWeather(Renderer& r, const WeatherSnapshot& snapshot, uint64_t version)
{
    r.weather.snapshot = std::make_shared<const WeatherSnapshot>(snapshot);
    r.weather.version = takeVersion(r.weather, version);
    cancelStage(r.weather.stage);  // older than this one
    dropHistory(r);  // the previous frame shows other clouds
}

uint64_t stageWeather(Renderer& r, WeatherMaker make, StageSwap swap, StageHistory history, uint64_t version)
{
    version = takeVersion(r.weather, version);
    stage(r.weather.stage, version, std::move(make), swap, history);
    return version;
}

uint64_t stageWeather(Renderer& r, std::shared_ptr<const WeatherSnapshot> snapshot, StageSwap swap,
                      StageHistory history, uint64_t version)
{
    return stageWeather(r, [snapshot = std::move(snapshot)] { return snapshot; }, swap, history, version);
}

void releaseStagedWeather(Renderer& r) { releaseStage(r.weather.stage); }

void cancelStagedWeather(Renderer& r) { cancelStage(r.weather.stage); }

bool weatherStagePending(const Renderer& r) { return stagePending(r.weather.stage); }

void dropHistory(Renderer& r)
{
    r.reconstruct.reprojection.valid = false;
    ++r.reconstruct.reprojection.drops;
}

const std::string& lastHistoryDropReason(const Renderer& r) { return r.reconstruct.reprojection.lastDropReason; }

}  // namespace sky
