// SPDX-License-Identifier: MIT
#include "skyservice/render/reconstruct_pass.h"

#include "shaders/shared/bindings.h"

namespace sky
{

SkyStatus createReconstructPass(const Context& ctx, ReconstructPass& pass)
{
    return createProgram(ctx, pass.program, "reconstruct");
}

void destroyReconstructPass(const Context& ctx, MemoryTracker& memory, ReconstructPass& pass)
{
    for (Image* img : {&pass.history[0].colour, &pass.history[0].alphaDepth, &pass.history[1].colour,
                       &pass.history[1].alphaDepth, &pass.frontHistory[0], &pass.frontHistory[1]})
        destroyImage(ctx, memory, *img);
    destroyProgram(ctx, pass.program);
}

SkyStatus ensureReconstructImages(ReconstructPass& pass, ImageChanges& changes, uint32_t width, uint32_t height,
                                  bool front)
{
    if (!hasSize(pass.history[0].colour, width, height))
    {
        pass.reprojection.valid = false;
        for (CloudHistoryImages& h : pass.history)
        {
            SKY_TRY(makeImage(changes, h.colour, cloudHistoryColourDesc(width, height), "cloud history radiance"));
            SKY_TRY(makeImage(changes, h.alphaDepth, cloudHistoryAlphaDepthDesc(width, height),
                              "cloud history alpha and depth"));
        }
        for (Image& h : pass.frontHistory)
            retireImage(changes, h);
    }
    // Made cleared: the reconstruct pass then takes each pixel's depth as its front until it is marched.
    ImageDesc d;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    d.width = width;
    d.height = height;
    d.format = VK_FORMAT_R32_SFLOAT;
    for (Image& h : pass.frontHistory)
    {
        if (front && !h.image)
            SKY_TRY(makeImage(changes, h, d, "cloud front history", true));
        else if (!front)
            retireImage(changes, h);
    }
    return SkyStatus::success();
}

void recordReconstruct(const PassFrame& f, const ReconstructPass& pass, const ReconstructInputs& in, uint32_t width,
                       uint32_t height)
{
    const uint32_t prev = pass.reprojection.current;
    const uint32_t next = prev ^ 1u;
    // One invocation per quad of RECONSTRUCT_QUAD_PX^2 pixels (shaders/shared/bindings.h).
    const uint32_t quadsX = (width + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
    const uint32_t quadsY = (height + RECONSTRUCT_QUAD_PX - 1) / RECONSTRUCT_QUAD_PX;
    const bool front = in.freshFront != nullptr;
    const Image& standIn = in.depthStandIn;
    const VkSampler clamp = f.samplers.linearClamp;
    dispatch(f.ctx, f.cmd, pass.program, quadsX, quadsY, 1, nullptr, 0,
             {DescriptorInfo(f.frameUniforms), DescriptorInfo(in.freshCloud), DescriptorInfo(in.freshDepth),
              DescriptorInfo(pass.history[prev].colour, clamp), DescriptorInfo(pass.history[prev].alphaDepth, clamp),
              DescriptorInfo(pass.history[next].colour), DescriptorInfo(pass.history[next].alphaDepth),
              DescriptorInfo(front ? *in.freshFront : standIn), DescriptorInfo(front ? pass.frontHistory[prev] : standIn),
              DescriptorInfo(front ? pass.frontHistory[next] : standIn)});
    computeBarrier(f.cmd);
}

}  // namespace sky
