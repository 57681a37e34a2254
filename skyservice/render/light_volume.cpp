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

namespace
{

// `frame` with the camera axes, the image part (size, flags, exposure), the sequence part (frame index,
// sub-pixel jitter, animation time: the drift is in the noise offsets), the march jitter and the
// reprojection part zeroed: what the volume's build does not read.
FrameParams lightVolumeInputs(const FrameParams& frame)
{
    FrameParams f = frame;
    std::memset(&f.camera, 0, sizeof f.camera);
    f.camera.eyeAltitudeM = frame.camera.eyeAltitudeM;  // the eye altitude places the texels
    std::memset(&f.image, 0, sizeof f.image);
    std::memset(&f.sequence, 0, sizeof f.sequence);
    std::memset(&f.reprojection, 0, sizeof f.reprojection);
    f.march.jitterTexelRad = 0.0f;
    return f;
}

}  // namespace

void recordLightVolume(const PassFrame& f, LightVolumePass& pass, const LightVolumeInputs& in,
                       const FrameParams& frame)
{
    if (frame.lightVolume.nearCascade.texelM <= 0.0f)
        return;
    LightVolumeKey key;
    key.inputs = lightVolumeInputs(frame);
    key.window = in.windowKey;
    key.valid = true;
    // FrameParams has no padding (frame_params.h: every part is whole 16-byte slots, unused members
    // written as zero): bytewise equality is field equality.
    if (pass.key.valid && pass.key.window == key.window &&
        std::memcmp(&pass.key.inputs, &key.inputs, sizeof(FrameParams)) == 0)
        return;
    pass.key = key;
    for (uint32_t cascade = 0; cascade < (frame.lightVolume.farCascade.texelM > 0.0f ? 2u : 1u); ++cascade)
        dispatch(f.ctx, f.cmd, pass.program, LIGHT_VOLUME_SIZE, LIGHT_VOLUME_SIZE, LIGHT_VOLUME_LEVELS, cascade,
                 {DescriptorInfo(f.frameUniforms), DescriptorInfo(in.weatherWindow, f.samplers.linearClamp),
                  DescriptorInfo(in.noise.base, f.samplers.linearRepeat),
                  DescriptorInfo(in.noise.detail, f.samplers.linearRepeat),
                  DescriptorInfo(in.noise.curl, f.samplers.linearRepeat),
                  DescriptorInfo(cascade == 0 ? pass.image : pass.farImage)});
    computeBarrier(f.cmd);
}

}  // namespace sky
