// SPDX-License-Identifier: MIT
#include "skyservice/render/march_pass.h"

#include "skyservice/render/reprojection.h"

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
    for (Image* img : {&pass.cloudImage, &pass.depthImage, &pass.frontImage, &pass.freshCloudImage,
                       &pass.freshDepthImage, &pass.freshFrontImage})
        destroyImage(ctx, memory, *img);
    destroyMarchOrder(ctx, memory, pass.order);
    destroyProgram(ctx, pass.program);
}

VkExtent2D freshImageExtent(uint32_t width, uint32_t height, uint32_t blockPx)
{
    const uint32_t newColumnTexels = blockPx > 1 ? maxNewColumns(width) * blockPx : 0u;
    const uint32_t newRowTexels = blockPx > 1 ? maxNewRows(height) * blockPx : 0u;
    return {(width + blockPx - 1) / blockPx + newColumnTexels, (height + blockPx - 1) / blockPx + newRowTexels};
}

SkyStatus ensureMarchImages(MarchPass& pass, ImageChanges& changes, const MarchImageNeeds& needs)
{
    ImageDesc d;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    d.width = needs.width;
    d.height = needs.height;
    // The full-resolution cloud images: made when a frame first needs them; kept at their size while
    // frames do not (a renderer that draws full frames between reprojected ones keeps them), let go when
    // the frame size changes.
    const bool cloudSized = hasSize(pass.cloudImage, needs.width, needs.height);
    if (needs.fullResolutionCloud && !cloudSized)
    {
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        SKY_TRY(makeImage(changes, pass.cloudImage, d, "cloud radiance"));
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(makeImage(changes, pass.depthImage, d, "cloud depth"));
    }
    else if (!needs.fullResolutionCloud && pass.cloudImage.image && !cloudSized)
    {
        retireImage(changes, pass.cloudImage);
        retireImage(changes, pass.depthImage);
    }
    if (needs.fullResolutionFront && !hasSize(pass.frontImage, needs.width, needs.height))
    {
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(makeImage(changes, pass.frontImage, d, "cloud front"));
    }
    else if (!needs.fullResolutionFront)
        retireImage(changes, pass.frontImage);
    if (needs.blockPx == 0)
        return SkyStatus::success();  // a full frame: the fresh images stay for the next reprojected one

    const VkExtent2D fresh = freshImageExtent(needs.width, needs.height, needs.blockPx);
    d.width = fresh.width;
    d.height = fresh.height;
    const bool blockChanged = !hasSize(pass.freshCloudImage, fresh.width, fresh.height);
    if (blockChanged)
    {
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        SKY_TRY(makeImage(changes, pass.freshCloudImage, d, "fresh cloud radiance (one pixel per block)"));
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(makeImage(changes, pass.freshDepthImage, d, "fresh cloud depth (one pixel per block)"));
    }
    if (needs.freshFront && (blockChanged || !pass.freshFrontImage.image))
    {
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(makeImage(changes, pass.freshFrontImage, d, "fresh cloud front (one pixel per block)"));
    }
    else if (!needs.freshFront)
        retireImage(changes, pass.freshFrontImage);
    return SkyStatus::success();
}

void recordMarch(const PassFrame& f, const MarchPass& pass, const MarchInputs& in, const MarchTargets& out,
                 uint32_t marchX, uint32_t marchY)
{
    const Samplers& s = f.samplers;
    dispatch(f.ctx, f.cmd, pass.program, marchX, marchY, 1, nullptr, 0,
             {DescriptorInfo(f.frameUniforms), DescriptorInfo(f.atmosphereUniforms),
              DescriptorInfo(in.weatherWindow, s.linearClamp), DescriptorInfo(in.noise.base, s.linearRepeat),
              DescriptorInfo(in.noise.detail, s.linearRepeat), DescriptorInfo(in.noise.curl, s.linearRepeat),
              DescriptorInfo(in.noise.blue, s.nearestRepeat), DescriptorInfo(in.transmittanceLut, s.linearClamp),
              DescriptorInfo(out.cloud), DescriptorInfo(out.depth), DescriptorInfo(in.lightVolume, s.linearClamp),
              DescriptorInfo(in.columnBounds, s.nearestRepeat), DescriptorInfo(in.lightVolumeFar, s.linearClamp),
              DescriptorInfo(pass.order.buffer), DescriptorInfo(out.front)});
    computeBarrier(f.cmd);
}

}  // namespace sky
