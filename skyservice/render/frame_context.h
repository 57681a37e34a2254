// SPDX-License-Identifier: MIT
// The per-frame Vulkan objects of the renderer, one set per frame in flight, made once and reused:
// a command pool and buffer, a fence, the timestamp queries, the uniform buffers the frame's passes
// read (the CPU writes the next frame's while the GPU reads this one's), the host-cached buffer the
// frame's images are copied into, and a deletion queue of what the frame was the last to use.
//
// A frame: beginFrameCommands (waits for the context's previous frame, frees its deletion queue, resets
// the pool) -> record -> submitFrameCommands -> ... -> waitFrameCommands -> read `readback`.
// Nothing on that path allocates, creates a pool, or waits for the whole queue; the readback buffer
// grows only when a frame asks for more bytes than any before it.
#pragma once

#include "skyservice/vk/resources.h"

#include <functional>
#include <vector>

namespace sky
{

/// Frames the renderer keeps in flight: the CPU prepares and records one while the GPU runs the other.
constexpr uint32_t kFramesInFlight = 2;

/// Where one image of the frame lies in FrameContext::readback.
struct ReadbackRegion
{
    VkDeviceSize offset = 0;
    VkDeviceSize bytes = 0;  ///< the image's bytes (tightly packed rows); 0: not read back this frame
};

/// Where a recorded frame's images lie in its readback buffer (bytes 0: not read back).
struct FrameReadbackPlan
{
    ReadbackRegion display, cloud, depth, linear, sky, cloudLayer, depthLayer;
};

struct FrameContext
{
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkQueryPool timestamps = VK_NULL_HANDLE;  ///< kFrameTimestampSlots queries
    Buffer frameUniforms;       ///< FrameParams (shaders/shared/frame_params.h)
    Buffer atmosphereUniforms;  ///< AtmosphereParams (shaders/shared/atmosphere_params.h)
    Buffer readback;            ///< MemoryUse::HostReadback: the images this frame copies back
    VkDeviceSize readbackUsed = 0;  ///< bytes handed out by addImageReadback since beginFrameCommands
    /// Images queued by addImageReadback, copied by recordReadbacks.
    std::vector<std::pair<const Image*, VkDeviceSize>> readbackQueue;
    /// The shadow map (ShadowMapDrawing::id) whose transmittance `readback` holds at shadowMapHeldOffset
    /// (0: none). A reused map is not copied again: frames reserve its region at the same place first.
    uint64_t shadowMapIdHeld = 0;
    VkDeviceSize shadowMapHeldOffset = 0;
    bool submitted = false;     ///< its fence will signal (wait before reuse)
    /// Objects this frame was the last to use, freed once its fence has signalled.
    std::vector<std::function<void()>> deletions;
};

/// Timestamp queries per frame: the main passes and the shadow map (frame_recording.h, shadow_map.cpp).
constexpr uint32_t kFrameTimestampSlots = 8;

/// Makes the context's objects (`index` names them). On failure the context is left empty.
SkyStatus createFrameContext(const Context& ctx, MemoryTracker& memory, FrameContext& frame, uint32_t index);
/// Waits for the context's frame (if any), runs its deletion queue, destroys everything.
void destroyFrameContext(const Context& ctx, MemoryTracker& memory, FrameContext& frame);

/// Waits for the context's previous frame, runs its deletion queue, resets its command pool and begins
/// its command buffer. `readbackBytes`: the bytes this frame will copy back (the buffer grows to fit).
SkyStatus beginFrameCommands(const Context& ctx, MemoryTracker& memory, FrameContext& frame,
                             VkDeviceSize readbackBytes);
/// Ends and submits the command buffer with the context's fence.
SkyStatus submitFrameCommands(const Context& ctx, FrameContext& frame);
/// Waits for the submitted frame and makes its readback visible to the CPU. A no-op when none is pending.
SkyStatus waitFrameCommands(const Context& ctx, FrameContext& frame);

/// Reserves room for `image` (layer 0, GENERAL layout) in the readback buffer (16-byte aligned) and queues
/// its copy for recordReadbacks.
ReadbackRegion addImageReadback(FrameContext& frame, const Image& image);
/// The two halves of addImageReadback: room reserved now, the copy queued later (or not at all, when the
/// region still holds what the copy would write).
ReadbackRegion reserveImageReadback(FrameContext& frame, const Image& image);
void queueImageReadback(FrameContext& frame, const Image& image, const ReadbackRegion& region);
/// Records the queued copies (one barrier into TRANSFER_SRC for all, the copies, one barrier back to
/// GENERAL) and the barrier that makes them visible to the host. After the frame's last pass.
void recordReadbacks(FrameContext& frame);

/// Bytes an image occupies in a readback buffer (16-byte aligned).
VkDeviceSize readbackBytes(const Image& image);

}  // namespace sky
