// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_recording.h"

#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/render/light_volume.h"

#include <cstring>

namespace sky
{
namespace
{

template <typename T>
void copyRegion(const FrameContext& frame, const ReadbackRegion& region, std::vector<T>& out)
{
    out.resize(size_t(region.bytes) / sizeof(T));
    if (region.bytes > 0)
        std::memcpy(out.data(), static_cast<const uint8_t*>(frame.readback.mapped) + region.offset, region.bytes);
}

}  // namespace

SkyStatus prepareFrameImages(Renderer& r, const ViewRequest& request, const QualitySettings& quality,
                             const FrameOutputs& outputs)
{
    // The newest frame submitted is the last that can use an image let go now; its context's fence is
    // waited for before the context is used again, which is after every older frame too. Collected:
    // frames are collected in order, so none is in flight.
    FrameContext& newest = recording(r);
    ImageChanges changes{r.ctx, r.memory, newest.submitted ? &newest.deletions : nullptr, r.newImages};
    const bool reprojected = quality.reprojected;
    SKY_TRY(ensureCompositeImages(r.composite, changes, request.width, request.height, outputs));
    MarchImageNeeds march;
    march.width = request.width;
    march.height = request.height;
    march.fullResolutionCloud = !reprojected || outputs.cloud || outputs.depth;
    march.fullResolutionFront = outputs.depthLayer && !reprojected;
    march.blockPx = reprojected ? r.reconstruct.reprojection.block.blockPx : 0u;
    march.freshFront = outputs.depthLayer;
    SKY_TRY(ensureMarchImages(r.march, changes, march));
    if (reprojected)
        SKY_TRY(ensureReconstructImages(r.reconstruct, changes, request.width, request.height, outputs.depthLayer));
    if (request.shadowMap)
        SKY_TRY(ensureShadowMapImages(r.shadowPass, changes, request.shadowMapSize));
    return SkyStatus::success();
}

VkDeviceSize frameReadbackBytes(const Renderer& r, const ViewRequest& request)
{
    const FrameOutputs o = FrameOutputs::of(request);
    VkDeviceSize bytes = 0;
    const std::pair<bool, const Image*> images[] = {
        {o.display, &r.composite.displayImage}, {o.cloud, &r.march.cloudImage},      {o.depth, &r.march.depthImage},
        {o.linear, &r.composite.linearImage},   {o.readSky, &r.composite.skyImage},
        {o.readCloudLayer, &r.composite.cloudLayerImage}, {o.readDepthLayer, &r.composite.depthLayerImage},
        {request.shadowMap && request.copyToHost, &r.shadowPass.transmittance},
        {request.shadowMap && o.shadowDetail, &r.shadowPass.image},
    };
    for (const auto& [wanted, image] : images)
        if (wanted)
            bytes += readbackBytes(*image);
    return bytes;
}

PassFrame passFrame(const Renderer& r, const FrameContext& frame)
{
    return PassFrame{r.ctx, frame.cmd, frame.frameUniforms, frame.atmosphereUniforms, r.samplers};
}

CompositeInputs compositeInputs(const Renderer& r, const FrameOutputs& outputs, bool reprojected)
{
    const StandInImages& standIn = r.standIns;
    const MarchPass& march = r.march;
    const ReconstructPass& reconstruct = r.reconstruct;
    // Reprojected: the cloud history the reconstruct pass writes this frame (which the next frame
    // reprojects) holds the pixels not marched this frame; the composite takes the marched ones from the
    // fresh images, and writes the full-resolution cloud image only when a reader asks for it.
    const uint32_t next = reconstruct.reprojection.current ^ 1u;
    const bool writeCloud = reprojected && (outputs.cloud || outputs.depth);
    const Image& front = !outputs.depthLayer ? standIn.depth : reprojected ? march.freshFrontImage : march.frontImage;
    return CompositeInputs{
        .atmosphere = r.atmosphere,
        .cloud = reprojected ? march.freshCloudImage : march.cloudImage,
        .depth = reprojected ? march.freshDepthImage : march.depthImage,
        .history = reprojected ? reconstruct.history[next] : standIn.history,
        .front = front,
        .frontHistory = outputs.depthLayer && reprojected ? reconstruct.frontHistory[next] : standIn.depth,
        .cloudOut = writeCloud ? march.cloudImage : standIn.linear,
        .depthOut = writeCloud ? march.depthImage : standIn.depth,
        .standIns = standIn,
        .outputs = outputs,
    };
}

void recordFrame(Renderer& r, FrameContext& frame, const ViewRequest& request, const CameraFrame& camera,
                 const SunMoon& sunMoon, const FrameInputs& in, const FrameParams& params, FrameReadbackPlan& plan,
                 RenderResult& facts)
{
    const bool reprojected = in.quality->reprojected;
    const FrameOutputs outputs = FrameOutputs::of(request);
    const PassFrame f = passFrame(r, frame);
    VkCommandBuffer cmd = frame.cmd;
    recordNewImages(cmd, r.newImages);
    vkCmdResetQueryPool(cmd, frame.timestamps, 0, kTsCount);
    // Reprojected: one invocation per block (4x4, or finer near clouds) into the fresh images.
    const uint32_t block = reprojected ? r.reconstruct.reprojection.block.blockPx : 1u;
    // And, beside the blocks of each block row (below those of each block column), one invocation per
    // pixel of the columns (rows) the previous frame did not see (reprojection.h NewLines): B per line.
    const NewLines none, &lines = reprojected ? r.reconstruct.reprojection.newLines : none;
    const uint32_t marchX = (request.width + block - 1) / block + lines.columns.count * block;
    const uint32_t marchY = (request.height + block - 1) / block + lines.rows.count * block;
    // The order of the march's workgroup rows (march_order.h), uploaded first: its barrier then waits
    // for nothing.
    const uint32_t marchGroupRows = (marchY + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D;
    facts.marchRowOrder = prepareMarchOrder(r.march.order, cmd, marchGroupRows, r.march.dispatchRanges,
                                            r.tuning.costOrderedMarch);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, frame.timestamps, kTsStart);

    recordAtmosphere(f, r.atmosphere, camera, sunMoon, in);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsSkyView);

