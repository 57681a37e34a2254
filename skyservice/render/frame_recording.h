// SPDX-License-Identifier: MIT
// One GPU frame: the passes recorded into the frame context's command buffer, the copies of the images a
// reader asked for into its readback buffer, and, once its fence has signalled, the timestamps and pixels.
#pragma once

#include "skyservice/render/frame_context.h"
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/renderer.h"

namespace sky
{

// Timestamp slots: one before the frame and one after each pass; two around the shadow map.
enum TimestampSlot : uint32_t
{
    kTsStart,
    kTsSkyView,
    kTsLightVolume,  ///< after the light volume (written right after kTsSkyView when there is none)
    kTsClouds,  ///< after the march (full or 1/16)
    kTsReconstruct,  ///< after the reconstruct pass (written right after kTsClouds in full mode)
    kTsComposite,
    kTsShadowBegin,
    kTsShadowEnd,
    kTsCount
};
static_assert(kTsCount <= kFrameTimestampSlots, "frame_context.h: kFrameTimestampSlots");

/// What the composite writes and the readback copies for `request` (its readback bits, its linearOutput
/// and copyToHost switches).
struct FrameOutputs
{
    bool display = false, cloud = false, depth = false, linear = false;
    /// Compositing layers drawn (read back, or only kept on the GPU for the zero-copy export)...
    bool sky = false, cloudLayer = false, depthLayer = false;
    /// ... and read back.
    bool readSky = false, readCloudLayer = false, readDepthLayer = false;
    bool shadowDetail = false;
    bool linearImage = false;  ///< the composite writes the linear frame (even when not read back)

    static FrameOutputs of(const ViewRequest& request);
};

/// Bytes of the readback buffer the frame needs (its images must exist: after ensureOutputImages etc.).
VkDeviceSize frameReadbackBytes(const Renderer& r, const ViewRequest& request);

/// Records one frame into `frame.cmd` (`params`: what its frame uniforms hold): sky-view LUT, light volume,
/// cloud march, reconstruct, composite; queues the readback of the asked-for images (recordReadbacks then
/// records the copies after the frame's last pass). Sets facts.marchRowOrder.
void recordFrame(Renderer& r, FrameContext& frame, const ViewRequest& request, const CameraFrame& camera,
                 const SunMoon& sunMoon, const FrameInputs& in, const FrameParams& params, FrameReadbackPlan& plan,
                 RenderResult& facts);

/// After the frame's fence: the GPU times, the march's row lookups and the images of `plan` into `result`.
void collectFrame(Renderer& r, const FrameContext& frame, const ViewRequest& request, bool reprojected,
                  bool lightVolume, const FrameReadbackPlan& plan, RenderResult& result);

}  // namespace sky
