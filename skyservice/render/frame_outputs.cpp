// SPDX-License-Identifier: MIT
#include "skyservice/render/frame_outputs.h"

namespace sky
{

FrameOutputs FrameOutputs::of(const ViewRequest& request)
{
    FrameOutputs o;
    o.linearImage = request.linearOutput;
    const uint32_t bits = request.readback;
    // Layers kept on the GPU for the export are drawn even when nothing is read back (sky-bench).
    o.sky = (bits & kDrawSky) != 0;
    o.cloudLayer = (bits & kDrawCloudLayer) != 0;
    o.depthLayer = (bits & kDrawDepthLayer) != 0;
    if (!request.copyToHost)
        return o;
    o.display = (bits & kReadDisplay) != 0;
    o.cloud = (bits & kReadCloud) != 0;
    o.depth = (bits & kReadDepth) != 0;
    o.readSky = (bits & kReadSky) != 0;
    o.readCloudLayer = (bits & kReadCloudLayer) != 0;
    o.readDepthLayer = (bits & kReadDepthLayer) != 0;
    o.sky = o.sky || o.readSky;
    o.cloudLayer = o.cloudLayer || o.readCloudLayer;
    o.depthLayer = o.depthLayer || o.readDepthLayer;
    o.shadowDetail = (bits & kReadShadowDetail) != 0;
    o.linear = request.linearOutput;
    return o;
}

}  // namespace sky
