// SPDX-License-Identifier: MIT
// The cloud march (shaders/clouds/cloud_march.comp.glsl): its program, the order its workgroup rows are
// launched in (march_order.h), and the full-resolution cloud images.
#pragma once

#include "skyservice/render/frame_context.h"
#include "skyservice/render/march_order.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct Renderer;

struct MarchPass
{
    Program program;
    MarchOrder order;  ///< the workgroup-row order and the lookups of the last march (march_order.h)
    uint32_t dispatchRanges = 1;  ///< contiguous ranges the device runs a dispatch in (dispatchRanges)
    /// Full-resolution cloud radiance and depth: what a full-resolution frame marches into, and what the
    /// composite of a reprojected frame writes when a reader asks for them (frame_images.h).
    Image cloudImage, depthImage;
    /// Full-resolution front distance of the depth layer: made while full-resolution frames draw it.
    Image frontImage;
};

/// Loads the program and makes the row-order buffers (the cloud images are made with the first frame).
SkyStatus createMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass);
void destroyMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass);

/// Records the march of marchX x marchY rays (one per pixel; in reprojected frames one per block) into
/// `cloud`, `depth` and `front` (written with FRAME_FLAG_DEPTH_LAYER only), then a barrier. The row order
/// must have been prepared (prepareMarchOrder).
void recordMarch(Renderer& r, const FrameContext& frame, VkCommandBuffer cmd, uint32_t marchX, uint32_t marchY,
                 const Image& cloud, const Image& depth, const Image& front);

}  // namespace sky
