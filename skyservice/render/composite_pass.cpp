// SPDX-License-Identifier: MIT
#include "skyservice/render/composite_pass.h"

#include "skyservice/render/renderer.h"

namespace sky
{

SkyStatus createCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass)
{
    SKY_TRY(createProgram(ctx, pass.program, "composite"));
    ImageDesc d;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    SKY_TRY(createImage(ctx, memory, pass.linearStandIn, d, "linear frame stand-in (1x1)"));
    SKY_TRY(createImage(ctx, memory, pass.historyStandIn.colour, cloudHistoryColourDesc(1, 1),
                        "cloud history radiance stand-in (1x1)"));
    SKY_TRY(createImage(ctx, memory, pass.historyStandIn.alphaDepth, cloudHistoryAlphaDepthDesc(1, 1),
                        "cloud history alpha and depth stand-in (1x1)"));
    d.format = VK_FORMAT_R32_SFLOAT;
    SKY_TRY(createImage(ctx, memory, pass.depthStandIn, d, "cloud depth stand-in (1x1)"));
    d.format = VK_FORMAT_R32G32_SFLOAT;
    SKY_TRY(createImage(ctx, memory, pass.depthLayerStandIn, d, "depth layer stand-in (1x1)"));
    OneShot shot;
    SKY_TRY(beginOneShot(ctx, shot));
    for (Image* img : {&pass.linearStandIn, &pass.historyStandIn.colour, &pass.historyStandIn.alphaDepth,
                       &pass.depthStandIn, &pass.depthLayerStandIn})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(ctx, shot);
}

void destroyCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass)
{
    for (Image* img : {&pass.displayImage, &pass.linearImage, &pass.skyImage, &pass.cloudLayerImage,
                       &pass.depthLayerImage, &pass.linearStandIn, &pass.historyStandIn.colour,
                       &pass.historyStandIn.alphaDepth, &pass.depthStandIn,
                       &pass.depthLayerStandIn})
        destroyImage(ctx, memory, *img);
    destroyProgram(ctx, pass.program);
}

void recordComposite(Renderer& r, VkCommandBuffer cmd, const ViewRequest& request, const CompositeImages& images)
{
    const AtmospherePass& a = r.atmosphere;
    dispatch(r.ctx, cmd, r.composite.program, request.width, request.height, 1, nullptr, 0,
             {DescriptorInfo(recording(r).frameUniforms), DescriptorInfo(recording(r).atmosphereUniforms),
              DescriptorInfo(a.transmittanceLut, r.linearClamp), DescriptorInfo(a.skyViewLut, r.linearRepeat),
              DescriptorInfo(a.aerialInscatterLut, r.linearRepeat),
              DescriptorInfo(a.aerialTransmittanceLut, r.linearRepeat), DescriptorInfo(*images.cloud),
              DescriptorInfo(*images.depth), DescriptorInfo(images.history->colour, r.linearClamp),
              DescriptorInfo(images.history->alphaDepth, r.linearClamp), DescriptorInfo(*images.linear),
              DescriptorInfo(r.composite.displayImage), DescriptorInfo(*images.sky), DescriptorInfo(*images.cloudLayer),
              DescriptorInfo(*images.cloudOut), DescriptorInfo(*images.depthOut), DescriptorInfo(*images.front),
              DescriptorInfo(*images.frontHistory), DescriptorInfo(*images.depthLayer)});
}

}  // namespace sky
