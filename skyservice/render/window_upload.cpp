// SPDX-License-Identifier: MIT
#include "skyservice/render/window_upload.h"

#include "skyservice/render/reprojection.h"

namespace sky
{

namespace
{

/// Puts `window` into the images frames read: the copy is ordered on the GPU between the frames before
/// and after it (window_copy.h), so this frame draws it without the CPU waiting, unless the previous copy
/// still holds the command buffer.
SkyStatus showWindow(Renderer& r, std::shared_ptr<const PreparedWindow> window)
{
    RendererWeather& w = r.weather;
    if (!windowCopyDone(r.ctx, w.copy))
    {
        ++w.windowCopiesWaited;
        SKY_TRY(waitWindowCopy(r.ctx, w.copy));
    }
    w.window.reset();  // until the copy is submitted, the images hold nothing usable
    SKY_TRY(startWindowCopy(r.ctx, r.memory, w.copy, *window, w.windowImage, w.columnBoundsImage));
    w.window = std::move(window);
    return SkyStatus::success();
}

}  // namespace

SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality)
{
    const auto now = std::chrono::steady_clock::now();
    RendererWeather& w = r.weather;
    WindowKey key;  // its weather part is set once this frame's snapshot is known
    key.centre = windowCentreForEye(camera.eye.latDeg, camera.eye.lonDeg);
    key.halfExtentM = quality.windowHalfExtentM;
    key.warpRadiusM = quality.windowWarpRadiusM;
    // A staged weather whose window for this node is ready replaces the current one from this frame on
    // (with nothing drawn yet, this frame waits for it: there is no old weather to keep drawing).
    std::shared_ptr<const PreparedWindow> wanted;  // the window to draw when it is not on the GPU yet
    if (std::optional<StagedResult> staged = advanceStage(w.stage, w.worker, key, !w.snapshot))
    {
        w.snapshot = staged->weather;
        w.version = staged->version;
        wanted = staged->window;
        if (!staged->keepHistory)
            dropHistory(r);  // the previous frame shows other clouds (a small step's still matches them)
    }
    if (!w.snapshot)
        setWeather(r, WeatherSnapshot{});  // no weather given (or the staged one was refused): an empty sky
    key.weatherVersion = w.version;
    key.weatherValidTimeUnixS = w.snapshot->validTimeUnixS;
    const glm::dvec3 moveEnu = glm::transpose(camera.enuToEcef) * (camera.eyeEcefM - w.lastEyeEcefM);
    const double moveM = glm::length(glm::dvec2(moveEnu));
    const bool hadFrame = w.lastFrameClock != std::chrono::steady_clock::time_point{};
    if (wanted && !(wanted->key == key))
        wanted.reset();
    if (!wanted && !(w.window && w.window->key == key))
        wanted = takeWindow(w.prefetch, w.snapshot, key);
    if (wanted)
        SKY_TRY(showWindow(r, std::move(wanted)));
    // The next node: the first one along the eye's horizontal motion, prefetched once it is within the
    // look-ahead (1.5 s of motion at the eye's speed, window_provider.h). The speed comes from real time
    // between frames; it only says when a window is made, never what is drawn.
    const double dtS = std::chrono::duration<double>(now - w.lastFrameClock).count();
    w.lastEyeEcefM = camera.eyeEcefM;
    w.lastFrameClock = now;
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
