// SPDX-License-Identifier: MIT
// Where the light volume sits and whether it is worth building: CPU arithmetic only (no Vulkan), so that
// the frame set-up (frame_setup.cpp) links without the renderer, as the config fuzzer does.
#include "skyservice/render/light_volume.h"

#include "shaders/shared/light_volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sky
{

namespace
{

// The placement of a volume of `texelM` texels around the eye: its corner snapped in double to a whole
// number of texels on the window plane, so that frames (and display channels) with eyes in the same
// texel build the same volume.
LightVolumeCascadeParams volumePlacement(const vec2& eyeOnPlaneM, double texelM)
{
    const double half = 0.5 * double(LIGHT_VOLUME_SIZE);
    const double cornerX = (std::floor(double(eyeOnPlaneM.x) / texelM) - half) * texelM;
    const double cornerY = (std::floor(double(eyeOnPlaneM.y) / texelM) - half) * texelM;
    LightVolumeCascadeParams c;
    std::memset(&c, 0, sizeof c);
    c.cornerM = vec2(float(cornerX), float(cornerY));
    c.texelM = float(texelM);
    return c;
}

}  // namespace

LightVolumeParams placeLightVolume(const QualitySettings& quality, const RenderTuning& tuning, const vec2& eyeOnPlaneM,
                                   bool volumetricCloud, uint64_t marchedRays)
{
    LightVolumeParams v;
    std::memset(&v, 0, sizeof v);
    const uint32_t samples = std::min(quality.lightSamples, 6u);
    if (quality.lightVolumeTexelM > 0.0 && quality.fullConeSamples < samples && volumetricCloud &&
        marchedRays >= quality.lightVolumeMinRays)
    {
        v.nearCascade = volumePlacement(eyeOnPlaneM, quality.lightVolumeTexelM);
        if (tuning.lightVolumeFarCascade)
            v.farCascade = volumePlacement(eyeOnPlaneM, quality.lightVolumeTexelM * LIGHT_VOLUME_FAR_SCALE);
    }
    return v;
}

uint64_t marchedRays(uint32_t widthPx, uint32_t heightPx, uint32_t blockPx)
{
    const uint32_t block = std::max(blockPx, 1u);
    return uint64_t((widthPx + block - 1) / block) * uint64_t((heightPx + block - 1) / block);
}

}  // namespace sky
