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

FrameOutputs FrameOutputs::of(const ViewRequest& request)
{
    FrameOutputs o;
    o.linearImage = request.linearOutput;
    const uint32_t bits = request.readback;
    // Layers kept on the GPU for the export are drawn even when nothing is read back (sky-bench).
    o.sky = (bits & kDrawSky) != 0;
    o.cloudLayer = (bits & kDrawCloudLayer) != 0;
    o.depthLayer = (bits & kDrawDepthLayer) != 0;
    if (!request.copyToHost)
        return o;
    o.display = (bits & kReadDisplay) != 0;
    o.cloud = (bits & kReadCloud) != 0;
    o.depth = (bits & kReadDepth) != 0;
    o.readSky = (bits & kReadSky) != 0;
    o.readCloudLayer = (bits & kReadCloudLayer) != 0;
    o.readDepthLayer = (bits & kReadDepthLayer) != 0;
    o.sky = o.sky || o.readSky;
    o.cloudLayer = o.cloudLayer || o.readCloudLayer;
    o.depthLayer = o.depthLayer || o.readDepthLayer;
    o.shadowDetail = (bits & kReadShadowDetail) != 0;
    o.linear = request.linearOutput;
    return o;
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

void recordFrame(Renderer& r, FrameContext& frame, const ViewRequest& request, const CameraFrame& camera,
                 const SunMoon& sunMoon, const FrameInputs& in, const FrameParams& params, FrameReadbackPlan& plan,
                 RenderResult& facts)
{
    const bool reprojected = in.quality->reprojected;
    const FrameOutputs outputs = FrameOutputs::of(request);
    VkCommandBuffer cmd = frame.cmd;
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
    recordAtmosphere(r, cmd, camera, sunMoon, in);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsSkyView);
    recordLightVolume(r, cmd, params);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsLightVolume);
    const Image& marchCloud = reprojected ? r.reconstruct.freshCloudImage : r.march.cloudImage;
    const Image& marchDepth = reprojected ? r.reconstruct.freshDepthImage : r.march.depthImage;
    const Image& marchFront = !outputs.depthLayer ? r.composite.depthStandIn
                              : reprojected       ? r.reconstruct.freshFrontImage
                                                  : r.march.frontImage;
    recordMarch(r, frame, cmd, marchX, marchY, marchCloud, marchDepth, marchFront);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsClouds);
    // Reprojected: the cloud history the reconstruct pass writes this frame (which the next frame
    // reprojects) holds the pixels not marched this frame; the composite takes the marched ones from the
    // fresh images, and writes the full-resolution cloud image only when a reader asks for it.
    const uint32_t next = r.reconstruct.reprojection.current ^ 1u;
    if (reprojected)
        recordReconstruct(r, frame, cmd, request.width, request.height);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, frame.timestamps, kTsReconstruct);
    const bool writeCloud = reprojected && (outputs.cloud || outputs.depth);
    CompositeImages images;
    images.cloud = &marchCloud;
    images.depth = &marchDepth;
    images.history = reprojected ? &r.reconstruct.history[next] : &r.composite.historyStandIn;
    images.linear = outputs.linearImage ? &r.composite.linearImage : &r.composite.linearStandIn;
    images.sky = outputs.sky ? &r.composite.skyImage : &r.composite.linearStandIn;
    images.cloudLayer = outputs.cloudLayer ? &r.composite.cloudLayerImage : &r.composite.linearStandIn;
    images.cloudOut = writeCloud ? &r.march.cloudImage : &r.composite.linearStandIn;
    images.depthOut = writeCloud ? &r.march.depthImage : &r.composite.depthStandIn;
    images.front = &marchFront;
    images.frontHistory = outputs.depthLayer && reprojected ? &r.reconstruct.frontHistory[next] : &r.composite.depthStandIn;
    images.depthLayer = outputs.depthLayer ? &r.composite.depthLayerImage : &r.composite.depthLayerStandIn;
    recordComposite(r, cmd, request, images);
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
