// SPDX-License-Identifier: MIT
// The light volume (shaders/shared/light_volume.h): the far part of every light cone around the eye,
// precomputed once per frame so that the march's lit samples near the eye read it instead of marching it.
#pragma once

#include "shaders/shared/frame_params.h"
#include "skyservice/render/render_tuning.h"
#include "skyservice/render/render_types.h"
#include "skyservice/weather/window_provider.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct Renderer;

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
 * Fills frame.lightVolume (and frame.lightVolumeFar, its cascade of LIGHT_VOLUME_FAR_SCALE times wider
 * texels, unless tuning.lightVolumeFarCascade is false): the volume's corner on the window plane, snapped
 * to whole texels so that the
 * texels stay fixed to the ground while the eye moves in a window, and its texel size; z = 0 (no volume)
 * when the quality turns it off, when no cone sample is cheap (nothing to precompute) or when the frame
 * has no volumetric cloud, or marches fewer rays than quality.lightVolumeMinRays (frame.image.xy and the
 * march block frame.reprojection.x must be final).
 **********************************************************************/
void placeLightVolume(const QualitySettings& quality, const RenderTuning& tuning, FrameParams& frame);

/// Records the pass that fills the volume for `frame`, then a barrier; nothing when frame.lightVolume.z
/// is 0 or when the volume already holds these inputs (LightVolumePass::key).
void recordLightVolume(Renderer& r, VkCommandBuffer cmd, const FrameParams& frame);

}  // namespace sky
