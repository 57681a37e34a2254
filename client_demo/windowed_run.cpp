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

// Opens the window, the Vulkan device on its surface, the service connection, the swapchain and the
// presenter, in that order: the service picks its device by the surface.
bool openWindowSession(WindowSession& s, const DemoOptions& o, std::string& error)
{
    if (!createDemoWindow(s.window, o.width, o.height, "client_demo: sky service", error))
        return false;
    if (!createVulkanInstance(s.vk, windowInstanceExtensions(), error))
        return false;
    s.surface = createWindowSurface(s.window, s.vk.instance);
    if (s.surface == VK_NULL_HANDLE)
    {
        error = "cannot create a Vulkan surface for the window";
        return false;
    }
    DeviceRequest request;
    request.surface = s.surface;
    s.source = SkyClientSource::open(o.socketPath, o.transport, &s.vk, request,
                                     o.composite == CompositeMode::Layers, error);
    if (!s.source)
        return false;
    uint32_t fbWidth = 0;
    uint32_t fbHeight = 0;
    framebufferSize(s.window, fbWidth, fbHeight);
    if (!createSwapchain(s.swapchain, s.vk, s.surface, std::max(fbWidth, 1u), std::max(fbHeight, 1u), VK_NULL_HANDLE))
    {
        error = "cannot create the swapchain";
        return false;
    }
    createPresenter(s.vk, s.presenter);
    return true;
}

// What the window loop carries from one turn to the next.
struct WindowLoop
{
    Aircraft aircraft;
    CompositeOptions composite;
    LatestFrame frame;
    sky::ImageRgba8 composited;
    SkyShmView sentView{};
    unsigned framesShown = 0;
    double fps = 0.0;
    Clock::time_point lastTick = Clock::now();
    Clock::time_point lastFrameAt = Clock::now();
    Clock::time_point lastRequestAt = Clock::now() - std::chrono::seconds(10);
    Clock::time_point lastPresentAt = Clock::now();
    bool haveImage = false;
    bool newImage = false;
};

// How one turn of the window loop ends.
enum class LoopStep
{
    Next,    ///< go round again
    Stop,    ///< the user quit or the last frame was shown
    Failed,  ///< error says why
};

// Reads the keys and flies the aircraft; false when the user quits.
bool applyInput(WindowSession& s, const DemoOptions& o, WindowLoop& l)
{
    WindowEvents events;
    const FlightInput input = readInput(s.window, events);
    if (events.quit)
        return false;
    const double dt = std::min(secondsSince(l.lastTick), 0.25);  // a long stall must not teleport the aircraft
    l.lastTick = Clock::now();
    advanceAircraft(l.aircraft, input, dt);
    if (events.toggleGround)
        l.composite.ground = !l.composite.ground;
    if (events.timeJumpHours > 0 && l.frame.frameId > 0 &&
        !s.source->setTime(l.frame.simTimeUnixS + 3600.0 * events.timeJumpHours, o.rate))
        std::fprintf(stderr, "client_demo: %s\n", s.source->lastError().c_str());
    return true;
}

// Sends the view when it changed and, from a service rendering only on request (render_rate_hz = 0),
// asks for a frame when nothing came for a while.
bool sendViewAndRequest(WindowSession& s, const DemoOptions& o, WindowLoop& l, std::string& error)
{
    unsigned renderWidth = 0;
    unsigned renderHeight = 0;
    renderSizeFor(s.swapchain.width, s.swapchain.height, o, renderWidth, renderHeight);
    const SkyShmView view = viewOf(l.aircraft, o.angles, renderWidth, renderHeight);
    if (!sameView(view, l.sentView))
    {
        if (!s.source->setView(view))
        {
            error = s.source->lastError();
            return false;
        }
        l.sentView = view;
    }
    uint64_t requested = 0;
    if (secondsSince(l.lastFrameAt) > 0.3 && secondsSince(l.lastRequestAt) > 0.3)
    {
        if (!s.source->requestFrame(requested))
        {
            error = s.source->lastError();
            return false;
        }
        l.lastRequestAt = Clock::now();
    }
    return true;
}

// Takes the service's newest frame, if one came, and composites it.
bool fetchFrame(WindowSession& s, WindowLoop& l, std::string& error)
{
    const FetchStatus fetched = s.source->fetch(l.frame.frameId, l.haveImage ? 15 : 200, l.frame);
    if (fetched == FetchStatus::Failed)
    {
        error = "lost the service: " + s.source->lastError();
        return false;
    }
    if (fetched == FetchStatus::NewFrame)
    {
        // Service frames per second, smoothed; the first frame (already waiting at connect) has no interval.
        const double rate = 1.0 / std::max(secondsSince(l.lastFrameAt), 1e-3);
        if (l.haveImage)
            l.fps = l.fps == 0.0 ? rate : 0.8 * l.fps + 0.2 * rate;
        l.lastFrameAt = Clock::now();
        compositeFrame(l.frame, l.composite, l.composited);
        l.haveImage = l.newImage = true;
    }
    return true;
}

