// SPDX-License-Identifier: MIT
#include "skyservice/render/composite_pass.h"

#include "skyservice/render/atmosphere_passes.h"

namespace sky
{

SkyStatus createCompositePass(const Context& ctx, CompositePass& pass)
{
    return createProgram(ctx, pass.program, "composite");
}

void destroyCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass)
{
    for (Image* img :
         {&pass.displayImage, &pass.linearImage, &pass.skyImage, &pass.cloudLayerImage, &pass.depthLayerImage})
        destroyImage(ctx, memory, *img);
    destroyProgram(ctx, pass.program);
}

SkyStatus ensureCompositeImages(CompositePass& pass, ImageChanges& changes, uint32_t width, uint32_t height,
                                const FrameOutputs& outputs)
{
    ImageDesc d;
    d.width = width;
    d.height = height;
    d.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    // Made when a frame first asks for it or at a new size; let go at the first frame that does not ask.
    auto keep = [&](Image& img, bool wanted, VkFormat format, const char* name) -> SkyStatus {
        if (!wanted)
        {
            retireImage(changes, img);
            return SkyStatus::success();
        }
        if (hasSize(img, width, height))
            return SkyStatus::success();
        d.format = format;
        return makeImage(changes, img, d, name);
    };
    SKY_TRY(keep(pass.displayImage, true, VK_FORMAT_R8G8B8A8_UNORM, "display frame"));
    SKY_TRY(keep(pass.linearImage, outputs.linearImage, VK_FORMAT_R16G16B16A16_SFLOAT, "linear frame"));
    SKY_TRY(keep(pass.skyImage, outputs.sky, VK_FORMAT_R16G16B16A16_SFLOAT, "sky layer"));
    SKY_TRY(keep(pass.cloudLayerImage, outputs.cloudLayer, VK_FORMAT_R16G16B16A16_SFLOAT, "cloud layer"));
    return keep(pass.depthLayerImage, outputs.depthLayer, VK_FORMAT_R32G32_SFLOAT, "depth layer");
}

void recordComposite(const PassFrame& f, const CompositePass& pass, const CompositeInputs& in, uint32_t width,
                     uint32_t height)
{
    const AtmospherePass& a = in.atmosphere;
    const Samplers& s = f.samplers;
    const FrameOutputs& o = in.outputs;
    const StandInImages& standIn = in.standIns;
    dispatch(f.ctx, f.cmd, pass.program, width, height, 1, nullptr, 0,
             {DescriptorInfo(f.frameUniforms), DescriptorInfo(f.atmosphereUniforms),
              DescriptorInfo(a.transmittanceLut, s.linearClamp), DescriptorInfo(a.skyViewLut, s.linearRepeat),
              DescriptorInfo(a.aerialInscatterLut, s.linearRepeat),
              DescriptorInfo(a.aerialTransmittanceLut, s.linearRepeat), DescriptorInfo(in.cloud),
              DescriptorInfo(in.depth), DescriptorInfo(in.history.colour, s.linearClamp),
              DescriptorInfo(in.history.alphaDepth, s.linearClamp),
              DescriptorInfo(o.linearImage ? pass.linearImage : standIn.linear), DescriptorInfo(pass.displayImage),
              DescriptorInfo(o.sky ? pass.skyImage : standIn.linear),
              DescriptorInfo(o.cloudLayer ? pass.cloudLayerImage : standIn.linear), DescriptorInfo(in.cloudOut),
              DescriptorInfo(in.depthOut), DescriptorInfo(in.front), DescriptorInfo(in.frontHistory),
              DescriptorInfo(o.depthLayer ? pass.depthLayerImage : standIn.depthLayer)});
}

}  // namespace sky
