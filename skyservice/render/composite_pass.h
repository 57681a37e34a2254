// SPDX-License-Identifier: MIT
// The composite pass (shaders/composite/composite.comp.glsl): sky, clouds and aerial perspective into
// the display image, and the optional outputs a reader asks for (linear frame, sky and cloud layers, the
// full-resolution cloud image of a reprojected frame). Its program, its output images and the 1x1
// stand-ins bound where a frame has nothing to read or write.
#pragma once

#include "skyservice/render/cloud_history_images.h"
#include "skyservice/render/render_types.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct Renderer;

struct CompositePass
{
    Program program;
    Image displayImage;  ///< tone-mapped sRGB, every frame (frame_images.h makes the frame-size images)
    Image linearImage;   ///< only while frames ask for it (ViewRequest::linearOutput)
    /// Compositing layers, only while frames ask for them (kReadSky, kReadCloudLayer).
    Image skyImage, cloudLayerImage;
    /// The depth layer (kReadDepthLayer, kDrawDepthLayer): RG32F, R the cloud's front, G its weighted distance.
    Image depthLayerImage;
    // 1x1 images bound where a pass has nothing to read or write (every binding needs an image): the
    // optional outputs when none is asked for, the history in full-resolution frames.
    Image linearStandIn, depthStandIn, depthLayerStandIn;
    CloudHistoryImages historyStandIn;
};

/// Loads the program and makes the stand-ins (layout GENERAL); the frame-size images come with the first frame.
SkyStatus createCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass);
void destroyCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass);

/// The images the composite reads and writes. Each optional output is the frame's image while a reader
/// asks for it (its FRAME_FLAG_* set), else a 1x1 stand-in the shader does not write.
struct CompositeImages
{
    const Image* cloud = nullptr;    ///< the march's cloud image (block resolution in reprojected frames)
    const Image* depth = nullptr;    ///< ... and its depth
    const CloudHistoryImages* history = nullptr;  ///< of the pixels not marched (stand-in: full frames)
    const Image* linear = nullptr;   ///< linear frame (FRAME_FLAG_NO_LINEAR_OUTPUT clear)
    const Image* sky = nullptr;      ///< FRAME_FLAG_SKY_LAYER
    const Image* cloudLayer = nullptr;  ///< FRAME_FLAG_CLOUD_LAYER
    const Image* cloudOut = nullptr;    ///< FRAME_FLAG_WRITE_CLOUD: the full-resolution cloud image...
    const Image* depthOut = nullptr;    ///< ... and depth of a reprojected frame
    const Image* front = nullptr;         ///< FRAME_FLAG_DEPTH_LAYER: the march's fronts (as `depth`)...
    const Image* frontHistory = nullptr;  ///< ... the front history of the pixels not marched...
    const Image* depthLayer = nullptr;    ///< ... and the layer written
};

/// Records the composite pass (sky + clouds + aerial perspective -> display image and the outputs asked for).
void recordComposite(Renderer& r, VkCommandBuffer cmd, const ViewRequest& request, const CompositeImages& images);

}  // namespace sky
