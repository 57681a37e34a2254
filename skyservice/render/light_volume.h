// SPDX-License-Identifier: MIT
// The light volume (shaders/shared/light_volume.h): the far part of every light cone around the eye,
// precomputed once per frame so that the march's lit samples near the eye read it instead of marching it.
#pragma once

#include "shaders/shared/frame_params.h"
#include "skyservice/render/noise_textures.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/render_tuning.h"
#include "skyservice/render/render_types.h"
#include "skyservice/weather/window_provider.h"
#include "skyservice/vk/programs.h"

namespace sky
{

/// What the volume was built from: the frame uniforms less the fields that only aim the camera or
/// time-stamp the frame, and the weather window's key. A frame with the same inputs
/// (a still view, the frames of an accumulation, a paused simulator) reuses the volume: bit for bit what
/// it would build.
struct LightVolumeKey
{
    FrameParams inputs{};
    WindowKey window;
    bool valid = false;
};

/// The pass that fills the volume, its two images and what they hold.
struct LightVolumePass
{
    Program program;
    Image image;     ///< 3D: the light volume around the eye
    Image farImage;  ///< its far cascade (LIGHT_VOLUME_FAR_SCALE times wider texels)
    LightVolumeKey key;  ///< what the images hold (valid = false: nothing yet)
};

/// Loads the program and creates the volume image and its far cascade's (each LIGHT_VOLUME_SIZE^2 x
/// LIGHT_VOLUME_LEVELS, RG16F: 0.88 MB), layout GENERAL.
SkyStatus createLightVolumePass(const Context& ctx, MemoryTracker& memory, LightVolumePass& pass);
void destroyLightVolumePass(const Context& ctx, MemoryTracker& memory, LightVolumePass& pass);

/**
 * The light volume part of a frame's uniforms: the volume (and its far cascade of LIGHT_VOLUME_FAR_SCALE
 * times wider texels, unless tuning.lightVolumeFarCascade is false) around the eye at `eyeOnPlaneM` on
 * the window plane: its corner snapped to whole texels so that the texels stay fixed to the ground while
 * the eye moves in a window, and its texel size; texelM = 0 (no volume) when the quality turns it off,
 * when no cone sample is cheap (nothing to precompute), when the frame has no volumetric cloud, or when it
 * marches fewer rays than quality.lightVolumeMinRays (`marchedRays`: one per march block).
 */
LightVolumeParams placeLightVolume(const QualitySettings& quality, const RenderTuning& tuning, const vec2& eyeOnPlaneM,
                                   bool volumetricCloud, uint64_t marchedRays);

/// The rays the march casts for an image of widthPx x heightPx in blocks of blockPx (1: every pixel).
uint64_t marchedRays(uint32_t widthPx, uint32_t heightPx, uint32_t blockPx);

/// What the light volume reads: the frame's weather window (and its key) and the noise.
struct LightVolumeInputs
{
    const Image& weatherWindow;
    const WindowKey& windowKey;
    const NoiseTextures& noise;
};

/// Records the pass that fills the volume for `frame`, then a barrier; nothing when
/// frame.lightVolume.nearCascade.texelM is 0 or when the volume already holds these inputs (LightVolumePass::key).
void recordLightVolume(const PassFrame& f, LightVolumePass& pass, const LightVolumeInputs& in,
                       const FrameParams& frame);

}  // namespace sky
