// SPDX-License-Identifier: MIT
// The copy of a new weather window into the images frames read (renderer_weather.h), without the frame
// thread waiting for it and without a second pair of images (which would cost the 1080p device-memory
// budget another 4.4 MB, tests/gpu/test_memory.cpp).
//
// The copy is submitted on the frame queue between two frames. Its first barrier (source scope: all
// commands) orders its writes after the reads of the frames submitted before it, which draw the old
// window; its last barrier makes the texels visible to every frame submitted after it, which draw the new
// one. So the frame that wants a new window draws it at once, with no CPU wait, and its picture is the
// one a one-shot render of the same view makes. The staging buffer is kept (reallocating it per window
// fragments the host heap) and counted as host memory (MemoryUse::HostStaging).
#pragma once

#include "skyservice/weather/window_provider.h"
#include "skyservice/vk/resources.h"

#include <memory>

namespace sky
{

struct WindowCopy
{
    bool inFlight = false;    ///< a copy was submitted and its fence has not been seen signalled
    Buffer staging;           ///< the bytes of the copy (host memory; reused, grown when a window needs more)
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

/// Makes the command buffer and fence.
SkyStatus createWindowCopy(const Context& ctx, WindowCopy& copy);
/// Waits for a copy in flight, then destroys everything.
void destroyWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy);

/// Records and submits the copy of `window` into `windowImage` and `columnBoundsImage`, and returns
/// without waiting. The previous copy must be done (windowCopyDone).
SkyStatus startWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy, const PreparedWindow& window,
                          const Image& windowImage, const Image& columnBoundsImage);
/// True when no copy is in flight any more (polls the fence, never waits).
bool windowCopyDone(const Context& ctx, WindowCopy& copy);
/// Waits for the copy in flight (before the next copy reuses the command buffer).
SkyStatus waitWindowCopy(const Context& ctx, WindowCopy& copy);

}  // namespace sky
