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
