// SPDX-License-Identifier: MIT
#include "skyservice/render/window_upload.h"

#include "skyservice/render/reprojection.h"

namespace sky
{

SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality)
{
    const auto now = std::chrono::steady_clock::now();
    RendererWeather& w = r.weather;
    WindowKey key{w.version, windowCentreForEye(camera.eye.latDeg, camera.eye.lonDeg),
                  quality.windowHalfExtentM, quality.windowWarpRadiusM};
    // A staged weather whose window for this node is ready replaces the current one from this frame on
    // (with nothing drawn yet, this frame waits for it: there is no old weather to keep drawing).
    if (std::optional<StagedResult> staged = advanceStage(w.stage, w.worker, key, !w.snapshot))
    {
        w.snapshot = staged->weather;
        w.version = staged->version;
        w.window = staged->window;
        w.windowOnGpu = false;
        if (!staged->keepHistory)
            dropHistory(r);  // the previous frame shows other clouds (a small step's still matches them)
        key.weatherVersion = w.version;
    }
    if (!w.snapshot)
    {
        setWeather(r, WeatherSnapshot{});  // no weather given (or the staged one was refused): an empty sky
        key.weatherVersion = w.version;
    }
    if (!w.window || !(w.window->key == key))
    {
        w.window = takeWindow(w.prefetch, w.snapshot, key);
        w.windowOnGpu = false;
    }
    if (!w.windowOnGpu)  // stays false if the upload fails: the next frame uploads again
    {
        // Both images in one submit: a window made on the frame path (first frame, a jump, a prefetch that
        // missed) waits for the GPU once.
        const std::vector<uint16_t>& texels = w.window->gpuTexelsHalf;
        const std::vector<uint8_t>& bounds = w.window->columnBounds;
        SKY_TRY(uploadImages(r.ctx, r.memory,
                             {ImageUpload{&w.windowImage, texels.data(), texels.size() * sizeof(uint16_t),
                                          VK_IMAGE_LAYOUT_GENERAL},
                              ImageUpload{&w.columnBoundsImage, bounds.data(), bounds.size(), VK_IMAGE_LAYOUT_GENERAL}}));
        w.windowOnGpu = true;
    }
    // The next node: the first one along the eye's horizontal motion, prefetched once it is within the
    // look-ahead (1.5 s of motion at the eye's speed, window_provider.h). The speed comes from real time
    // between frames; it only says when a window is made, never what is drawn.
    glm::dvec3 moveEnu = glm::transpose(camera.enuToEcef) * (camera.eyeEcefM - w.lastEyeEcefM);
    const bool hadFrame = w.lastFrameClock != std::chrono::steady_clock::time_point{};
    const double dtS = std::chrono::duration<double>(now - w.lastFrameClock).count();
    w.lastEyeEcefM = camera.eyeEcefM;
    w.lastFrameClock = now;
    double moveM = glm::length(glm::dvec2(moveEnu));
    if (!hadFrame || moveM >= kReprojectionMaxMoveM)
        w.eyeSpeedMps = 0;  // a jump, not a flight
    else
        w.eyeSpeedMps = updateEyeSpeedMps(w.eyeSpeedMps, moveM, dtS);
    if (hadFrame && moveM > 1e-3 && moveM < kReprojectionMaxMoveM)
    {
        if (std::optional<WindowCentre> next =
                nextWindowNode(camera, glm::dvec2(moveEnu), windowLookAheadM(w.eyeSpeedMps)))
        {
            WindowKey nextKey = key;
            nextKey.centre = *next;
            prefetchWindow(w.prefetch, w.worker, w.snapshot, nextKey);
        }
    }
    return SkyStatus::success();
}

}  // namespace sky
