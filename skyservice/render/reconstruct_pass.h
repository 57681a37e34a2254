// SPDX-License-Identifier: MIT
// The reconstruct pass of temporal reprojection (shaders/clouds/reconstruct.comp.glsl; the CPU side's
// decisions are in reprojection.h): its program, the pixels the march wrote at block resolution, the
// cloud history of the last two frames, and what the renderer remembers of the last reprojected frame.
#pragma once

#include "skyservice/render/cloud_history_images.h"
#include "skyservice/render/frame_context.h"
#include "skyservice/render/reprojection.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct Renderer;

struct ReconstructPass
{
    Program program;
    /// This frame's marched pixels, one per block, at the size of the block in use (frame_images.h).
    Image freshCloudImage, freshDepthImage;
    /// The reconstructed cloud radiance, alpha and depth of the last two frames (ping-pong), 8 bytes a
    /// texel (cloud_history_images.h); made on the first reprojected frame.
    CloudHistoryImages history[2];
    /// The depth layer's front distance: the fresh pixels' (block resolution) and its own full-resolution
    /// history beside the radiance's (R32F, ping-pong with it); made while frames draw the layer (zero at
    /// first: the reconstruct pass then takes the depth), let go when they stop.
    Image freshFrontImage, frontHistory[2];
    ReprojectionHistory reprojection;  ///< which history image holds which frame, and whether it is usable
};

/// Loads the program (the images are made on the first reprojected frame).
SkyStatus createReconstructPass(const Context& ctx, ReconstructPass& pass);
void destroyReconstructPass(const Context& ctx, MemoryTracker& memory, ReconstructPass& pass);

/// Records the reconstruct pass of a width x height frame: the fresh pixels and
/// history[reprojection.current] into history[reprojection.current ^ 1], then a barrier.
void recordReconstruct(Renderer& r, const FrameContext& frame, VkCommandBuffer cmd, uint32_t width, uint32_t height);

}  // namespace sky
