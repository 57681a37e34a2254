// SPDX-License-Identifier: MIT
// The composite pass (shaders/composite/composite.comp.glsl): sky, clouds and aerial perspective into
// the display image, and the optional outputs a reader asks for (linear frame, sky and cloud layers, the
// depth layer, the full-resolution cloud image of a reprojected frame). Its program and every image it
// owns: the display image and the optional outputs, each made only while frames ask for it.
#pragma once

#include "skyservice/render/cloud_history_images.h"
#include "skyservice/render/frame_outputs.h"
#include "skyservice/render/pass_frame.h"
#include "skyservice/render/pass_images.h"
#include "skyservice/render/stand_in_images.h"
#include "skyservice/vk/programs.h"

namespace sky
{

struct AtmospherePass;

struct CompositePass
{
    Program program;
    Image displayImage;  ///< tone-mapped sRGB, every frame
    Image linearImage;   ///< only while frames ask for it (FrameOutputs::linearImage)
    /// Compositing layers, only while frames ask for them (FrameOutputs::sky, cloudLayer).
    Image skyImage, cloudLayerImage;
    /// The depth layer (FrameOutputs::depthLayer): RG32F, R the cloud's front, G its weighted distance.
    Image depthLayerImage;
};

/// What the composite reads, and the images of other passes it writes into.
struct CompositeInputs
{
    const AtmospherePass& atmosphere;  ///< its transmittance, sky-view and aerial-perspective LUTs
    const Image& cloud;    ///< the march's cloud image (block resolution in reprojected frames)
    const Image& depth;    ///< ... and its depth
    const CloudHistoryImages& history;  ///< of the pixels not marched (stand-in: full frames)
    const Image& front;         ///< the march's fronts (as `depth`; stand-in without a depth layer)...
    const Image& frontHistory;  ///< ... and the front history of the pixels not marched
    /// FRAME_FLAG_WRITE_CLOUD: the full-resolution cloud image and depth of a reprojected frame (the
    /// march's), else stand-ins.
    const Image& cloudOut;
    const Image& depthOut;
    const StandInImages& standIns;  ///< bound for the outputs no reader asks for
    FrameOutputs outputs;           ///< which of the composite's own outputs the frame writes
};

/// Loads the program; the frame-size images come with the first frame.
SkyStatus createCompositePass(const Context& ctx, CompositePass& pass);
void destroyCompositePass(const Context& ctx, MemoryTracker& memory, CompositePass& pass);

/// Makes the display image for a width x height frame and the optional outputs `outputs` asks for; lets
/// go those it no longer asks for (pass_images.h: no queue idles).
SkyStatus ensureCompositeImages(CompositePass& pass, ImageChanges& changes, uint32_t width, uint32_t height,
                                const FrameOutputs& outputs);

/// Records the composite pass (sky + clouds + aerial perspective -> display image and the outputs asked for).
void recordComposite(const PassFrame& f, const CompositePass& pass, const CompositeInputs& in, uint32_t width,
                     uint32_t height);

}  // namespace sky
