// SPDX-License-Identifier: MIT
#include "skyservice/service/daemon.h"

#include "skyservice/ipc/control_socket.h"
#include "skyservice/ipc/shm_ring.h"
#include "skyservice/render/renderer.h"
#include "skyservice/service/cigi_link.h"
#include "skyservice/service/control_loop.h"
#include "skyservice/service/files_root.h"
#include "skyservice/service/log.h"
#include "skyservice/service/render_loop.h"
#include "skyservice/service/service_config.h"
#include "skyservice/service/signals.h"
#include "skyservice/service/weather_loader.h"
#include "skyservice/service/weather_watcher.h"
#include "skyservice/sky/ephemeris.h"

#include <malloc.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>

namespace sky
{
namespace
{

constexpr int kExitClean = 0, kExitFailure = 1, kExitConfig = 2;

class Daemon
{
public:
    explicit Daemon(const DaemonOptions& options) : options_(options) {}
    int run();

private:
    bool readConfig(ServiceConfig& out, std::string& error) const;
    void reload();
    void startWatcher(const std::string& dir);
    void onWeather(const std::string& path, std::shared_ptr<const WeatherTimeline> timeline, const std::string& error);
    int shutdown(int code);

    DaemonOptions options_;
    ServiceConfig config_;
    ServiceState state_;
    Renderer renderer_;
    ShmRingWriter ring_;
    FilesRoot filesRoot_;
    ControlSocketServer server_;
    WeatherLoader loader_;
    WeatherWatcher watcher_;
    SignalWatcher signals_;
    RenderLoop renderLoop_;
    CigiLink cigi_;
    std::atomic<bool> terminate_{false}, hangup_{false};
};

bool Daemon::readConfig(ServiceConfig& out, std::string& error) const
{
    out = defaultServiceConfig();
    if (!options_.config.empty() && !loadServiceConfig(options_.config, out, error))
        return false;
    if (!options_.socket.empty())
        out.socketPath = options_.socket;
    if (!options_.weatherDir.empty())
        out.weatherDir = options_.weatherDir;
    if (!options_.device.empty())
        out.device = options_.device;
    out.validate = out.validate || options_.validate;
    if (options_.cigiPort >= 0)
        out.cigi.port = uint32_t(options_.cigiPort);
    if (options_.cigiHostPort >= 0)
        out.cigi.hostPort = uint32_t(options_.cigiHostPort);
    if (options_.cigiViewId >= 0)
        out.cigi.viewId = uint32_t(options_.cigiViewId);
    if (options_.cigiOwnship >= 0)
        out.cigi.ownship = uint32_t(options_.cigiOwnship);
    if (!options_.logLevel.empty() && !parseLogLevel(options_.logLevel, out.logLevel))
    {
        error = "--log-level " + options_.logLevel + ": expected error, warn, info or debug";
        return false;
    }
    if (out.socketPath.empty())
        out.socketPath = defaultSocketPath();
    if (out.shmName.empty())
        out.shmName = defaultShmName(out.socketPath);
    if (out.filesRoot.empty())
        out.filesRoot = defaultFilesRoot();
    return checkServiceConfig(out, options_.config.empty() ? "command line" : options_.config, error);
}

void Daemon::startWatcher(const std::string& dir)
{
    watcher_.stop();
    if (dir.empty())
        return;
    std::string error;
    if (watcher_.start(dir, [this](const std::string& path) { loader_.enqueue(path); }, error))
        SKY_LOG_INFO("watching %s for *.skywx", dir.c_str());
    else
        SKY_LOG_ERROR("%s (no weather folder is watched)", error.c_str());
}

void Daemon::onWeather(const std::string& path, std::shared_ptr<const WeatherTimeline> timeline, const std::string& error)
{
    std::lock_guard<std::mutex> lock(state_.mutex);
    if (!timeline)
    {
        state_.weather.lastError = error;
        state_.weather.lastErrorPath = path;
        SKY_LOG_WARN("weather %s refused: %s (keeping %s)", path.c_str(), error.c_str(), state_.weather.source.c_str());
        return;
    }
    // Swapped in here, used from the render thread's next frame on: a frame never sees half a swap.
    state_.weather.timeline = std::move(timeline);
    state_.weather.source = path;
    state_.weather.lastError.clear();
    ++state_.weather.version;
    SKY_LOG_INFO("weather %s loaded: %zu valid time(s), %s .. %s", path.c_str(), state_.weather.timeline->size(),
                 formatIso8601Utc(state_.weather.timeline->firstTimeUnixS()).c_str(),
                 formatIso8601Utc(state_.weather.timeline->lastTimeUnixS()).c_str());
}

void Daemon::reload()
{
    if (options_.config.empty())
    {
        SKY_LOG_INFO("SIGHUP: no --config file to reload");
        return;
    }
    ServiceConfig fresh;
    std::string error;
    if (!readConfig(fresh, error))
    {
        SKY_LOG_ERROR("SIGHUP: %s; keeping the running configuration", error.c_str());
        return;
    }
    // What the ring, the socket and the device were built with stays until a restart.
    auto keep = [&](bool changed, const char* field) {
        if (changed)
            SKY_LOG_WARN("SIGHUP: service.%s changed: takes effect after a restart", field);
    };
    keep(fresh.socketPath != config_.socketPath, "socket_path");
    keep(fresh.socketMode != config_.socketMode, "socket_mode");
    keep(fresh.maxWidth != config_.maxWidth || fresh.maxHeight != config_.maxHeight, "max_width/max_height");
    keep(fresh.shmSlots != config_.shmSlots, "shm_slots");
    keep(fresh.shadowMapSize != config_.shadowMapSize, "shadow_map_size");
    keep(fresh.device != config_.device || fresh.validate != config_.validate, "device/validate");
    if (!(fresh.cigi == config_.cigi))
        SKY_LOG_WARN("SIGHUP: [cigi] changed: takes effect after a restart");
    fresh.cigi = config_.cigi;
    keep(fresh.filesRoot != config_.filesRoot, "files_root");
    // The noise textures are made from the seed once, when the renderer starts: a new seed is refused (the
    // running one stays, in the renderer and in the state's quality alike).
    if (fresh.qualitySettings.noiseSeed != config_.qualitySettings.noiseSeed)
        SKY_LOG_WARN("SIGHUP: noise.seed changed (%u -> %u): takes effect after a restart",
                     config_.qualitySettings.noiseSeed, fresh.qualitySettings.noiseSeed);
    fresh.qualitySettings.noiseSeed = config_.qualitySettings.noiseSeed;
    fresh.socketPath = config_.socketPath;
    fresh.socketMode = config_.socketMode;
    fresh.shmName = config_.shmName;
    fresh.maxWidth = config_.maxWidth;
    fresh.maxHeight = config_.maxHeight;
    fresh.shmSlots = config_.shmSlots;
    fresh.shadowMapSize = config_.shadowMapSize;
    fresh.device = config_.device;
    fresh.validate = config_.validate;
    fresh.filesRoot = config_.filesRoot;

    setLogLevel(fresh.logLevel);
    {
        std::lock_guard<std::mutex> lock(state_.mutex);
        state_.quality = fresh.qualitySettings;
        state_.renderRateHz = fresh.renderRateHz;
        state_.view.shadowMapExtentM = fresh.shadowMapExtentM;
        std::erase_if(state_.files, [](const FilesSubscription& f) { return f.client == 0; });
        if (fresh.filesEvery > 0)
            state_.files.push_back(FilesSubscription{0, fresh.filesDir, fresh.filesEvery, fresh.filesFormat});
        if (fresh.weather != config_.weather && fresh.weather == "builtin")
        {
            state_.weather.timeline.reset();
            state_.weather.source = "builtin";
            ++state_.weather.version;
        }
    }
    state_.wake.notify_all();
    if (fresh.weather != config_.weather && fresh.weather != "builtin")
        loader_.enqueue(fresh.weather);
    if (fresh.weatherDir != config_.weatherDir)
        startWatcher(fresh.weatherDir);
    config_ = fresh;
    SKY_LOG_INFO("SIGHUP: %s reloaded", options_.config.c_str());
}

int Daemon::run()
{
    std::string error;
    if (!readConfig(config_, error))
    {
        std::fprintf(stderr, "skyservice: %s\n", error.c_str());
        return kExitConfig;
    }
    setLogLevel(config_.logLevel);
    // Before any thread starts, so that every thread inherits the blocked mask.
    blockServiceSignals();

    state_.view = config_.view;
    state_.view.shadowMap = config_.shadowMapSize > 0;
    state_.view.shadowMapSize = config_.shadowMapSize;
    state_.view.shadowMapExtentM = config_.shadowMapExtentM;
    state_.clock.baseUnixS = double(config_.timeUnixS);
    state_.clock.rate = config_.rate;
    state_.quality = config_.qualitySettings;
    state_.renderRateHz = config_.renderRateHz;
    if (config_.filesEvery > 0)
        state_.files.push_back(FilesSubscription{0, config_.filesDir, config_.filesEvery, config_.filesFormat});
    if (config_.weather != "builtin")
    {
        auto timeline = std::make_shared<WeatherTimeline>();
        if (!timeline->loadFile(config_.weather, error))
        {
            std::fprintf(stderr, "skyservice: %s: 'service.weather': %s\n",
                         options_.config.empty() ? "command line" : options_.config.c_str(), error.c_str());
            return kExitConfig;
        }
        state_.weather.timeline = timeline;
        state_.weather.source = config_.weather;
    }

    RendererOptions ro;
    ro.context.deviceSelector = config_.device;
    ro.context.validation = config_.validate;
    ro.noiseSeed = config_.qualitySettings.noiseSeed;
    SkyStatus status = createRenderer(renderer_, ro);
    if (!status.ok())
    {
        SKY_LOG_ERROR("renderer: %s", status.message.c_str());
        destroyRenderer(renderer_);
        return kExitFailure;
    }
    SKY_LOG_INFO("device %s (%s)", renderer_.ctx.deviceName.c_str(), renderer_.ctx.driverInfo.c_str());

    ShmRingConfig rc;
    rc.name = config_.shmName;
    rc.slotCount = config_.shmSlots;
    rc.maxWidth = config_.maxWidth;
    rc.maxHeight = config_.maxHeight;
    rc.maxShadowSize = config_.shadowMapSize;
    rc.mode = config_.socketMode;  // who may read frames is who may drive the service
    if (!ring_.create(rc, error))
    {
        SKY_LOG_ERROR("shared memory: %s", error.c_str());
        return shutdown(kExitFailure);
    }
    if (filesRoot_.open(config_.filesRoot, error))
        SKY_LOG_INFO("files are written beneath %s", filesRoot_.path().c_str());
    else
        SKY_LOG_ERROR("%s (no files are written)", error.c_str());
    ControlSocketLimits limits;
    if (!server_.listen(config_.socketPath, config_.socketMode, limits, error))
    {
        SKY_LOG_ERROR("control socket: %s", error.c_str());
        return shutdown(kExitFailure);
    }
    SKY_LOG_INFO("listening on %s (mode %04o), frames in %s (%u slots of up to %ux%u)", config_.socketPath.c_str(),
                 config_.socketMode, ring_.name().c_str(), ring_.slotCount(), config_.maxWidth, config_.maxHeight);

    signals_.start([this](int signo) {
        (signo == SIGHUP ? hangup_ : terminate_) = true;
        SKY_LOG_INFO("signal %s", signo == SIGHUP ? "SIGHUP" : signo == SIGINT ? "SIGINT" : "SIGTERM");
        server_.wake();
    });
    loader_.start([this](const std::string& path, std::shared_ptr<const WeatherTimeline> t, const std::string& e) {
        onWeather(path, std::move(t), e);
    });
    startWatcher(config_.weatherDir);
    if (config_.cigi.port != 0 && !cigi_.start(config_.cigi, &state_, error))
    {
        SKY_LOG_ERROR("%s", error.c_str());
        return shutdown(kExitFailure);
    }

    ControlContext cc;
    cc.server = &server_;
    cc.state = &state_;
    cc.loader = &loader_;
    cc.ring = &ring_;
    cc.filesRoot = &filesRoot_;
    cc.limits.maxWidth = config_.maxWidth;
    cc.limits.maxHeight = config_.maxHeight;
    cc.deviceName = renderer_.ctx.deviceName;
    cc.driver = renderer_.ctx.driverInfo;
    cc.cigi = cigi_.running() ? &cigi_ : nullptr;
    ControlLoop control(cc);
    ControlSocketServer::Handlers handlers = control.handlers();

    RenderLoop::Setup setup;
    setup.renderer = &renderer_;
    setup.ring = &ring_;
    setup.filesRoot = &filesRoot_;
    setup.state = &state_;
    setup.repliesReady = [this] { server_.wake(); };
    setup.exportSlots = config_.shmSlots;
    setup.exportMaxWidth = config_.maxWidth;
    setup.exportMaxHeight = config_.maxHeight;
    setup.exportShadowSize = config_.shadowMapSize;
    if (cigi_.running())
        setup.frameEnded = [this](uint64_t id, bool ok) { cigi_.frameEnded(id, ok); };
    renderLoop_.start(setup);

    while (!terminate_.load())
    {
        server_.poll(250, handlers);
        control.sendPendingReplies();
        control.logHeldBack();
        if (hangup_.exchange(false))
            reload();
    }
    SKY_LOG_INFO("shutting down");
    return shutdown(kExitClean);
}

int Daemon::shutdown(int code)
{
    renderLoop_.stop();  // first: it uses the ring, the renderer and the export
    cigi_.stop();        // after it: the render loop sends Start of Frame through it
    watcher_.stop();     // before the loader it feeds
    loader_.stop();
    signals_.stop();
    server_.close();     // unlinks the socket
    ring_.destroy();     // unlinks the shared memory
    uint32_t validation = renderer_.ctx.validationMessages.load();
    destroyRenderer(renderer_);
    VkDeviceSize leaked = 0;
    {
        std::lock_guard<std::mutex> lock(renderer_.memory.mutex);
        leaked = renderer_.memory.totalBytes;
    }
    if (leaked != 0)
    {
        SKY_LOG_ERROR("%llu bytes of device memory still tracked after shutdown", (unsigned long long)leaked);
        code = kExitFailure;
    }
    if (config_.validate && validation > 0)
    {
        SKY_LOG_ERROR("%u Vulkan validation messages", validation);
        code = kExitFailure;
    }
    if (code == kExitClean)
        SKY_LOG_INFO("stopped cleanly (socket and shared memory removed, device memory 0 bytes)");
    return code;
}

}  // namespace

int runDaemon(const DaemonOptions& options)
{
    // Buffers of 1 MiB and more (weather windows: 17 MB each, snapshots, frames) come from mmap and go
    // back to the system when freed. glibc's default threshold rises to 32 MiB after the first such
    // free, after which a replaced window stays in the heap and the RSS of a long-running service
    // wanders by tens of MB (tests/service soak: 242-283 MB over 4000 frames with weather swaps;
    // with this setting it tracks the live memory).
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    // Before the Daemon exists: its Renderer starts the weather worker thread when constructed, and a
    // thread that leaves SIGTERM unblocked takes it (the default action kills the process uncleanly).
    blockServiceSignals();
    auto daemon = std::make_unique<Daemon>(options);  // the Renderer is large: not on the stack
    return daemon->run();
}

}  // namespace sky
