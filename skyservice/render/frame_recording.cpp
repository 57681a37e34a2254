// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_recording.h"

#include "skyservice/render/atmosphere_passes.h"
#include "skyservice/render/light_volume.h"
#include "skyservice/render/march_order.h"

#include <cstring>
#include <glm/gtc/packing.hpp>

namespace sky
{
namespace
{

namespace glsl
{
using namespace glm;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "shaders/lib/cloud_history.glsl"
#pragma GCC diagnostic pop
}  // namespace glsl

// A reprojected frame's cloud image on the host, as the composite sees it: `result` holds the fresh
// (block-resolution) pixels on entry and the full-resolution frame on return, the marched pixels from
// them, the others unpacked from the history texels in `packed` (RGBA16UI, shaders/lib/cloud_history.glsl).
void mergeReprojectedCloud(const Renderer& r, const ViewRequest& request, const std::vector<uint8_t>& packed,
                           RenderResult& result)
{
    const uint32_t w = request.width, h = request.height, B = r.reprojection.block.blockPx;
    const glm::uvec2 phase = reprojectionPhase(r.reprojection.frameIndex, B);
    const uint32_t freshWidth = r.freshCloudImage.extent.width;
    std::vector<uint16_t> cloud(size_t(w) * h * 4);
    std::vector<float> depth(size_t(w) * h);
    std::vector<uint16_t> texels(packed.size() / 2);
    std::memcpy(texels.data(), packed.data(), packed.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
        {
            const size_t i = size_t(y) * w + x;
            const uint32_t bx = x / B, by = y / B;
            if (x == bx * B + phase.x && y == by * B + phase.y)
            {
                const size_t f = size_t(by) * freshWidth + bx;
                std::memcpy(&cloud[i * 4], &result.cloudRgbaHalf[f * 4], 4 * sizeof(uint16_t));
                depth[i] = result.cloudDepthM[f];
                continue;
            }
            const glm::uvec4 t(texels[i * 4], texels[i * 4 + 1], texels[i * 4 + 2], texels[i * 4 + 3]);
            float depthM = 0.0f;
            const glm::vec4 c = glsl::unpackCloudHistory(t, depthM);
            for (int k = 0; k < 4; ++k)
                cloud[i * 4 + size_t(k)] = glm::packHalf1x16(c[k]);
            depth[i] = depthM;
        }
    result.cloudRgbaHalf = std::move(cloud);
    result.cloudDepthM = std::move(depth);
}

}  // namespace

SkyStatus renderOnce(Renderer& r, const ViewRequest& request, const CameraFrame& camera, const SunMoon& sunMoon,
                     const FrameInputs& in, const FrameParams& params, RenderResult& result)
{
    const bool reprojected = in.quality->reprojected;
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    VkCommandBuffer cmd = shot.cmd;
    vkCmdResetQueryPool(cmd, r.timestamps, 0, kTsCount);
    // Reprojected: one invocation per block (4x4, or finer near clouds) into the fresh images.
    const uint32_t block = reprojected ? r.reprojection.block.blockPx : 1u;
    const uint32_t marchX = (request.width + block - 1) / block;
    const uint32_t marchY = (request.height + block - 1) / block;
    // The order of the march's workgroup rows (march_order.h), uploaded first: its barrier then waits
    // for nothing.
    const uint32_t marchGroupRows = (marchY + WORKGROUP_SIZE_2D - 1) / WORKGROUP_SIZE_2D;
    result.marchRowOrder = prepareMarchOrder(r.marchOrder, cmd, marchGroupRows, r.marchDispatchRanges,
                                             in.quality->costOrderedMarch);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, r.timestamps, kTsStart);
    recordAtmosphere(r, cmd, camera, sunMoon, in);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsSkyView);
    recordLightVolume(r, cmd, params);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsLightVolume);
    const Image& marchCloud = reprojected ? r.freshCloudImage : r.cloudImage;
    const Image& marchDepth = reprojected ? r.freshDepthImage : r.depthImage;
    dispatch(r.ctx, cmd, r.cloudProgram, marchX, marchY, 1, nullptr, 0,
             {DescriptorInfo(r.frameUniforms), DescriptorInfo(r.atmosphereUniforms),
              DescriptorInfo(r.weatherWindowImage, r.linearClamp), DescriptorInfo(r.baseNoise, r.linearRepeat),
              DescriptorInfo(r.detailNoise, r.linearRepeat), DescriptorInfo(r.curlNoise, r.linearRepeat),
              DescriptorInfo(r.blueNoise, r.nearestRepeat), DescriptorInfo(r.transmittanceLut, r.linearClamp),
              DescriptorInfo(marchCloud), DescriptorInfo(marchDepth), DescriptorInfo(r.lightVolume, r.linearClamp),
              DescriptorInfo(r.columnBoundsImage, r.nearestRepeat), DescriptorInfo(r.lightVolumeFar, r.linearClamp),
              DescriptorInfo(r.marchOrder.buffer)});
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsClouds);
    // Reprojected: the packed history the reconstruct pass writes this frame (which the next frame
    // reprojects) holds the pixels not marched this frame; the composite and the readback take the
    // marched ones from the fresh images.
    const uint32_t next = r.reprojection.current ^ 1u;
    if (reprojected)
    {
        const uint32_t prev = r.reprojection.current;
        // One invocation per quad of RECONSTRUCT_QUAD_PX^2 pixels (shaders/shared/bindings.h).
        const uint32_t quadsX = (request.width + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
        const uint32_t quadsY = (request.height + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
        dispatch(r.ctx, cmd, r.reconstructProgram, quadsX, quadsY, 1, nullptr, 0,
                 {DescriptorInfo(r.frameUniforms), DescriptorInfo(r.freshCloudImage), DescriptorInfo(r.freshDepthImage),
                  DescriptorInfo(r.history[prev]), DescriptorInfo(r.history[next])});
        computeBarrier(cmd);
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsReconstruct);
    recordComposite(r, cmd, request, marchCloud, marchDepth, reprojected ? r.history[next] : r.historyStandIn,
                    in.quality->linearOutput ? r.linearImage : r.linearStandIn);
    computeBarrier(cmd);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, r.timestamps, kTsComposite);
    recordMarchLookupsReadback(r.marchOrder, cmd);
    SKY_TRY(endOneShot(r.ctx, shot));
    result.marchRowLookups = collectMarchLookups(r.marchOrder, marchGroupRows);

    uint64_t ts[kTsCount] = {};
    if (r.ctx.timestampPeriodNs > 0 &&
        vkGetQueryPoolResults(r.ctx.device, r.timestamps, 0, kTsCount, sizeof ts, ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT) == VK_SUCCESS)
    {
        auto ms = [&](uint32_t a, uint32_t b) { return double(ts[b] - ts[a]) * r.ctx.timestampPeriodNs * 1e-6; };
        result.gpuMs["sky"] = ms(kTsStart, kTsSkyView);
        // Part of the march (and of "clouds" in full mode), shown on its own as well.
        if (params.lightVolume.z > 0.0f)
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
    if (!in.quality->readback)
        return SkyStatus::success();  // timing runs: the GPU work is done, nothing to copy
    std::vector<uint8_t> bytes;
    SKY_TRY(readbackImage(r.ctx, r.memory, marchCloud, bytes));
    result.cloudRgbaHalf.resize(bytes.size() / 2);
    std::memcpy(result.cloudRgbaHalf.data(), bytes.data(), bytes.size());
    SKY_TRY(readbackImage(r.ctx, r.memory, marchDepth, bytes));
    result.cloudDepthM.resize(bytes.size() / 4);
    std::memcpy(result.cloudDepthM.data(), bytes.data(), bytes.size());
    if (reprojected)
    {
        SKY_TRY(readbackImage(r.ctx, r.memory, r.history[next], bytes));
        mergeReprojectedCloud(r, request, bytes, result);
    }
    result.linearRgbaHalf.clear();
    if (in.quality->linearOutput)
    {
        SKY_TRY(readbackImage(r.ctx, r.memory, r.linearImage, bytes));
        result.linearRgbaHalf.resize(bytes.size() / 2);
        std::memcpy(result.linearRgbaHalf.data(), bytes.data(), bytes.size());
    }
    return readbackImage(r.ctx, r.memory, r.displayImage, result.displayRgba8);
}

}  // namespace sky
