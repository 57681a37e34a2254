// SPDX-License-Identifier: MIT
#include "skyservice/render/pass_images.h"

#include <algorithm>

namespace sky
{

bool hasSize(const Image& image, uint32_t width, uint32_t height)
{
    return image.image && image.extent.width == width && image.extent.height == height;
}

SkyStatus makeImage(ImageChanges& changes, Image& image, const ImageDesc& desc, const char* name, bool cleared)
{
    retireImage(changes, image);
    SKY_TRY(createImage(changes.ctx, changes.memory, image, desc, name));
    changes.newImages.push_back(NewImage{image.image, cleared});
    return SkyStatus::success();
}

void retireImage(ImageChanges& changes, Image& image)
{
    if (!image.image)
        return;
    // An image made for a frame that was never submitted has nothing to initialize any more.
    std::vector<NewImage>& pending = changes.newImages;
    pending.erase(std::remove_if(pending.begin(), pending.end(),
                                 [&](const NewImage& n) { return n.image == image.image; }),
                  pending.end());
    if (!changes.inFlightDeletions)
    {
        destroyImage(changes.ctx, changes.memory, image);
        return;
    }
    Image doomed = image;
    image = Image{};
    const Context* ctx = &changes.ctx;
    MemoryTracker* memory = &changes.memory;
    changes.inFlightDeletions->push_back([ctx, memory, doomed]() mutable { destroyImage(*ctx, *memory, doomed); });
}

void recordNewImages(VkCommandBuffer cmd, const std::vector<NewImage>& images)
{
    if (images.empty())
        return;
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0,
                                         VK_REMAINING_ARRAY_LAYERS};
    std::vector<VkImageMemoryBarrier2> barriers;
    barriers.reserve(images.size());
    for (const NewImage& n : images)
    {
        // Nothing wrote a new image before: no source stage to wait for.
        VkImageMemoryBarrier2 b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = VK_PIPELINE_STAGE_2_NONE;
        b.srcAccessMask = VK_ACCESS_2_NONE;
        b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = n.image;
        b.subresourceRange = all;
        barriers.push_back(b);
    }
    VkDependencyInfo dep = {VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = uint32_t(barriers.size());
    dep.pImageMemoryBarriers = barriers.data();
    vkCmdPipelineBarrier2(cmd, &dep);
    bool anyCleared = false;
    const VkClearColorValue zero = {};
    for (const NewImage& n : images)
        if (n.cleared)
        {
            vkCmdClearColorImage(cmd, n.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
            anyCleared = true;
        }
    if (anyCleared)
        computeBarrier(cmd);  // the clears before the passes that read them
}

}  // namespace sky