    const RendererWeather& weather = r.weather;
    const WindowKey noWindow;
    recordLightVolume(f, r.lightVolume,
                      LightVolumeInputs{weather.windowImage, weather.window ? weather.window->key : noWindow, r.noise},
                      params);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsLightVolume);

    const CompositeInputs composite = compositeInputs(r, outputs, reprojected);
    const MarchInputs marchIn{weather.windowImage,  weather.columnBoundsImage, r.noise,
                              r.atmosphere.transmittanceLut, r.lightVolume.image, r.lightVolume.farImage};
    recordMarch(f, r.march, marchIn, MarchTargets{composite.cloud, composite.depth, composite.front}, marchX, marchY);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsClouds);

    if (reprojected)
    {
        const ReconstructInputs fresh{r.march.freshCloudImage, r.march.freshDepthImage,
                                      outputs.depthLayer ? &r.march.freshFrontImage : nullptr, r.standIns.depth};
        recordReconstruct(f, r.reconstruct, fresh, request.width, request.height);
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsReconstruct);

    recordComposite(f, r.composite, composite, request.width, request.height);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsComposite);
    recordMarchLookupsReadback(r.march.order, cmd);

    plan = FrameReadbackPlan{};
    if (outputs.display)
        plan.display = addImageReadback(frame, r.composite.displayImage);
    if (outputs.cloud)
        plan.cloud = addImageReadback(frame, r.march.cloudImage);
    if (outputs.depth)
        plan.depth = addImageReadback(frame, r.march.depthImage);
    if (outputs.linear)
        plan.linear = addImageReadback(frame, r.composite.linearImage);
    if (outputs.readSky)
        plan.sky = addImageReadback(frame, r.composite.skyImage);
    if (outputs.readCloudLayer)
        plan.cloudLayer = addImageReadback(frame, r.composite.cloudLayerImage);
    if (outputs.readDepthLayer)
        plan.depthLayer = addImageReadback(frame, r.composite.depthLayerImage);
}

void recordFrameShadowMap(Renderer& r, FrameContext& frame, const ViewRequest& request, const QualitySettings& quality,
                          const CameraFrame& camera, const SunMoon& sunMoon, ShadowMapReadback& readback,
                          RenderResult& facts)
{
    const RendererWeather& weather = r.weather;
    const ShadowMapInputs in{weather.windowImage, r.noise,          weather.window.get(),
                             weather.version,     weather.snapshot->validTimeUnixS, r.tuning};
    recordShadowMap(passFrame(r, frame), frame, r.shadowPass, in, request, quality, camera, sunMoon, readback, facts);
}

void collectFrame(Renderer& r, const FrameContext& frame, const ViewRequest& request, bool reprojected,
                  bool lightVolume, const FrameReadbackPlan& plan, RenderResult& result)
{
    const uint32_t block = reprojected ? r.reconstruct.reprojection.block.blockPx : 1u;
    const uint32_t marchY = (request.height + block - 1) / block;
    result.marchRowLookups = collectMarchLookups(r.march.order, (marchY + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D);
    uint64_t ts[kTsShadowBegin] = {};
    if (r.ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(r.ctx.device, frame.timestamps, 0, kTsShadowBegin, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
    {
        auto ms = [&](uint32_t a, uint32_t b) { return double(ts[b] - ts[a]) * r.ctx.timestampPeriodNs * 1e-6; };
        result.gpuMs["sky"] = ms(kTsStart, kTsSkyView);
        // Part of the march (and of "clouds" in full mode), shown on its own as well.
        if (lightVolume)
            result.gpuMs["lightVolume"] = ms(kTsSkyView, kTsLightVolume);
        if (reprojected)
        {
            result.gpuMs["march"] = ms(kTsSkyView, kTsClouds);
            result.gpuMs["reconstruct"] = ms(kTsClouds, kTsReconstruct);
        }
        else
            result.gpuMs["clouds"] = ms(kTsSkyView, kTsClouds);
        result.gpuMs["composite"] = ms(kTsReconstruct, kTsComposite);
        result.gpuMs["total"] = ms(kTsStart, kTsComposite);
    }
    copyRegion(frame, plan.display, result.displayRgba8);
    copyRegion(frame, plan.cloud, result.cloudRgbaHalf);
    copyRegion(frame, plan.depth, result.cloudDepthM);
    copyRegion(frame, plan.linear, result.linearRgbaHalf);
    copyRegion(frame, plan.sky, result.skyRgbaHalf);
    copyRegion(frame, plan.cloudLayer, result.cloudLayerRgbaHalf);
    copyRegion(frame, plan.depthLayer, result.depthLayerM);
}

}  // namespace sky
