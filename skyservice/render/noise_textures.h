// SPDX-License-Identifier: MIT
// The noise textures the clouds are shaped with (docs/model.md): the base and detail 3D noises, the curl
// noise and the blue noise of the march's jitter, with the programs that make them. Made once, at start-up,
// from the seed; read by the march, the light volume and the shadow map.
#pragma once

#include "skyservice/vk/programs.h"

namespace sky
{

struct NoiseTextures
{
    Program baseProgram, detailProgram, curlProgram;
    Image base;    ///< 3D, BASE_NOISE_SIZE^3 (shaders/shared/noise_params.h)
    Image detail;  ///< 3D, DETAIL_NOISE_SIZE^3
    Image curl;    ///< 2D, CURL_NOISE_SIZE^2
    Image blue;    ///< 2D, BLUE_NOISE_SIZE^2, made on the CPU (sky/blue_noise.h)
    double startupMs = 0;  ///< GPU time to generate them (0 where the device has no timestamps)
};

/// Loads the programs, makes the images and fills them from `seed` (layout GENERAL); `timestamps` (two
/// free queries) times the generation.
SkyStatus createNoiseTextures(const Context& ctx, MemoryTracker& memory, NoiseTextures& noise, uint32_t seed,
                              VkQueryPool timestamps);
void destroyNoiseTextures(const Context& ctx, MemoryTracker& memory, NoiseTextures& noise);

}  // namespace sky
