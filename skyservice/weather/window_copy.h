// SPDX-License-Identifier: MIT
// The second pair of weather-window images and the copy into them, which runs while frames go on drawing
// the first pair (renderer_weather.h): a new window never goes into an image that a frame in flight reads,
// and the frame thread does not wait for the copy. Frames swap the pair in once its fence has signalled
// (window_upload.h decides when).
//
// The copy is submitted on the frame queue after the frames that last read these images: its first
// barrier orders the writes after their reads on the GPU, so the CPU need not wait for them. Its last
// barrier makes the texels visible to every frame submitted after it.
#pragma once

#include "skyservice/weather/window_provider.h"
#include "skyservice/vk/resources.h"

#include <memory>

namespace sky
{

struct WindowCopy
{
    Image windowImage;        ///< the back window slices (shaders/shared/weather_window.h)
    Image columnBoundsImage;  ///< the back column-bounds pyramid (shaders/shared/column_bounds.h)
    /// The window these images hold, or are being filled with (null: none, or the copy failed).
    std::shared_ptr<const PreparedWindow> window;
    bool inFlight = false;    ///< the copy of `window` was submitted and its fence has not been seen signalled
    Buffer staging;           ///< the bytes of the copy (host-visible; reused, grown when a window needs more)
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

/// Makes the back images like `windowImage` and `columnBoundsImage` (descs), the command buffer and fence.
SkyStatus createWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy, const ImageDesc& windowDesc,
                           const ImageDesc& columnBoundsDesc);
/// Waits for a copy in flight, then destroys everything.
void destroyWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy);

/// Records and submits the copy of `window` into the back images, and returns without waiting. The
/// previous copy must be done (windowCopyDone).
SkyStatus startWindowCopy(const Context& ctx, MemoryTracker& memory, WindowCopy& copy,
                          std::shared_ptr<const PreparedWindow> window);
/// True when no copy is in flight any more (polls the fence, never waits).
bool windowCopyDone(const Context& ctx, WindowCopy& copy);
/// Waits for the copy in flight (for a frame that has no other window to draw).
SkyStatus waitWindowCopy(const Context& ctx, WindowCopy& copy);

}  // namespace sky
