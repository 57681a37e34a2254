// SPDX-License-Identifier: MIT
// The frame-size images of a renderer: made on the first frame of a size, resized with the request.
#pragma once

#include "skyservice/render/frame_recording.h"
#include "skyservice/render/renderer.h"

namespace sky
{

// The full-resolution images of a frame: display always; linear, the sky layer and the cloud layer only
// while frames ask for them (made when asked for, let go at the first frame that does not ask); the cloud
// radiance and depth for full-resolution frames, and for reprojected frames whose reader asks for them
// (the composite then writes them from the fresh pixels and the history). A renderer that has made
// them keeps them.
SkyStatus ensureOutputImages(Renderer& r, uint32_t width, uint32_t height, const FrameOutputs& outputs,
                             bool reprojected);

// Destroys `image` once the frames in flight that may use it are done (the newest frame context's
// deletion queue); `image` is empty on return.
void deferDestroy(Renderer& r, Image& image);

// The reprojection images: the two full-resolution cloud histories (cloud_history_images.h) and the fresh pixels at the
// resolution of the block in use (`blockPx`). The fresh images follow the block (finer near and inside
// clouds, back to 1/16 after) and are replaced without touching the history, so that flying into and
// out of a cloud (block 4 -> 2 -> 1 -> 2 -> 4) keeps the history. With `front` (the frame draws the depth
// layer) also the fronts' fresh image and history (made cleared; let go when a frame does not draw it).
SkyStatus ensureReprojectionImages(Renderer& r, uint32_t width, uint32_t height, uint32_t blockPx, bool front);

}  // namespace sky
