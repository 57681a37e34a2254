// SPDX-License-Identifier: MIT
// One frame's cloud history of reprojected frames (shaders/lib/cloud_history.glsl): premultiplied
// radiance, alpha and depth in two 32-bit images, 8 bytes a texel. Shaders write them as plain bits
// through R32_UINT storage views and read them through sampled views in formats the texture unit decodes
// and filters (E5B9G9R9 radiance; R16G16_UNORM alpha and depth code).
#pragma once

#include "skyservice/vk/resources.h"

namespace sky
{

struct CloudHistoryImages
{
    Image colour;      ///< premultiplied radiance: R32_UINT storage, E5B9G9R9_UFLOAT_PACK32 sampled
    Image alphaDepth;  ///< alpha and the depth's log code: R32_UINT storage, R16G16_UNORM sampled
};

/// The descriptions of a width x height history's images (made with createImage, or Renderer helpers).
ImageDesc cloudHistoryColourDesc(uint32_t width, uint32_t height);
ImageDesc cloudHistoryAlphaDepthDesc(uint32_t width, uint32_t height);

}  // namespace sky
