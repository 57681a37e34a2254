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

// Makes `img` (destroyed first) and adds it to the images to move to the GENERAL layout.
SkyStatus remake(Renderer& r, Image& img, const ImageDesc& d, const char* name, std::vector<Image*>& made)
{
    destroyImage(r.ctx, r.memory, img);
    SKY_TRY(createImage(r.ctx, r.memory, img, d, name));
    made.push_back(&img);
    return SkyStatus::success();
}

// Moves the images made to GENERAL; those in `cleared` are also filled with zeros.
SkyStatus toGeneral(Renderer& r, const std::vector<Image*>& made, const std::vector<Image*>& cleared = {})
{
    if (made.empty())
        return SkyStatus::success();
    OneShot shot;
    SKY_TRY(beginOneShot(r.ctx, shot));
    for (Image* img : made)
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    const VkClearColorValue zero = {};
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (Image* img : cleared)
        vkCmdClearColorImage(shot.cmd, img->image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    return endOneShot(r.ctx, shot);
}

}  // namespace

SkyStatus ensureOutputImages(Renderer& r, uint32_t width, uint32_t height, const FrameOutputs& outputs,
                             bool reprojected)
{
    const bool cloudImages = !reprojected || outputs.cloud || outputs.depth;
    const bool frameOk = hasSize(r.composite.displayImage, width, height);
    const bool cloudOk = !cloudImages || hasSize(r.march.cloudImage, width, height);
    if (!frameOk || !cloudOk)
    {
        // Resize or the first frame: never in steady state. Everything of the old size goes.
        VK_TRY(vkQueueWaitIdle(r.ctx.queue));
        for (Image* img : {&r.composite.displayImage, &r.composite.linearImage, &r.composite.skyImage,
                           &r.composite.cloudLayerImage, &r.composite.depthLayerImage, &r.march.frontImage})
            destroyImage(r.ctx, r.memory, *img);
        if (!frameOk || cloudImages)  // a resize drops cloud images of the old size
        {
            destroyImage(r.ctx, r.memory, r.march.cloudImage);
            destroyImage(r.ctx, r.memory, r.march.depthImage);
        }
    }
    std::vector<Image*> made;
    ImageDesc d;
    d.width = width;
    d.height = height;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    // Made when a frame first asks for them; an optional image no frame asks for any more goes once the
    // frames in flight that used it are done (the deletion queue), without a wait.
    auto optional = [&](Image& img, bool wanted, VkFormat format, const char* name) -> SkyStatus {
        if (wanted && !img.image)
        {
            d.format = format;
            return remake(r, img, d, name, made);
        }
        if (!wanted && img.image)
            deferDestroy(r, img);
        return SkyStatus::success();
    };
    SKY_TRY(optional(r.composite.displayImage, true, VK_FORMAT_R8G8B8A8_UNORM, "display frame"));
    SKY_TRY(optional(r.composite.linearImage, outputs.linearImage, VK_FORMAT_R16G16B16A16_SFLOAT, "linear frame"));
    SKY_TRY(optional(r.composite.skyImage, outputs.sky, VK_FORMAT_R16G16B16A16_SFLOAT, "sky layer"));
    SKY_TRY(optional(r.composite.cloudLayerImage, outputs.cloudLayer, VK_FORMAT_R16G16B16A16_SFLOAT, "cloud layer"));
    SKY_TRY(optional(r.composite.depthLayerImage, outputs.depthLayer, VK_FORMAT_R32G32_SFLOAT, "depth layer"));
    // Full-resolution frames march the fronts at full resolution; reprojected ones into the fresh images.
    SKY_TRY(optional(r.march.frontImage, outputs.depthLayer && !reprojected, VK_FORMAT_R32_SFLOAT, "cloud front"));
    if (cloudImages && !r.march.cloudImage.image)  // a renderer that made full frames keeps their cloud images
    {
        SKY_TRY(optional(r.march.cloudImage, true, VK_FORMAT_R16G16B16A16_SFLOAT, "cloud radiance"));
        SKY_TRY(optional(r.march.depthImage, true, VK_FORMAT_R32_SFLOAT, "cloud depth"));
    }
    return toGeneral(r, made);
}

