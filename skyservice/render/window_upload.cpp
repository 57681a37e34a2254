// SPDX-License-Identifier: MIT
#include "skyservice/render/window_upload.h"

#include "skyservice/render/reprojection.h"

namespace sky
{

SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality)
{
    WindowKey key{r.weatherVersion, windowCentreForEye(camera.eye.latDeg, camera.eye.lonDeg),
                  quality.windowHalfExtentM, quality.windowWarpRadiusM};
    if (!r.window || !(r.window->key == key) || !r.windowOnGpu)
    {
        r.windowOnGpu = false;  // stays false if the upload fails
        r.window = takeWindow(r.windowPrefetch, r.weather, key);
        const std::vector<uint16_t>& texels = r.window->gpuTexelsHalf;
        SKY_TRY(uploadImage(r.ctx, r.memory, r.weatherWindowImage, texels.data(), texels.size() * sizeof(uint16_t),
                            VK_IMAGE_LAYOUT_GENERAL));
        r.windowOnGpu = true;
    }
    // The next node: the one under the point kWindowLookAheadM ahead along the eye's horizontal motion.
    glm::dvec3 moveEnu = glm::transpose(camera.enuToEcef) * (camera.eyeEcefM - r.lastEyeEcefM);
    r.lastEyeEcefM = camera.eyeEcefM;
    double moveM = glm::length(glm::dvec2(moveEnu));
    if (moveM > 1e-3 && moveM < kReprojectionMaxMoveM)
    {
        glm::dvec2 ahead = glm::dvec2(moveEnu) / moveM * kWindowLookAheadM;
        double latDeg = 0, lonDeg = 0, hM = 0;
        enuToGeodetic(camera, glm::dvec3(ahead, 0.0), latDeg, lonDeg, hM);
        WindowKey next = key;
        next.centre = windowCentreForEye(latDeg, lonDeg);
        if (!(next == key))
            prefetchWindow(r.windowPrefetch, r.weather, next);
    }
    return SkyStatus::success();
}

}  // namespace sky
