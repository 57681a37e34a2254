// SPDX-License-Identifier: MIT
// The timestamp queries of a frame (FrameContext::timestamps): one before the frame and one after each
// pass; two around the shadow map.
#pragma once

#include "skyservice/render/frame_context.h"

namespace sky
{

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

}  // namespace sky
