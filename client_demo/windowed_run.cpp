// SPDX-License-Identifier: MIT
#include "client_demo/windowed_run.h"

#include "client_demo/compositor.h"
#include "client_demo/overlay.h"
#include "client_demo/presenter.h"
#include "client_demo/utc_time.h"
#include "client_demo/window.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

namespace demo
{
namespace
{

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool sameView(const SkyShmView& a, const SkyShmView& b)
{
    return a.lat_deg == b.lat_deg && a.lon_deg == b.lon_deg && a.alt_m == b.alt_m && a.heading_deg == b.heading_deg &&
           a.pitch_deg == b.pitch_deg && a.fov_deg == b.fov_deg && a.asymmetric == b.asymmetric &&
           a.left_deg == b.left_deg && a.right_deg == b.right_deg && a.up_deg == b.up_deg && a.down_deg == b.down_deg && a.width == b.width && a.height == b.height;
}

// Everything the window owns, destroyed in reverse order of creation.
struct WindowSession
{
    DemoWindow window;
    VulkanDevice vk;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    std::unique_ptr<SkyClientSource> source;
    Swapchain swapchain;
    Presenter presenter;

    ~WindowSession()
    {
        if (presenter.cmd != VK_NULL_HANDLE)
            destroyPresenter(vk, presenter);
        if (vk.device != VK_NULL_HANDLE)
            destroySwapchain(vk, swapchain);
        source.reset();
        destroyVulkanDeviceOnly(vk);
        if (surface != VK_NULL_HANDLE)
            vkDestroySurfaceKHR(vk.instance, surface, nullptr);
        destroyVulkanDevice(vk);
        destroyDemoWindow(window);
    }
};

// The render size for a framebuffer: the window's, at most the --width x --height area's pixel count times 4
// (a big window on lavapipe would otherwise ask the service for frames it takes seconds to render).
void renderSizeFor(uint32_t fbWidth, uint32_t fbHeight, const DemoOptions& o, unsigned& width, unsigned& height)
{
    const double maxPixels = 4.0 * o.width * o.height;
    const double scale = std::min(1.0, std::sqrt(maxPixels / std::max(1.0, double(fbWidth) * fbHeight)));
    width = std::max(8u, unsigned(fbWidth * scale));
    height = std::max(8u, unsigned(fbHeight * scale));
}

}  // namespace

int runWindowed(const DemoOptions& o)
{
    WindowSession s;
    std::string error;
    auto fail = [&](const std::string& why) {
        std::fprintf(stderr, "client_demo: %s\n", why.c_str());
        return 1;
    };
    if (!createDemoWindow(s.window, o.width, o.height, "client_demo: sky service", error))
        return fail(error);
    if (!createVulkanInstance(s.vk, windowInstanceExtensions(), error))
        return fail(error);
    s.surface = createWindowSurface(s.window, s.vk.instance);
    if (s.surface == VK_NULL_HANDLE)
        return fail("cannot create a Vulkan surface for the window");
    DeviceRequest request;
    request.surface = s.surface;
    s.source = SkyClientSource::open(o.socketPath, o.transport, &s.vk, request,
                                     o.composite == CompositeMode::Layers, error);
    if (!s.source)
        return fail(error);
    uint32_t fbWidth = 0;
    uint32_t fbHeight = 0;
    framebufferSize(s.window, fbWidth, fbHeight);
    if (!createSwapchain(s.swapchain, s.vk, s.surface, std::max(fbWidth, 1u), std::max(fbHeight, 1u), VK_NULL_HANDLE))
        return fail("cannot create the swapchain");
    createPresenter(s.vk, s.presenter);
    std::printf("client_demo: window %ux%u on %s, transport %s\n", s.swapchain.width, s.swapchain.height,
                s.vk.deviceName.c_str(), s.source->transportName().c_str());

    double unixTimeS = 0.0;
    if (!o.timeIso.empty() && parseUtc(o.timeIso, unixTimeS) && !s.source->setTime(unixTimeS, o.rate))
        return fail(s.source->lastError());

    Aircraft aircraft = o.aircraft;
    CompositeOptions composite = compositeOptionsOf(o);
    LatestFrame frame;
    sky::ImageRgba8 composited;
    SkyShmView sentView{};
    unsigned framesShown = 0;
    double fps = 0.0;
    auto lastTick = Clock::now();
    auto lastFrameAt = Clock::now();
    auto lastRequestAt = Clock::now() - std::chrono::seconds(10);
    auto lastPresentAt = Clock::now();
    bool haveImage = false;
    bool newImage = false;
    for (;;)
    {
        WindowEvents events;
        const FlightInput input = readInput(s.window, events);
        if (events.quit)
            break;
        const double dt = std::min(secondsSince(lastTick), 0.25);  // a long stall must not teleport the aircraft
        lastTick = Clock::now();
        advanceAircraft(aircraft, input, dt);
        if (events.toggleGround)
            composite.ground = !composite.ground;
        if (events.timeJumpHours > 0 && frame.frameId > 0 &&
            !s.source->setTime(frame.simTimeUnixS + 3600.0 * events.timeJumpHours, o.rate))
            std::fprintf(stderr, "client_demo: %s\n", s.source->lastError().c_str());

        framebufferSize(s.window, fbWidth, fbHeight);
        const SwapchainStatus status =
            updateSwapchain(s.swapchain, s.vk, s.surface, fbWidth, fbHeight, s.presenter.outOfDate);
        if (status == SwapchainStatus::Resized)
            s.presenter.outOfDate = false;
        if (status == SwapchainStatus::NotReady)
        {
            std::this_thread::sleep_for(std::chrono::milliseconds(50));  // minimised: nothing to draw
            continue;
        }
        unsigned renderWidth = 0;
        unsigned renderHeight = 0;
        renderSizeFor(s.swapchain.width, s.swapchain.height, o, renderWidth, renderHeight);
        const SkyShmView view = viewOf(aircraft, o.angles, renderWidth, renderHeight);
        if (!sameView(view, sentView))
        {
            if (!s.source->setView(view))
                return fail(s.source->lastError());
            sentView = view;
        }
        // A service rendering only on request (render_rate_hz = 0) gets one when nothing came for a while.
        uint64_t requested = 0;
        if (secondsSince(lastFrameAt) > 0.3 && secondsSince(lastRequestAt) > 0.3)
        {
            if (!s.source->requestFrame(requested))
                return fail(s.source->lastError());
            lastRequestAt = Clock::now();
        }
        const FetchStatus fetched = s.source->fetch(frame.frameId, haveImage ? 15 : 200, frame);
        if (fetched == FetchStatus::Failed)
            return fail("lost the service: " + s.source->lastError());
        if (fetched == FetchStatus::NewFrame)
        {
            // Service frames per second, smoothed; the first frame (already waiting at connect) has no interval.
            const double rate = 1.0 / std::max(secondsSince(lastFrameAt), 1e-3);
            if (haveImage)
                fps = fps == 0.0 ? rate : 0.8 * fps + 0.2 * rate;
            lastFrameAt = Clock::now();
            compositeFrame(frame, composite, composited);
            haveImage = newImage = true;
        }
        // Between service frames only the overlay changes: 30 redraws a second are plenty, and every redraw
        // costs CPU that a lavapipe service would rather render with.
        const bool resized = status == SwapchainStatus::Resized;
        if (!haveImage || (!newImage && !resized && secondsSince(lastPresentAt) < 1.0 / 30.0))
            continue;
        lastPresentAt = Clock::now();
        sky::ImageRgba8 shown = composited;
        OverlayInfo info;
        info.aircraft = aircraft;
        info.simTimeUnixS = frame.simTimeUnixS;
        info.fps = fps;
        info.frameId = frame.frameId;
        info.transport = s.source->transportName();
        drawOverlay(shown, info);
        const bool last = o.frames > 0 && newImage && framesShown + 1 >= o.frames;
        sky::ImageRgba8 screenshot;
        const bool wantShot = last && !o.screenshotPath.empty();
        const SwapchainStatus presented =
            presentImage(s.vk, s.presenter, s.swapchain, shown, wantShot ? &screenshot : nullptr);
        if (presented != SwapchainStatus::Ready)
            continue;  // out of date: re-created at the top of the loop, the frame is shown next time round
        if (newImage)
            ++framesShown;
        newImage = false;
        if (wantShot)
        {
            if (screenshot.pixels.empty())
                return fail("the window's swapchain cannot be read back (no TRANSFER_SRC usage): no screenshot");
            if (!sky::writePng(o.screenshotPath, screenshot, error))
                return fail(error);
            std::printf("client_demo: screenshot %s (%ux%u)\n", o.screenshotPath.c_str(), screenshot.width,
                        screenshot.height);
        }
        if (last)
            break;
    }
    std::printf("client_demo: %u frames shown\n", framesShown);
    return 0;
}

}  // namespace demo
