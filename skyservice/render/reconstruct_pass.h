// SPDX-License-Identifier: MIT
// The reconstruct pass of temporal reprojection (shaders/clouds/reconstruct.comp.glsl; the CPU side's
// decisions are in reprojection.h): its program, the cloud history of the last two frames it writes, and
// what the renderer remembers of the last reprojected frame.
#pragma once

#include "skyservice/render/cloud_history_images.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/pass_images.h"
#include "skyservice/render/reprojection.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct ReconstructPass
{
    Program program;
    /// The reconstructed cloud radiance, alpha and depth of the last two frames (ping-pong), 8 bytes a
    /// texel (cloud_history_images.h); made on the first reprojected frame.
    CloudHistoryImages history[2];
    /// The depth layer's front distance: its own full-resolution history beside the radiance's (R32F,
    /// ping-pong with it); made while frames draw the layer (zero at first: the reconstruct pass then
    /// takes the depth), let go when they stop.
    Image frontHistory[2];
    ReprojectionHistory reprojection;  ///< which history image holds which frame, and whether it is usable
};

/// What the reconstruct pass reads besides its history: the march's fresh pixels (block resolution).
struct ReconstructInputs
{
    const Image& freshCloud;
    const Image& freshDepth;
    const Image* freshFront = nullptr;  ///< null: the frame draws no depth layer
    const Image& depthStandIn;          ///< bound for the fronts when there are none
};

/// Loads the program (the images are made on the first reprojected frame).
SkyStatus createReconstructPass(const Context& ctx, ReconstructPass& pass);
void destroyReconstructPass(const Context& ctx, MemoryTracker& memory, ReconstructPass& pass);

/// Makes the histories for a width x height frame (a new size also makes the history unusable), and the
/// fronts' history while `front` (the frame draws the depth layer), made cleared; lets it go after.
SkyStatus ensureReconstructImages(ReconstructPass& pass, ImageChanges& changes, uint32_t width, uint32_t height,
                                  bool front);

/// Records the reconstruct pass of a width x height frame: the fresh pixels and
/// history[reprojection.current] into history[reprojection.current ^ 1], then a barrier.
void recordReconstruct(const PassFrame& f, const ReconstructPass& pass, const ReconstructInputs& in, uint32_t width,
                       uint32_t height);

}  // namespace sky
