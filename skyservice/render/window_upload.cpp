// SPDX-License-Identifier: MIT
#include "skyservice/render/window_upload.h"

#include "skyservice/render/reprojection.h"

namespace sky
{

namespace
{

/// The back images hold the wanted window now: they become the ones frames draw (the old ones become the
/// back pair, still holding the old window, so an eye turning back swaps without a copy).
void swapInBack(RendererWeather& w)
{
    std::swap(w.windowImage, w.back.windowImage);
    std::swap(w.columnBoundsImage, w.back.columnBoundsImage);
    std::swap(w.window, w.back.window);
    w.wanted.reset();
}

/// Puts `w.wanted` on screen: swapped in as soon as its copy into the back images is done. While the copy
/// runs, frames draw the current window when it is `usable` (the same weather, a flight from a neighbouring
/// cell); else (the first frame, a new weather, a jump) this frame waits for the copy.
SkyStatus showWantedWindow(Renderer& r, bool usable)
{
    RendererWeather& w = r.weather;
    if (w.wanted == w.window)
    {
        w.wanted.reset();
        return SkyStatus::success();
    }
    if (w.back.window != w.wanted)
    {
        if (!windowCopyDone(r.ctx, w.back))
        {
            if (usable)
                return SkyStatus::success();  // the back images are busy: a later frame copies this one
            ++w.windowCopiesWaited;
            SKY_TRY(waitWindowCopy(r.ctx, w.back));
        }
        SKY_TRY(startWindowCopy(r.ctx, r.memory, w.back, w.wanted));
    }
    if (!windowCopyDone(r.ctx, w.back))
    {
        if (usable)
            return SkyStatus::success();
        ++w.windowCopiesWaited;
        SKY_TRY(waitWindowCopy(r.ctx, w.back));
    }
    swapInBack(w);
    return SkyStatus::success();
}

/// A prefetched window whose job has finished goes into the back images ahead of the eye, so the frame
/// that enters its cell swaps it in at once: no copy to wait for, the same window a one-shot render makes.
SkyStatus copyFinishedPrefetch(Renderer& r)
{
    RendererWeather& w = r.weather;
    if (w.wanted || !windowCopyDone(r.ctx, w.back))
        return SkyStatus::success();  // the back images are taken
    std::shared_ptr<const PreparedWindow> next = takeFinishedWindow(w.prefetch);
    if (!next)
        return SkyStatus::success();
    w.backFromPrefetch = true;
    return startWindowCopy(r.ctx, r.memory, w.back, std::move(next));
}

}  // namespace

SkyStatus updateWeatherWindow(Renderer& r, const CameraFrame& camera, const QualitySettings& quality)
{
    const auto now = std::chrono::steady_clock::now();
    RendererWeather& w = r.weather;
    WindowKey key{w.version, windowCentreForEye(camera.eye.latDeg, camera.eye.lonDeg),
                  quality.windowHalfExtentM, quality.windowWarpRadiusM};
    // A staged weather whose window for this node is ready replaces the current one from this frame on
    // (with nothing drawn yet, this frame waits for it: there is no old weather to keep drawing).
    bool usable = true;  // the window drawn may stand in while the wanted one is copied
    if (std::optional<StagedResult> staged = advanceStage(w.stage, w.worker, key, !w.snapshot))
    {
        w.snapshot = staged->weather;
        w.version = staged->version;
        w.wanted = staged->window;
        usable = false;
        if (!staged->keepHistory)
            dropHistory(r);  // the previous frame shows other clouds (a small step's still matches them)
        key.weatherVersion = w.version;
    }
    if (!w.snapshot)
    {
        setWeather(r, WeatherSnapshot{});  // no weather given (or the staged one was refused): an empty sky
        key.weatherVersion = w.version;
    }
    // Motion since the last frame: a jump (or the first frame) leaves the window drawn unusable here.
    const glm::dvec3 moveEnu = glm::transpose(camera.enuToEcef) * (camera.eyeEcefM - w.lastEyeEcefM);
    const double moveM = glm::length(glm::dvec2(moveEnu));
    const bool hadFrame = w.lastFrameClock != std::chrono::steady_clock::time_point{};
    const WindowKey& drawnKey = w.window ? w.window->key : WindowKey{};
    usable = usable && w.window && hadFrame && moveM < kReprojectionMaxMoveM &&
             drawnKey.weatherVersion == key.weatherVersion && drawnKey.halfExtentM == key.halfExtentM &&
             drawnKey.warpRadiusM == key.warpRadiusM;
    if (w.wanted && !(w.wanted->key == key))
        w.wanted.reset();  // the eye left that cell before its window was swapped in
    if (!w.wanted && !(w.window && w.window->key == key))
    {
        if (w.back.window && w.back.window->key == key)
        {
            w.wanted = w.back.window;
            if (w.backFromPrefetch)
                ++w.prefetch.used;  // made on the worker, copied ahead of the eye
        }
        else
            w.wanted = takeWindow(w.prefetch, w.snapshot, key);
        w.backFromPrefetch = false;
    }
    if (w.wanted)
        SKY_TRY(showWantedWindow(r, usable));
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
            if (!(w.back.window && w.back.window->key == nextKey))  // else it is on the GPU already
                prefetchWindow(w.prefetch, w.worker, w.snapshot, nextKey);
        }
    }
    return copyFinishedPrefetch(r);
}

}  // namespace sky
