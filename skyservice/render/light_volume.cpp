// SPDX-License-Identifier: MIT
#include "skyservice/render/light_volume.h"

#include "shaders/shared/light_volume.h"
#include "skyservice/vk/programs.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace sky
{

SkyStatus createLightVolumePass(const Context& ctx, MemoryTracker& memory, LightVolumePass& pass)
{
    SKY_TRY(createProgram(ctx, pass.program, "light_volume"));
    ImageDesc d;
    d.viewType = VK_IMAGE_VIEW_TYPE_3D;
    // Transmittance (half floats keep 11 bits down to 6e-5, less to 6e-8) and diffusion factor (0..1).
    d.format = VK_FORMAT_R16G16_SFLOAT;
    d.width = d.height = LIGHT_VOLUME_SIZE;
    d.depth = LIGHT_VOLUME_LEVELS;
    SKY_TRY(createImage(ctx, memory, pass.image, d, "light volume"));
    SKY_TRY(createImage(ctx, memory, pass.farImage, d, "light volume, far cascade"));
    OneShot shot;
    SKY_TRY(beginOneShot(ctx, shot));
    for (Image* img : {&pass.image, &pass.farImage})
        transitionImage(shot.cmd, *img, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    return endOneShot(ctx, shot);
}

void destroyLightVolumePass(const Context& ctx, MemoryTracker& memory, LightVolumePass& pass)
{
    destroyImage(ctx, memory, pass.image);
    destroyImage(ctx, memory, pass.farImage);
    destroyProgram(ctx, pass.program);
}

namespace
{

// The placement of a volume of `texelM` texels around the eye: its corner snapped in double to a whole
// number of texels on the window plane, so that frames (and display channels) with eyes in the same
// texel build the same volume.
vec4 volumePlacement(const FrameParams& frame, double texelM)
{
    const double half = 0.5 * double(LIGHT_VOLUME_SIZE);
    const double cornerX = (std::floor(double(frame.windowOffsetM.x) / texelM) - half) * texelM;
    const double cornerY = (std::floor(double(frame.windowOffsetM.y) / texelM) - half) * texelM;
    return vec4(float(cornerX), float(cornerY), float(texelM), 0.0f);
}

}  // namespace

void placeLightVolume(const QualitySettings& quality, const RenderTuning& tuning, FrameParams& frame)
{
    frame.lightVolume = vec4(0.0f);
    frame.lightVolumeFar = vec4(0.0f);
    const uint32_t samples = std::min(quality.lightSamples, 6u);
    const bool hasVolumetricCloud = frame.shell.y > frame.shell.x;
    const uint32_t block = std::max(frame.reprojection.x, 1u);
    const uint64_t rays = uint64_t((frame.image.x + block - 1) / block) * uint64_t((frame.image.y + block - 1) / block);
    if (quality.lightVolumeTexelM > 0.0 && quality.fullConeSamples < samples && hasVolumetricCloud &&
        rays >= quality.lightVolumeMinRays)
    {
        frame.lightVolume = volumePlacement(frame, quality.lightVolumeTexelM);
        if (tuning.lightVolumeFarCascade)
            frame.lightVolumeFar = volumePlacement(frame, quality.lightVolumeTexelM * LIGHT_VOLUME_FAR_SCALE);
    }
    // Where neither volume reaches, lit samples this close to the last cone that marched its far
    // samples take those (cloud_lighting.glsl ConeTail).
    frame.lightVolume.w = float(std::max(tuning.coneTailReuseM, 0.0));
    frame.lightVolumeFar.w = float(std::max(tuning.coneTailReuseBeyondM, 0.0));
}

namespace
{

// `frame` with the camera axes, image size, frame index, sub-pixel jitter and reprojection fields
// zeroed: what the volume's build does not read.
FrameParams lightVolumeInputs(const FrameParams& frame)
{
    FrameParams f = frame;
    f.cameraRight = f.cameraUp = vec4(0.0f);
    f.cameraForward = vec4(0.0f, 0.0f, 0.0f, frame.cameraForward.w);  // the eye altitude places the texels
    f.exposure = vec4(0.0f);
    f.image = uvec4(0u);
    f.reprojection = uvec4(0u);
    f.previousRight = f.previousUp = f.previousForward = f.previousEye = vec4(0.0f);
    f.worldJitter = vec4(0.0f);
    return f;
}

}  // namespace

void recordLightVolume(const PassFrame& f, LightVolumePass& pass, const LightVolumeInputs& in,
                       const FrameParams& frame)
{
    if (frame.lightVolume.z <= 0.0f)
        return;
    LightVolumeKey key;
    key.inputs = lightVolumeInputs(frame);
    key.window = in.windowKey;
    key.valid = true;
    // FrameParams is all vec4/uvec4 (std140 without padding): bytewise equality is field equality.
    if (pass.key.valid && pass.key.window == key.window &&
        std::memcmp(&pass.key.inputs, &key.inputs, sizeof(FrameParams)) == 0)
        return;
    pass.key = key;
    for (uint32_t cascade = 0; cascade < (frame.lightVolumeFar.z > 0.0f ? 2u : 1u); ++cascade)
        dispatch(f.ctx, f.cmd, pass.program, LIGHT_VOLUME_SIZE, LIGHT_VOLUME_SIZE, LIGHT_VOLUME_LEVELS, cascade,
                 {DescriptorInfo(f.frameUniforms), DescriptorInfo(in.weatherWindow, f.samplers.linearClamp),
                  DescriptorInfo(in.noise.base, f.samplers.linearRepeat),
                  DescriptorInfo(in.noise.detail, f.samplers.linearRepeat),
                  DescriptorInfo(in.noise.curl, f.samplers.linearRepeat),
                  DescriptorInfo(cascade == 0 ? pass.image : pass.farImage)});
    computeBarrier(f.cmd);
}

}  // namespace sky
