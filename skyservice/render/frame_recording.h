// SPDX-License-Identifier: MIT
// The frame function: the one place that wires one pass's outputs to the next one's inputs. It makes the
// passes' images for a frame (each pass makes its own), records the passes into the frame context's command
// buffer with their declared inputs, queues the copies of the images a reader asked for into its readback
// buffer, and, once its fence has signalled, collects the timestamps and pixels.
//
//   images made this frame: UNDEFINED -> GENERAL (pass_images.h)
//   atmosphere     sun, moon, eye altitude          -> transmittance, sky-view and aerial LUTs
//   light volume   weather window, noise             -> light volume (+ far cascade)
//   march          window, column bounds, noise, transmittance LUT, light volume
//                                                    -> cloud, depth, front (full frame) or fresh pixels (reprojected)
//   reconstruct    fresh pixels, history[current]    -> history[current ^ 1]           (reprojected only)
//   composite      LUTs, cloud, depth, history, fronts -> display (+ linear, sky, cloud, depth layers,
//                                                       full-resolution cloud image of a reprojected frame)
//   shadow map     weather window, noise             -> shadow map, its transmittance   (when asked for)
#pragma once

#include "skyservice/render/composite_pass.h"
#include "skyservice/render/frame_context.h"
#include "skyservice/render/frame_outputs.h"
#include "skyservice/render/frame_setup.h"
#include "skyservice/render/frame_timestamps.h"
#include "skyservice/render/renderer.h"

namespace sky
{

/// Makes, resizes and lets go the passes' images for the frame being prepared (without idling the
/// queue: pass_images.h). The march block (reconstruct.reprojection.block) must be chosen first.
SkyStatus prepareFrameImages(Renderer& r, const ViewRequest& request, const QualitySettings& quality,
                             const FrameOutputs& outputs);

/// Bytes of the readback buffer the frame needs (its images must exist: after prepareFrameImages).
VkDeviceSize frameReadbackBytes(const Renderer& r, const ViewRequest& request);

/// What every pass of the frame being recorded in `frame` reads besides its own inputs.
PassFrame passFrame(const Renderer& r, const FrameContext& frame);

/// The composite's inputs: a reprojected frame's (fresh pixels and history), or a full frame's. The
/// reference renderer composites its path-traced clouds with a full frame's.
CompositeInputs compositeInputs(const Renderer& r, const FrameOutputs& outputs, bool reprojected);

/// Records one frame into `frame.cmd` (`params`: what its frame uniforms hold): the images made for it,
/// sky-view LUT, light volume, cloud march, reconstruct, composite; queues the readback of the asked-for
/// images (recordReadbacks then records the copies after the frame's last pass). Sets facts.marchRowOrder.
void recordFrame(Renderer& r, FrameContext& frame, const ViewRequest& request, const CameraFrame& camera,
                 const SunMoon& sunMoon, const FrameInputs& in, const FrameParams& params, FrameReadbackPlan& plan,
                 RenderResult& facts);

/// Records the shadow map of the frame after its passes (shadow_map.h recordShadowMap).
void recordFrameShadowMap(Renderer& r, FrameContext& frame, const ViewRequest& request, const QualitySettings& quality,
                          const CameraFrame& camera, const SunMoon& sunMoon, ShadowMapReadback& readback,
                          RenderResult& facts);

/// After the frame's fence: the GPU times, the march's row lookups and the images of `plan` into `result`.
void collectFrame(Renderer& r, const FrameContext& frame, const ViewRequest& request, bool reprojected,
                  bool lightVolume, const FrameReadbackPlan& plan, RenderResult& result);

}  // namespace sky
