// SPDX-License-Identifier: MIT
// The cloud march (shaders/clouds/cloud_march.comp.glsl): its program, the order its workgroup rows are
// launched in (march_order.h), and every image it writes: the full-resolution cloud images of
// full-resolution frames, and the fresh pixels of reprojected frames (one per block).
#pragma once

#include "skyservice/render/march_order.h"
#include "skyservice/render/noise_textures.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/pass_images.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct MarchPass
{
    Program program;
    MarchOrder order;  ///< the workgroup-row order and the lookups of the last march (march_order.h)
    uint32_t dispatchRanges = 1;  ///< contiguous ranges the device runs a dispatch in (dispatchRanges)
    /// Full-resolution cloud radiance and depth: what a full-resolution frame marches into, and what the
    /// composite of a reprojected frame fills when a reader asks for them. A renderer that has made them
    /// keeps them at their size.
    Image cloudImage, depthImage;
    /// Full-resolution front distance of the depth layer: made while full-resolution frames draw it.
    Image frontImage;
    /// A reprojected frame's marched pixels at the size of the block in use (one per block, and the lines
    /// marched in full beside them): they grow when the eye nears or enters a cloud layer and shrink back
    /// when it leaves. They hold only this frame's pixels, so replacing them never touches the history.
    Image freshCloudImage, freshDepthImage;
    Image freshFrontImage;  ///< ... and fronts, while reprojected frames draw the depth layer
};

/// What the march reads.
struct MarchInputs
{
    const Image& weatherWindow;   ///< shaders/shared/weather_window.h
    const Image& columnBounds;    ///< shaders/shared/column_bounds.h
    const NoiseTextures& noise;
    const Image& transmittanceLut;
    const Image& lightVolume;     ///< light_volume.h, and its far cascade
    const Image& lightVolumeFar;
};

/// Where the march writes (its own images; `front` is a stand-in when the frame draws no depth layer).
struct MarchTargets
{
    const Image& cloud;
    const Image& depth;
    const Image& front;
};

/// The images the frame being prepared needs.
struct MarchImageNeeds
{
    uint32_t width = 0, height = 0;
    bool fullResolutionCloud = false;  ///< cloudImage and depthImage (full frames, or a reader asks for them)
    bool fullResolutionFront = false;  ///< frontImage (a full frame that draws the depth layer)
    uint32_t blockPx = 0;              ///< reprojected: the march block in use (0: a full frame)
    bool freshFront = false;           ///< freshFrontImage (a reprojected frame that draws the depth layer)
};

/// Loads the program and makes the row-order buffers (the images are made with the first frame).
SkyStatus createMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass);
void destroyMarchPass(const Context& ctx, MemoryTracker& memory, MarchPass& pass);

/// Makes, resizes and lets go the march's images for a frame (pass_images.h: no queue idles).
SkyStatus ensureMarchImages(MarchPass& pass, ImageChanges& changes, const MarchImageNeeds& needs);

/// Size of the fresh images of a width x height frame marched in blocks of `blockPx`: the blocks, and
/// beside them room for the columns marched in full in a turn (reprojection.h NewLines: B texels of a
/// block row per column) and below them for the rows of a pitch change (B texels of a block column per row).
VkExtent2D freshImageExtent(uint32_t width, uint32_t height, uint32_t blockPx);

/// Records the march of marchX x marchY rays (one per pixel; in reprojected frames one per block) into
/// `out`, then a barrier. The row order must have been prepared (prepareMarchOrder).
void recordMarch(const PassFrame& f, const MarchPass& pass, const MarchInputs& in, const MarchTargets& out,
                 uint32_t marchX, uint32_t marchY);

}  // namespace sky
