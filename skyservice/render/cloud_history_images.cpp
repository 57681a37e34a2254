// SPDX-License-Identifier: MIT
#include "skyservice/render/cloud_history_images.h"

namespace sky
{
namespace
{

ImageDesc historyDesc(uint32_t width, uint32_t height, VkFormat sampledFormat)
{
    ImageDesc d;
    d.width = width;
    d.height = height;
    d.format = VK_FORMAT_R32_UINT;  // a core storage format; the sampled one is in its size class
    d.sampledFormat = sampledFormat;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    return d;
}

}  // namespace

ImageDesc cloudHistoryColourDesc(uint32_t width, uint32_t height)
{
    return historyDesc(width, height, VK_FORMAT_E5B9G9R9_UFLOAT_PACK32);
}

ImageDesc cloudHistoryAlphaDepthDesc(uint32_t width, uint32_t height)
{
    return historyDesc(width, height, VK_FORMAT_R16G16_UNORM);
}

}  // namespace sky
