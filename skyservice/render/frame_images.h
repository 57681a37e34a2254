// SPDX-License-Identifier: MIT
// The frame-size images of a renderer: made on the first frame of a size, resized with the request.
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

// The full-resolution images of a frame: linear and display always; the cloud radiance and depth only
// for full-resolution frames (`cloudImages`): a reprojected frame's cloud image is the history image
// its reconstruct pass writes, which the composite and the readback take directly (25 MiB less at
// 1080p). A renderer that has made full frames keeps their cloud images.
SkyStatus ensureOutputImages(Renderer& r, uint32_t width, uint32_t height, bool cloudImages);

// The reprojection images: block-resolution fresh pixels and the two full-resolution histories. The
// fresh images only grow (to the finest block used so far) and are replaced without touching history,
// so that flying into a cloud (block 4 -> 2 -> 1) keeps the history.
SkyStatus ensureReprojectionImages(Renderer& r, uint32_t width, uint32_t height, uint32_t blockPx);

}  // namespace sky
