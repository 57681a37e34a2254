// SPDX-License-Identifier: MIT
// The frame-size images of a pass are made, resized and let go by that pass, on the frame path and
// without idling the queue: an image replaced or no longer needed goes to the deletion queue of the
// newest frame in flight (freed once its fence has signalled, when no frame can read it), and an image
// made is moved to the GENERAL layout (and cleared where asked) at the top of the next frame's command
// buffer, not by a submit of its own that the CPU would wait for.
#pragma once

#include "skyservice/vk/resources.h"

#include <functional>
#include <vector>

namespace sky
{

/// An image made since the last frame was recorded: its first frame moves it to GENERAL.
struct NewImage
{
    VkImage image = VK_NULL_HANDLE;
    bool cleared = false;  ///< filled with zeros as well
};

/// What a pass changes its images through while a frame is prepared.
struct ImageChanges
{
    const Context& ctx;
    MemoryTracker& memory;
    /// The deletion queue of the newest frame submitted and not yet collected (null when none is in
    /// flight: a retired image is destroyed at once).
    std::vector<std::function<void()>>* inFlightDeletions;
    /// Images made and not yet initialized by a recorded frame (recordNewImages).
    std::vector<NewImage>& newImages;
};

bool hasSize(const Image& image, uint32_t width, uint32_t height);

/// Makes `image` from `desc` (an image it held is retired first) and queues its initialization.
SkyStatus makeImage(ImageChanges& changes, Image& image, const ImageDesc& desc, const char* name,
                    bool cleared = false);
/// Lets `image` go once no frame in flight can read it; `image` is empty on return.
void retireImage(ImageChanges& changes, Image& image);

/// Records the initialization of the images made (UNDEFINED -> GENERAL, zeros where asked), then a
/// barrier. The caller forgets them once the frame is submitted (a frame that fails records them again).
void recordNewImages(VkCommandBuffer cmd, const std::vector<NewImage>& images);

}  // namespace sky
