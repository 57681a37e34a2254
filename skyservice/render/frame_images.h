// SPDX-License-Identifier: MIT
// The frame-size images of a renderer: made on the first frame of a size, resized with the request.
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

// The full-resolution images of a frame: display always; linear only while frames ask for it (`linear`:
// made when asked for, destroyed at the first frame that does not ask); the cloud radiance and depth
// only for full-resolution frames (`cloudImages`): a reprojected frame's cloud image is its fresh
// pixels and the packed history the reconstruct pass writes, which the composite and the readback
// take directly. A renderer that has made full frames keeps their cloud images.
SkyStatus ensureOutputImages(Renderer& r, uint32_t width, uint32_t height, bool cloudImages, bool linear);

// The reprojection images: the two full-resolution packed histories and the fresh pixels at the
// resolution of the block in use (`blockPx`). The fresh images follow the block (finer near and inside
// clouds, back to 1/16 after) and are replaced without touching the history, so that flying into and
// out of a cloud (block 4 -> 2 -> 1 -> 2 -> 4) keeps the history.
SkyStatus ensureReprojectionImages(Renderer& r, uint32_t width, uint32_t height, uint32_t blockPx);

}  // namespace sky
