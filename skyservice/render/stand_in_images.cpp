// SPDX-License-Identifier: MIT
#include "skyservice/render/stand_in_images.h"

namespace sky
{

SkyStatus createStandInImages(const Context& ctx, MemoryTracker& memory, StandInImages& s)
{
    ImageDesc d;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    SKY_TRY(createImage(ctx, memory, s.linear, d, "linear frame stand-in (1x1)"));
    SKY_TRY(createImage(ctx, memory, s.history.colour, cloudHistoryColourDesc(1, 1),
                        "cloud history radiance stand-in (1x1)"));
    SKY_TRY(createImage(ctx, memory, s.history.alphaDepth, cloudHistoryAlphaDepthDesc(1, 1),
                        "cloud history alpha and depth stand-in (1x1)"));
    d.format = VK_FORMAT_R32_SFLOAT;
    SKY_TRY(createImage(ctx, memory, s.depth, d, "cloud depth stand-in (1x1)"));
    d.format = VK_FORMAT_R32G32_SFLOAT;
    SKY_TRY(createImage(ctx, memory, s.depthLayer, d, "depth layer stand-in (1x1)"));
    OneShot shot;
    SKY_TRY(beginOneShot(ctx, shot));
    for (Image* img : {&s.linear, &s.history.colour, &s.history.alphaDepth, &s.depth, &s.depthLayer})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(ctx, shot);
}

void destroyStandInImages(const Context& ctx, MemoryTracker& memory, StandInImages& s)
{
    for (Image* img : {&s.linear, &s.history.colour, &s.history.alphaDepth, &s.depth, &s.depthLayer})
        destroyImage(ctx, memory, *img);
}

}  // namespace sky
