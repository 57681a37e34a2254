// SPDX-License-Identifier: MIT
// What every pass's record function reads besides its own inputs: the device, the command buffer being
// recorded, the frame's uniform buffers and the renderer's samplers. The frame function
// (frame_recording.cpp) makes one per frame and hands it to each pass with the pass's declared inputs.
#pragma once

#include "skyservice/vk/resources.h"

namespace sky
{

/// The samplers every pass binds textures with (made once by the renderer).
struct Samplers
{
    VkSampler linearRepeat = VK_NULL_HANDLE;   ///< tiling noise, the sky-view and aerial LUTs
    VkSampler linearClamp = VK_NULL_HANDLE;    ///< the weather window, the transmittance LUT, histories
    VkSampler nearestRepeat = VK_NULL_HANDLE;  ///< blue noise, column bounds
};

SkyStatus createSamplers(const Context& ctx, Samplers& samplers);
void destroySamplers(const Context& ctx, Samplers& samplers);

struct PassFrame
{
    const Context& ctx;
    VkCommandBuffer cmd;
    const Buffer& frameUniforms;       ///< FrameParams (shaders/shared/frame_params.h)
    const Buffer& atmosphereUniforms;  ///< AtmosphereParams: written by the atmosphere pass, read by the rest
    const Samplers& samplers;
};

}  // namespace sky
