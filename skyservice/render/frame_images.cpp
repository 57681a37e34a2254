// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_images.h"

namespace sky
{
namespace
{

bool hasSize(const Image& img, uint32_t width, uint32_t height)
{
    return img.image && img.extent.width == width && img.extent.height == height;
}

}  // namespace

SkyStatus ensureOutputImages(Renderer& r, uint32_t width, uint32_t height, bool cloudImages)
{
    const bool frameOk = hasSize(r.displayImage, width, height);
    const bool cloudOk = !cloudImages || hasSize(r.cloudImage, width, height);
    if (frameOk && cloudOk)
        return SkyStatus::success();
    VK_TRY(vkQueueWaitIdle(r.ctx.queue));  // resize or first full frame only: never in steady state
    std::vector<Image*> made;
    ImageDesc d;
    d.width = width;
    d.height = height;
    if (!frameOk)
    {
        destroyImage(r.ctx, r.memory, r.linearImage);
        destroyImage(r.ctx, r.memory, r.displayImage);
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        SKY_TRY(createImage(r.ctx, r.memory, r.linearImage, d, "linear frame"));
        d.format = VK_FORMAT_R8G8B8A8_UNORM;
        d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        SKY_TRY(createImage(r.ctx, r.memory, r.displayImage, d, "display frame"));
        d.usage = ImageDesc{}.usage;
        made = {&r.linearImage, &r.displayImage};
    }
    if (!frameOk || !cloudOk)  // a resize drops cloud images of the old size
    {
        destroyImage(r.ctx, r.memory, r.cloudImage);
        destroyImage(r.ctx, r.memory, r.depthImage);
        if (cloudImages)
        {
            d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            SKY_TRY(createImage(r.ctx, r.memory, r.cloudImage, d, "cloud radiance"));
            d.format = VK_FORMAT_R32_SFLOAT;
            SKY_TRY(createImage(r.ctx, r.memory, r.depthImage, d, "cloud depth"));
            made.push_back(&r.cloudImage);
            made.push_back(&r.depthImage);
        }
    }
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    for (Image* img : made)
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(r.ctx, shot);
}

SkyStatus ensureReprojectionImages(Renderer& r, uint32_t width, uint32_t height, uint32_t blockPx)
{
    OneShot shot;
    bool fresh = false;
    if (!(r.historyCloud[0].image && r.historyCloud[0].extent.width == width &&
          r.historyCloud[0].extent.height == height))
    {
        VK_TRY(vkQueueWaitIdle(r.ctx.queue));  // resize only: never in steady state
        for (Image* img : {&r.freshCloudImage, &r.freshDepthImage, &r.historyCloud[0], &r.historyCloud[1],
                           &r.historyDepth[0], &r.historyDepth[1]})
            destroyImage(r.ctx, r.memory, *img);
        r.reprojection.valid = false;
        ImageDesc d;
        d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        d.width = width;
        d.height = height;
        for (int k = 0; k < 2; ++k)
        {
            d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            SKY_TRY(createImage(r.ctx, r.memory, r.historyCloud[k], d, "cloud radiance history"));
            d.format = VK_FORMAT_R32_SFLOAT;
            SKY_TRY(createImage(r.ctx, r.memory, r.historyDepth[k], d, "cloud depth history"));
        }
        SKY_TRY(beginOneShot(r.ctx, shot));
        for (Image* img : {&r.historyCloud[0], &r.historyCloud[1], &r.historyDepth[0], &r.historyDepth[1]})
            transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        fresh = true;
    }
    uint32_t blocksX = (width + blockPx - 1) / blockPx, blocksY = (height + blockPx - 1) / blockPx;
    if (!(r.freshCloudImage.image && r.freshCloudImage.extent.width >= blocksX &&
          r.freshCloudImage.extent.height >= blocksY))
    {
        VK_TRY(vkQueueWaitIdle(r.ctx.queue));  // first frame at a finer block only
        destroyImage(r.ctx, r.memory, r.freshCloudImage);
        destroyImage(r.ctx, r.memory, r.freshDepthImage);
        ImageDesc d;
        d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
        d.width = blocksX;
        d.height = blocksY;
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        SKY_TRY(createImage(r.ctx, r.memory, r.freshCloudImage, d, "fresh cloud radiance (one pixel per block)"));
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(createImage(r.ctx, r.memory, r.freshDepthImage, d, "fresh cloud depth (one pixel per block)"));
        if (!fresh)
            SKY_TRY(beginOneShot(r.ctx, shot));
        for (Image* img : {&r.freshCloudImage, &r.freshDepthImage})
            transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
        fresh = true;
    }
    return fresh ? endOneShot(r.ctx, shot) : SkyStatus::success();
}

}  // namespace sky