void deferDestroy(Renderer& r, Image& image)
{
    // The newest frame submitted is the last that can use it; its context's fence is waited for before
    // the context is used again, which is after every older frame too.
    FrameContext& newest = recording(r);
    if (!newest.submitted)  // collected: frames are collected in order, so none is in flight
    {
        destroyImage(r.ctx, r.memory, image);
        return;
    }
    Image doomed = image;
    image = Image{};
    newest.deletions.push_back([&r, doomed]() mutable { destroyImage(r.ctx, r.memory, doomed); });
}

SkyStatus ensureReprojectionImages(Renderer& r, uint32_t width, uint32_t height, uint32_t blockPx, bool front)
{
    std::vector<Image*> made, cleared;
    ImageDesc d;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    if (!hasSize(r.reconstruct.history[0].colour, width, height))
    {
        VK_TRY(vkQueueWaitIdle(r.ctx.queue));  // resize only: never in steady state
        r.reconstruct.reprojection.valid = false;
        for (CloudHistoryImages& h : r.reconstruct.history)
        {
            SKY_TRY(remake(r, h.colour, cloudHistoryColourDesc(width, height), "cloud history radiance", made));
            SKY_TRY(remake(r, h.alphaDepth, cloudHistoryAlphaDepthDesc(width, height), "cloud history alpha and depth",
                           made));
        }
        for (Image& h : r.reconstruct.frontHistory)
            destroyImage(r.ctx, r.memory, h);
    }
    // The fronts' history exists only while frames draw the depth layer: made cleared (the reconstruct
    // pass then takes each pixel's depth as its front until it is marched), let go when they stop.
    for (Image& h : r.reconstruct.frontHistory)
    {
        if (front && !h.image)
        {
            d.width = width;
            d.height = height;
            d.format = VK_FORMAT_R32_SFLOAT;
            SKY_TRY(remake(r, h, d, "cloud front history", made));
            cleared.push_back(&h);
        }
        else if (!front && h.image)
            deferDestroy(r, h);
    }
    // The fresh images have the size of the block in use: they grow when the eye nears or enters a cloud
    // layer (every pixel is marched inside one: 25 MB at 1080p) and shrink back when it leaves. They only
    // hold this frame's marched pixels, so replacing them never touches the history.
    // Beside the blocks, room for the columns marched in full in a turn (reprojection.h NewLines): B
    // texels of a block row per column; below them, for the rows of a pitch change: B texels of a block
    // column per row.
    const uint32_t newColumnTexels = blockPx > 1 ? maxNewColumns(width) * blockPx : 0u;
    const uint32_t newRowTexels = blockPx > 1 ? maxNewRows(height) * blockPx : 0u;
    const uint32_t blocksX = (width + blockPx - 1) / blockPx + newColumnTexels;
    const uint32_t blocksY = (height + blockPx - 1) / blockPx + newRowTexels;
    const bool blockChanged = !hasSize(r.reconstruct.freshCloudImage, blocksX, blocksY);
    if (blockChanged)
    {
        VK_TRY(vkQueueWaitIdle(r.ctx.queue));  // a change of march block only
        d.width = blocksX;
        d.height = blocksY;
        d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
        SKY_TRY(remake(r, r.reconstruct.freshCloudImage, d, "fresh cloud radiance (one pixel per block)", made));
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(remake(r, r.reconstruct.freshDepthImage, d, "fresh cloud depth (one pixel per block)", made));
    }
    if (front && (blockChanged || !r.reconstruct.freshFrontImage.image))
    {
        d.width = blocksX;
        d.height = blocksY;
        d.format = VK_FORMAT_R32_SFLOAT;
        SKY_TRY(remake(r, r.reconstruct.freshFrontImage, d, "fresh cloud front (one pixel per block)", made));
    }
    else if (!front && r.reconstruct.freshFrontImage.image)
        deferDestroy(r, r.reconstruct.freshFrontImage);
    return toGeneral(r, made, cleared);
}

}  // namespace sky
