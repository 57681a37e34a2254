// SPDX-License-Identifier: MIT
// One GPU frame: the passes recorded into one command buffer, their timestamps, and the readback.
#pragma once

#include "skyservice/render/frame_setup.h"
#include "skyservice/render/renderer.h"

namespace sky
{

// Timestamp slots: one before the frame and one after each pass.
enum TimestampSlot : uint32_t
{
    kTsStart,
    kTsSkyView,
    kTsLightVolume,  ///< after the light volume (written right after kTsSkyView when there is none)
    kTsClouds,  ///< after the march (full or 1/16)
    kTsReconstruct,  ///< after the reconstruct pass (written right after kTsClouds in full mode)
    kTsComposite,
    kTsCount
};

// One frame on the GPU (`params`: what the frame uniforms hold): sky-view LUT, light volume, cloud march, composite, then the readback of every image.
SkyStatus renderOnce(Renderer& r, const ViewRequest& request, const CameraFrame& camera, const SunMoon& sunMoon,
                     const FrameInputs& in, const FrameParams& params, RenderResult& result);

}  // namespace sky
