// SPDX-License-Identifier: MIT
// 1x1 images bound where a pass has nothing to read or write (every binding needs an image): the
// composite's optional outputs when no reader asks for them, the march's fronts and the reconstruct's
// front history when the frame draws no depth layer, the cloud history in full-resolution frames. No
// shader writes them (the frame flags tell each pass which of its bindings are stand-ins).
#pragma once

#include "skyservice/render/cloud_history_images.h"

namespace sky
{

struct StandInImages
{
    Image linear;      ///< RGBA16F: the linear frame, sky layer, cloud layer, cloud image
    Image depth;       ///< R32F: depths and fronts
    Image depthLayer;  ///< RG32F: the depth layer
    CloudHistoryImages history;
};

/// Makes the stand-ins (layout GENERAL).
SkyStatus createStandInImages(const Context& ctx, MemoryTracker& memory, StandInImages& standIns);
void destroyStandInImages(const Context& ctx, MemoryTracker& memory, StandInImages& standIns);

}  // namespace sky
