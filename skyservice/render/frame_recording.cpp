// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_recording.h"

#include "skyservice/render/atmosphere_passes.h"

#include <cstring>

namespace sky
{

SkyStatus renderOnce(Renderer& r, const ViewRequest& request, const CameraFrame& camera, const SunMoon& sunMoon,
                     const FrameInputs& in, RenderResult& result)
{
    const bool reprojected = in.quality->reprojected;
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    VkCommandBuffer cmd = shot.cmd;
    vkCmdResetQueryPool(cmd, r.timestamps, 0, kTsCount);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r.timestamps, kTsStart);
    recordAtmosphere(r, cmd, camera, sunMoon, in);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsSkyView);
    // Reprojected: one invocation per block (4x4, or finer near clouds) into the fresh images.
    const uint32_t block = reprojected ? r.reprojection.block.blockPx : 1u;
    uint32_t marchX = (request.width + block - 1) / block;
    uint32_t marchY = (request.height + block - 1) / block;
    const Image& marchCloud = reprojected ? r.freshCloudImage : r.cloudImage;
    const Image& marchDepth = reprojected ? r.freshDepthImage : r.depthImage;
    dispatch(r.ctx, cmd, r.cloudProgram, marchX, marchY, 1, nullptr, 0,
             {DescriptorInfo(r.frameUniforms), DescriptorInfo(r.atmosphereUniforms),
              DescriptorInfo(r.weatherWindowImage, r.linearClamp), DescriptorInfo(r.baseNoise, r.linearRepeat),
              DescriptorInfo(r.detailNoise, r.linearRepeat), DescriptorInfo(r.curlNoise, r.linearRepeat),
              DescriptorInfo(r.blueNoise, r.nearestRepeat), DescriptorInfo(r.transmittanceLut, r.linearClamp),
              DescriptorInfo(marchCloud), DescriptorInfo(marchDepth)});
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsClouds);
    // The frame's cloud image: the march's output at full resolution, or the history image the
    // reconstruct pass writes this frame (which the next frame reprojects).
    const uint32_t next = r.reprojection.current ^ 1u;
    const Image& frameCloud = reprojected ? r.historyCloud[next] : r.cloudImage;
    const Image& frameDepth = reprojected ? r.historyDepth[next] : r.depthImage;
    if (reprojected)
    {
        const uint32_t prev = r.reprojection.current;
        dispatch(r.ctx, cmd, r.reconstructProgram, request.width, request.height, 1, nullptr, 0,
                 {DescriptorInfo(r.frameUniforms), DescriptorInfo(r.freshCloudImage), DescriptorInfo(r.freshDepthImage),
                  DescriptorInfo(r.historyCloud[prev]), DescriptorInfo(r.historyDepth[prev]),
                  DescriptorInfo(frameCloud), DescriptorInfo(frameDepth)});
        computeBarrier(cmd);
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsReconstruct);
    recordComposite(r, cmd, request, frameCloud, frameDepth);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsComposite);
    SKY_TRY(endOneShot(r.ctx, shot));

    uint64_t ts[kTsCount] = {};
    if (r.ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(r.ctx.device, r.timestamps, 0, kTsCount, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
    {
        auto ms = [&](uint32_t a, uint32_t b) { return double(ts[b] - ts[a]) * r.ctx.timestampPeriodNs * 1e-6; };
        result.gpuMs["sky"] = ms(kTsStart, kTsSkyView);
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
    if (!in.quality->readback)
        return SkyStatus::success();  // timing runs: the GPU work is done, nothing to copy
    std::vector<uint8_t> bytes;
    SKY_TRY(readbackImage(r.ctx, r.memory, frameCloud, bytes));
    result.cloudRgbaHalf.resize(bytes.size() / 2);
    std::memcpy(result.cloudRgbaHalf.data(), bytes.data(), bytes.size());
    SKY_TRY(readbackImage(r.ctx, r.memory, frameDepth, bytes));
    result.cloudDepthM.resize(bytes.size() / 4);
    std::memcpy(result.cloudDepthM.data(), bytes.data(), bytes.size());
    SKY_TRY(readbackImage(r.ctx, r.memory, r.linearImage, bytes));
    result.linearRgbaHalf.resize(bytes.size() / 2);
    std::memcpy(result.linearRgbaHalf.data(), bytes.data(), bytes.size());
    return readbackImage(r.ctx, r.memory, r.displayImage, result.displayRgba8);
}

}  // namespace sky
