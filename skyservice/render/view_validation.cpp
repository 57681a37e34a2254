// SPDX-License-Identifier: MIT
#include "skyservice/render/view_validation.h"

#include "skyservice/render/view_frustum.h"

namespace sky
{

bool validateView(const ViewRequest& view, std::string& error)
{
    if (!validateEyePose(view.pose, error))
        return false;
    if (view.width < kMinViewSizePx || view.height < kMinViewSizePx || view.width > kMaxViewSizePx ||
        view.height > kMaxViewSizePx)
    {
        error = "image size " + std::to_string(view.width) + "x" + std::to_string(view.height) + " outside " +
                std::to_string(kMinViewSizePx) + ".." + std::to_string(kMaxViewSizePx);
        return false;
    }
    if (view.frustum.asymmetric)
        return validateFrustum(view.frustum, error);
    if (!fovYInRange(view.fovYDeg))
    {
        error = "vertical field of view " + std::to_string(view.fovYDeg) + " outside [" +
                std::to_string(int(kMinFovYDeg)) + ", " + std::to_string(int(kMaxFovYDeg)) + "] degrees";
        return false;
    }
    error.clear();
    return true;
}

}  // namespace sky
