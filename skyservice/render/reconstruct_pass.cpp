// SPDX-License-Identifier: MIT
#include "skyservice/render/reconstruct_pass.h"

#include "shaders/shared/bindings.h"
#include "skyservice/render/renderer.h"

namespace sky
{

SkyStatus createReconstructPass(const Context& ctx, ReconstructPass& pass)
{
    return createProgram(ctx, pass.program, "reconstruct");
}

void destroyReconstructPass(const Context& ctx, MemoryTracker& memory, ReconstructPass& pass)
{
    for (Image* img : {&pass.freshCloudImage, &pass.freshDepthImage, &pass.history[0].colour,
                       &pass.history[0].alphaDepth, &pass.history[1].colour, &pass.history[1].alphaDepth,
                       &pass.freshFrontImage, &pass.frontHistory[0], &pass.frontHistory[1]})
        destroyImage(ctx, memory, *img);
    destroyProgram(ctx, pass.program);
}

void recordReconstruct(Renderer& r, const FrameContext& frame, VkCommandBuffer cmd, uint32_t width, uint32_t height)
{
    ReconstructPass& pass = r.reconstruct;
    const uint32_t prev = pass.reprojection.current;
    const uint32_t next = prev ^ 1u;
    // One invocation per quad of RECONSTRUCT_QUAD_PX^2 pixels (shaders/shared/bindings.h).
    const uint32_t quadsX = (width + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
    const uint32_t quadsY = (height + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
    const bool front = pass.freshFrontImage.image != VK_NULL_HANDLE;  // the frame draws the depth layer
    const Image& standIn = r.composite.depthStandIn;
    dispatch(r.ctx, cmd, pass.program, quadsX, quadsY, 1, nullptr, 0,
             {DescriptorInfo(frame.frameUniforms), DescriptorInfo(pass.freshCloudImage),
              DescriptorInfo(pass.freshDepthImage), DescriptorInfo(pass.history[prev].colour, r.linearClamp),
              DescriptorInfo(pass.history[prev].alphaDepth, r.linearClamp), DescriptorInfo(pass.history[next].colour),
              DescriptorInfo(pass.history[next].alphaDepth), DescriptorInfo(front ? pass.freshFrontImage : standIn),
              DescriptorInfo(front ? pass.frontHistory[prev] : standIn),
              DescriptorInfo(front ? pass.frontHistory[next] : standIn)});
    computeBarrier(cmd);
}

}  // namespace sky