bool writeScreenshot(const DemoOptions& o, const sky::ImageRgba8& screenshot, std::string& error)
{
    if (screenshot.pixels.empty())
    {
        error = "the window's swapchain cannot be read back (no TRANSFER_SRC usage): no screenshot";
        return false;
    }
    if (!sky::writePng(o.screenshotPath, screenshot, error))
        return false;
    std::printf("client_demo: screenshot %s (%ux%u)\n", o.screenshotPath.c_str(), screenshot.width,
                screenshot.height);
    return true;
}

// Draws the overlay on the composited frame and presents it; the last frame (--frames) may be kept as
// the screenshot.
LoopStep showFrame(WindowSession& s, const DemoOptions& o, WindowLoop& l, bool resized, std::string& error)
{
    // Between service frames only the overlay changes: 30 redraws a second are plenty, and every redraw
    // costs CPU that a lavapipe service would rather render with.
    if (!l.haveImage || (!l.newImage && !resized && secondsSince(l.lastPresentAt) < 1.0 / 30.0))
        return LoopStep::Next;
    l.lastPresentAt = Clock::now();
    sky::ImageRgba8 shown = l.composited;
    OverlayInfo info;
    info.aircraft = l.aircraft;
    info.simTimeUnixS = l.frame.simTimeUnixS;
    info.fps = l.fps;
    info.frameId = l.frame.frameId;
    info.transport = s.source->transportName();
    drawOverlay(shown, info);
    const bool last = o.frames > 0 && l.newImage && l.framesShown + 1 >= o.frames;
    sky::ImageRgba8 screenshot;
    const bool wantShot = last && !o.screenshotPath.empty();
    const SwapchainStatus presented =
        presentImage(s.vk, s.presenter, s.swapchain, shown, wantShot ? &screenshot : nullptr);
    if (presented != SwapchainStatus::Ready)
        return LoopStep::Next;  // out of date: re-created at the top of the loop, the frame is shown next time round
    if (l.newImage)
        ++l.framesShown;
    l.newImage = false;
    if (wantShot && !writeScreenshot(o, screenshot, error))
        return LoopStep::Failed;
    return last ? LoopStep::Stop : LoopStep::Next;
}

// One turn of the window loop: input, swapchain, view, fetch, present.
LoopStep runLoopStep(WindowSession& s, const DemoOptions& o, WindowLoop& l, std::string& error)
{
    if (!applyInput(s, o, l))
        return LoopStep::Stop;
    uint32_t fbWidth = 0;
    uint32_t fbHeight = 0;
    framebufferSize(s.window, fbWidth, fbHeight);
    const SwapchainStatus status =
        updateSwapchain(s.swapchain, s.vk, s.surface, fbWidth, fbHeight, s.presenter.outOfDate);
    if (status == SwapchainStatus::Resized)
        s.presenter.outOfDate = false;
    if (status == SwapchainStatus::NotReady)
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));  // minimised: nothing to draw
        return LoopStep::Next;
    }
    if (!sendViewAndRequest(s, o, l, error) || !fetchFrame(s, l, error))
        return LoopStep::Failed;
    return showFrame(s, o, l, status == SwapchainStatus::Resized, error);
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
    if (!openWindowSession(s, o, error))
        return fail(error);
    std::printf("client_demo: window %ux%u on %s, transport %s\n", s.swapchain.width, s.swapchain.height,
                s.vk.deviceName.c_str(), s.source->transportName().c_str());

    double unixTimeS = 0.0;
    if (!o.timeIso.empty() && parseUtc(o.timeIso, unixTimeS) && !s.source->setTime(unixTimeS, o.rate))
        return fail(s.source->lastError());

    WindowLoop loop;
    loop.aircraft = o.aircraft;
    loop.composite = compositeOptionsOf(o);
    for (;;)
    {
        const LoopStep step = runLoopStep(s, o, loop, error);
        if (step == LoopStep::Failed)
            return fail(error);
        if (step == LoopStep::Stop)
            break;
    }
    std::printf("client_demo: %u frames shown\n", loop.framesShown);
    return 0;
}

}  // namespace demo
