// SPDX-License-Identifier: MIT
#include "skyservice/service/shm_view.h"

#include "skyservice/render/view_frustum.h"

#include <cmath>

namespace sky
{

SkyShmView shmViewOf(const ViewRequest& request)
{
    SkyShmView v{};
    const double lon = std::fmod(request.pose.lonDeg + 180.0, 360.0);
    v.lat_deg = request.pose.latDeg;
    v.lon_deg = (lon < 0 ? lon + 360.0 : lon) - 180.0;
    v.alt_m = request.pose.altitudeM;
    v.heading_deg = request.pose.headingDeg;
    v.pitch_deg = request.pose.pitchDeg;
    v.roll_deg = request.pose.rollDeg;
    v.fov_deg = verticalExtentDeg(request);
    v.width = request.width;
    v.height = request.height;
    if (request.frustum.asymmetric)
    {
        v.asymmetric = 1;
        v.left_deg = request.frustum.leftDeg;
        v.right_deg = request.frustum.rightDeg;
        v.up_deg = request.frustum.upDeg;
        v.down_deg = request.frustum.downDeg;
    }
    return v;
}

}  // namespace sky
