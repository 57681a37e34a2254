// SPDX-License-Identifier: MIT
#include "skyservice/render/march_pass.h"

#include "skyservice/render/renderer.h"

namespace sky
{

SkyStatus createMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass)
{
    SKY_TRY(createProgram(ctx, pass.program, "cloud_march"));
    SKY_TRY(createMarchOrder(ctx, memory, pass.order));
    pass.dispatchRanges = dispatchRanges(ctx);
    return SkyStatus::success();
}

void destroyMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass)
{
    destroyImage(ctx, memory, pass.cloudImage);
    destroyImage(ctx, memory, pass.depthImage);
    destroyImage(ctx, memory, pass.frontImage);
    destroyMarchOrder(ctx, memory, pass.order);
    destroyProgram(ctx, pass.program);
}

void recordMarch(Renderer& r, const FrameContext& frame, VkCommandBuffer cmd, uint32_t marchX, uint32_t marchY,
                 const Image& cloud, const Image& depth, const Image& front)
{
    dispatch(r.ctx, cmd, r.march.program, marchX, marchY, 1, nullptr, 0,
             {DescriptorInfo(frame.frameUniforms), DescriptorInfo(frame.atmosphereUniforms),
              DescriptorInfo(r.weather.windowImage, r.linearClamp), DescriptorInfo(r.noise.base, r.linearRepeat),
              DescriptorInfo(r.noise.detail, r.linearRepeat), DescriptorInfo(r.noise.curl, r.linearRepeat),
              DescriptorInfo(r.noise.blue, r.nearestRepeat),
              DescriptorInfo(r.atmosphere.transmittanceLut, r.linearClamp),
              DescriptorInfo(cloud), DescriptorInfo(depth), DescriptorInfo(r.lightVolume.image, r.linearClamp),
              DescriptorInfo(r.weather.columnBoundsImage, r.nearestRepeat),
              DescriptorInfo(r.lightVolume.farImage, r.linearClamp), DescriptorInfo(r.march.order.buffer),
              DescriptorInfo(front)});
    computeBarrier(cmd);
}

}  // namespace sky
