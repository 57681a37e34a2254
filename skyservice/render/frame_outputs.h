// SPDX-License-Identifier: MIT
// What a frame draws and reads back beyond the display image: from the request's readback bits
// (render_types.h kRead* / kDraw*) and its linearOutput and copyToHost switches.
#pragma once

#include "skyservice/render/render_types.h"

namespace sky
{

struct FrameOutputs
{
    bool display = false, cloud = false, depth = false, linear = false;
    /// Compositing layers drawn (read back, or only kept on the GPU for the zero-copy export)...
    bool sky = false, cloudLayer = false, depthLayer = false;
    /// ... and read back.
    bool readSky = false, readCloudLayer = false, readDepthLayer = false;
    bool shadowDetail = false;
    bool linearImage = false;  ///< the composite writes the linear frame (even when not read back)

    static FrameOutputs of(const ViewRequest& request);
};

}  // namespace sky
