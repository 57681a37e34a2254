// SPDX-License-Identifier: MIT
// End-to-end: the real daemon, driven through libskyclient. Frames match a one-shot render; clients
// that die, crowd in or outlive the service never disturb it.
#include "skyservice/client/skyclient.h"
#include "skyservice/output/image_files.h"
#include "tests/service/service_harness.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cstring>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace skytest;

namespace
{

SkyView testView()
{
    SkyView v{};
    v.lat_deg = 46.0;
    v.lon_deg = 8.0;
    v.alt_m = 2500;
    v.heading_deg = 200;
    v.pitch_deg = 5;
    v.roll_deg = 0;
    v.fov_deg = 60;
    v.width = 64;
    v.height = 36;
    return v;
}

float halfToFloat(uint16_t h) { return glm::unpackHalf1x16(h); }

/// Waits for a frame newer than `after` and returns its id (0 on failure).
uint64_t nextFrame(SkyClient* c, uint64_t after, int timeoutMs = 20000)
{
    if (sky_client_wait_frame(c, after, timeoutMs) != SKY_OK)
        return 0;
    SkyFrame f{};
    if (sky_client_acquire_frame(c, &f) != SKY_OK)
        return 0;
    uint64_t id = f.frame_id;
    sky_client_release_frame(c, &f);
    return id;
}

/// The RGBA8 pixels of an acquired frame, rows packed (the ring's rows may be padded).
std::vector<uint8_t> framePixels(const SkyFrame& f)
{
    std::vector<uint8_t> pixels;
    for (uint32_t y = 0; y < f.height; ++y)
        pixels.insert(pixels.end(), f.pixels + size_t(y) * f.row_bytes, f.pixels + size_t(y) * f.row_bytes + f.width * 4);
    return pixels;
}

/// `skyservice render` of testView() at 2026-06-21T16:00:00Z with `extraArgs`, into dir/ref.png (+ .json),
/// read back into `ref`.
bool renderOneShotOfTestView(const std::string& dir, const std::string& extraArgs, sky::ImageRgba8& ref,
                             std::string& error)
{
    std::string cmd = serviceBinary() + " render --quality test --lat 46 --lon 8 --alt 2500 --heading 200 --pitch 5"
                      " --fov 60 --width 64 --height 36 --time 2026-06-21T16:00:00Z " + extraArgs + " --out " + dir +
                      "/ref > " + dir + "/ref.log 2>&1";
    if (std::system(cmd.c_str()) != 0)
    {
        error = "skyservice render failed: " + dir + "/ref.log";
        return false;
    }
    return sky::readPng(dir + "/ref.png", ref, error);
}

}  // namespace

// A frame from the service is byte for byte the frame `skyservice render` writes for the same view,
// time, quality, seed and weather: the service renders with the same renderer and inputs, and a frozen
// clock samples the weather once at the same second.
TEST(ServiceFrames, MatchesOneShotRender)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, DaemonConfig{}, error)) << error;

    SkyClient* c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "match", &c), SKY_OK);
    SkyView v = testView();
    ASSERT_EQ(sky_client_set_view(c, &v), SKY_OK) << sky_client_last_error(c);
    ASSERT_EQ(sky_client_set_time(c, 1782043200.0 + 3600.0 * 4, 0.0), SKY_OK);  // 2026-06-21T16:00:00Z
    ASSERT_EQ(sky_client_subscribe_shm(c), SKY_OK) << sky_client_last_error(c);
    uint64_t id = 0;
    ASSERT_EQ(sky_client_request_frame(c, &id), SKY_OK);
    ASSERT_EQ(sky_client_wait_frame(c, id - 1, 30000), SKY_OK) << sky_client_last_error(c);
    SkyFrame f{};
    ASSERT_EQ(sky_client_acquire_frame(c, &f), SKY_OK);
    EXPECT_GE(f.frame_id, id);
    ASSERT_EQ(f.width, 64u);
    ASSERT_EQ(f.height, 36u);
    EXPECT_DOUBLE_EQ(f.view.lat_deg, 46.0);
    std::vector<uint8_t> pixels = framePixels(f);
    ASSERT_EQ(sky_client_release_frame(c, &f), SKY_OK);
    sky_client_close(c);

    sky::ImageRgba8 ref;
    ASSERT_TRUE(renderOneShotOfTestView(tmp.path, "", ref, error)) << error;
    ASSERT_EQ(ref.pixels.size(), pixels.size());
    size_t differing = 0;
    int maxDiff = 0;
    for (size_t i = 0; i < pixels.size(); ++i)
    {
        int diff = std::abs(int(pixels[i]) - int(ref.pixels[i]));
        differing += diff != 0;
        maxDiff = std::max(maxDiff, diff);
    }
    EXPECT_EQ(differing, 0u) << "largest difference " << maxDiff << " of 255";
    EXPECT_EQ(d.stop(), 0);
}

// The compositing layers a subscriber asks for are those of the one-shot render of the same
// view: the clouds layer's alpha is the EXR's A (1 - transmittance) and the depth layer's G its Z, its R
// (the cloud's front) the EXR's ZFront, bit for bit, never beyond G and > 0 wherever G is;
// the sky layer is the sky alone (where no cloud is, the display is the sky layer tone-mapped, so it is
// not black). A subscriber without layers gets frames without them.
TEST(ServiceFrames, LayersMatchTheOneShotRendersExr)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, DaemonConfig{}, error)) << error;
    SkyClient* c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "layers", &c), SKY_OK);
    SkyView v = testView();
    ASSERT_EQ(sky_client_set_view(c, &v), SKY_OK) << sky_client_last_error(c);
    ASSERT_EQ(sky_client_set_time(c, 1782043200.0 + 3600.0 * 4, 0.0), SKY_OK);  // 2026-06-21T16:00:00Z
    EXPECT_EQ(sky_client_subscribe_shm_layers(c, 1u << 7), SKY_ERR_ARGUMENT);
    ASSERT_EQ(sky_client_subscribe_shm_layers(c, (1u << SKY_LAYER_SKY) | (1u << SKY_LAYER_CLOUDS) |
                                                     (1u << SKY_LAYER_DEPTH)),
              SKY_OK)
        << sky_client_last_error(c);
    uint64_t id = 0;
    ASSERT_EQ(sky_client_request_frame(c, &id), SKY_OK);
    ASSERT_EQ(sky_client_wait_frame(c, id - 1, 30000), SKY_OK) << sky_client_last_error(c);
    SkyFrame f{};
    ASSERT_EQ(sky_client_acquire_frame(c, &f), SKY_OK);
    const SkyFrameLayer& clouds = f.layers[SKY_LAYER_CLOUDS];
    const SkyFrameLayer& depth = f.layers[SKY_LAYER_DEPTH];
    const SkyFrameLayer& sky = f.layers[SKY_LAYER_SKY];
    ASSERT_EQ(clouds.format, SKY_FORMAT_RGBA16F_PREMULTIPLIED);
    ASSERT_EQ(depth.format, SKY_FORMAT_RG32F_METRES);
    ASSERT_EQ(sky.format, SKY_FORMAT_RGBA16F_LINEAR);
    ASSERT_EQ(f.layers[SKY_LAYER_DISPLAY].pixels, f.pixels);
    const size_t n = size_t(f.width) * f.height;
    std::vector<float> alpha(n), z(n), front(n), skyRed(n);
    for (uint32_t y = 0; y < f.height; ++y)
        for (uint32_t x = 0; x < f.width; ++x)
        {
            uint16_t a = 0, r = 0;
            std::memcpy(&a, clouds.pixels + size_t(y) * clouds.row_bytes + x * 8 + 6, 2);
            std::memcpy(&r, sky.pixels + size_t(y) * sky.row_bytes + x * 8, 2);
            alpha[size_t(y) * f.width + x] = halfToFloat(a);
            skyRed[size_t(y) * f.width + x] = halfToFloat(r);
            std::memcpy(&front[size_t(y) * f.width + x], depth.pixels + size_t(y) * depth.row_bytes + x * 8, 4);
            std::memcpy(&z[size_t(y) * f.width + x], depth.pixels + size_t(y) * depth.row_bytes + x * 8 + 4, 4);
        }
    ASSERT_EQ(sky_client_release_frame(c, &f), SKY_OK);
    sky_client_close(c);

    sky::ImageRgba8 ref;
    ASSERT_TRUE(renderOneShotOfTestView(tmp.path, "", ref, error)) << error;
    sky::ExrImage exr;
    ASSERT_TRUE(sky::readExr(tmp.path + "/ref.exr", exr, error)) << error;
    ASSERT_EQ(exr.channels["A"].values.size(), n);
    size_t cloudy = 0, frontNearer = 0;
    for (size_t i = 0; i < n; ++i)
    {
        ASSERT_EQ(alpha[i], exr.channels["A"].values[i]) << "alpha of pixel " << i;
        ASSERT_EQ(z[i], exr.channels["Z"].values[i]) << "depth of pixel " << i;
        ASSERT_EQ(front[i], exr.channels["ZFront"].values[i]) << "front of pixel " << i;
        ASSERT_LE(front[i], z[i]) << "pixel " << i;
        ASSERT_EQ(front[i] > 0.0f, z[i] > 0.0f) << "pixel " << i;
        // A cumulus is hundreds of metres deep: its front lies well before its weighted distance.
        frontNearer += alpha[i] > 0.5f && front[i] < z[i] - 50.0f;
        EXPECT_GT(skyRed[i], 0.0f) << "sky of pixel " << i;
        cloudy += alpha[i] > 0.5f;
    }
    EXPECT_GT(cloudy, 0u) << "the view should hold cloud";
    EXPECT_GT(frontNearer, cloudy / 2) << "the depth layer's front is its weighted distance: no front";
    EXPECT_EQ(d.stop(), 0);
}

// A weather loaded while the service runs is drawn from a frame on that depends on when its window was
// ready (status weather.frame says which); that frame is byte for byte what `skyservice render --weather`
// writes for the same view, time and file. The frames before it drew the old weather.
TEST(ServiceFrames, LoadedWeatherFrameMatchesOneShotRender)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, DaemonConfig{}, error)) << error;
    const std::string wx = tmp.path + "/later.skywx";
    ASSERT_TRUE(writeBuiltinSnapshot(wx, 1782043200 + 3600 * 2, error)) << error;  // 14:00, drawn at 16:00

    SkyClient* c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "load", &c), SKY_OK);
    SkyView v = testView();
    ASSERT_EQ(sky_client_set_view(c, &v), SKY_OK) << sky_client_last_error(c);
    ASSERT_EQ(sky_client_set_time(c, 1782043200.0 + 3600.0 * 4, 0.0), SKY_OK);  // 2026-06-21T16:00:00Z
    ASSERT_EQ(sky_client_subscribe_shm(c), SKY_OK) << sky_client_last_error(c);
    uint64_t id = 0;
    ASSERT_EQ(sky_client_request_frame(c, &id), SKY_OK);  // the built-in weather, drawn synchronously
    ASSERT_EQ(sky_client_wait_frame(c, id - 1, 30000), SKY_OK) << sky_client_last_error(c);

    RawClient raw;
    ASSERT_TRUE(raw.open(d.socketPath));
    nlohmann::json s = raw.request({{"type", "load_weather"}, {"path", wx}});
    ASSERT_EQ(s.value("type", ""), "ok") << s;
    ASSERT_TRUE(waitForStatus(raw, [&](const nlohmann::json& j) { return j["weather"]["source"] == wx; }, 10000, &s))
        << s;
    // Frames on request (render_rate_hz 0) until one draws the file: the last frame published is it.
    int frames = 0;
    for (; frames < 200; ++frames)
    {
        ASSERT_EQ(sky_client_request_frame(c, &id), SKY_OK);
        ASSERT_EQ(sky_client_wait_frame(c, id - 1, 30000), SKY_OK) << sky_client_last_error(c);
        s = raw.request({{"type", "status"}});
        if (s["frame_id"] == id && s["weather"]["frame"]["source"] == wx)
            break;
    }
    ASSERT_LT(frames, 200) << s;
    EXPECT_EQ(s["weather"]["frame"]["valid_time"], "2026-06-21T16:00:00Z") << s;  // sampled at the frame's time
    SkyFrame f{};
    ASSERT_EQ(sky_client_acquire_frame(c, &f), SKY_OK);
    ASSERT_EQ(f.frame_id, id);
    std::vector<uint8_t> pixels = framePixels(f);
    ASSERT_EQ(sky_client_release_frame(c, &f), SKY_OK);
    sky_client_close(c);

    sky::ImageRgba8 ref;
    ASSERT_TRUE(renderOneShotOfTestView(tmp.path, "--weather " + wx, ref, error)) << error;
    EXPECT_TRUE(ref.pixels == pixels) << "the first frame that draws the loaded weather differs from the one-shot render";
    // The sidecars say which weather was drawn: the service's of that frame, and the one-shot's.
    s = raw.request({{"type", "write_files"}, {"prefix", "svc"}}, 20000);  // beneath files_root
    ASSERT_EQ(s.value("type", ""), "ok") << s;
    for (const std::string& json : {d.filesRoot() + "/svc.json", tmp.path + "/ref.json"})
    {
        std::ifstream in(json);
        nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
        EXPECT_EQ(j["weather"], wx) << json;
        EXPECT_EQ(j["weatherValidTime"], "2026-06-21T16:00:00Z") << json;
    }
    std::printf("the loaded weather was drawn from the %d. frame after the load on\n", frames + 1);
    EXPECT_EQ(d.stop(), 0);
}

// A client killed with SIGKILL while it holds a frame: the service notices nothing (no lock, no
// blocking) and keeps publishing; the slot is simply overwritten on its turn.
TEST(ServiceFrames, ClientKilledMidRead)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(50);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;

    int ready[2];
    ASSERT_EQ(pipe(ready), 0);
    pid_t child = fork();
    if (child == 0)
    {
        SkyClient* c = nullptr;
        SkyFrame f{};
        if (sky_client_connect(d.socketPath.c_str(), "victim", &c) != SKY_OK || sky_client_subscribe_shm(c) != SKY_OK ||
            sky_client_wait_frame(c, 0, 20000) != SKY_OK || sky_client_acquire_frame(c, &f) != SKY_OK)
            _exit(1);
        char one = 1;
        (void)!write(ready[1], &one, 1);
        for (;;)  // holds the frame, mid-read, until killed
            pause();
    }
    char byte = 0;
    ASSERT_EQ(read(ready[0], &byte, 1), 1);
    ::kill(child, SIGKILL);
    waitpid(child, nullptr, 0);

    SkyClient* c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "survivor", &c), SKY_OK);
    ASSERT_EQ(sky_client_subscribe_shm(c), SKY_OK);
    uint64_t a = nextFrame(c, 0);
    ASSERT_GT(a, 0u);
    uint64_t b = nextFrame(c, a + 5);  // every slot came round at least once since the kill
    EXPECT_GT(b, a + 5);
    sky_client_close(c);
    EXPECT_TRUE(d.running());
    EXPECT_EQ(d.stop(), 0);
    close(ready[0]);
    close(ready[1]);
}

// Eight clients at once, each with its own connection and mapping, all see new frames.
TEST(ServiceFrames, EightClients)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(50);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    std::atomic<int> ok{0};
    std::vector<std::thread> threads;
    for (int i = 0; i < 8; ++i)
    {
        threads.emplace_back([&, i] {
            SkyClient* c = nullptr;
            std::string name = "client" + std::to_string(i);
            if (sky_client_connect(d.socketPath.c_str(), name.c_str(), &c) != SKY_OK)
                return;
            char status[8192];
            bool good = sky_client_subscribe_shm(c) == SKY_OK && sky_client_status(c, status, sizeof status) == SKY_OK;
            uint64_t last = 0;
            for (int k = 0; good && k < 5; ++k)
            {
                uint64_t id = nextFrame(c, last);
                good = id > last;
                last = id;
            }
            sky_client_close(c);
            if (good)
                ++ok;
        });
    }
    for (std::thread& t : threads)
        t.join();
    EXPECT_EQ(ok.load(), 8);
    EXPECT_EQ(d.stop(), 0);
}

// The service restarts under a connected client: the client's next request says SKY_ERR_CLOSED, and a
// new connection to the new service works.
TEST(ServiceFrames, ClientReconnectsAfterRestart)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(20);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    SkyClient* c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "restart", &c), SKY_OK);
    ASSERT_EQ(sky_client_subscribe_shm(c), SKY_OK);
    ASSERT_GT(nextFrame(c, 0), 0u);
    ASSERT_EQ(d.stop(), 0);
    ASSERT_TRUE(d.restart(error)) << error;
    uint64_t id = 0;
    EXPECT_EQ(sky_client_request_frame(c, &id), SKY_ERR_CLOSED);
    sky_client_close(c);
    c = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "restart", &c), SKY_OK);
    ASSERT_EQ(sky_client_subscribe_shm(c), SKY_OK);
    EXPECT_GT(nextFrame(c, 0), 0u);
    sky_client_close(c);
    EXPECT_EQ(d.stop(), 0);
}

// While every subscriber imports the exported images, the ring's slots carry the frame's facts but no display
// pixels (the GPU's copy into the export is the whole frame path); a shared-memory subscriber brings them back.
TEST(ServiceFrames, VulkanOnlySubscribersGetNoDisplayPixelsInTheRing)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(20), error)) << error;
    SkyClient* vulkan = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "vulkan", &vulkan), SKY_OK);
    SkyExportedFrames exported{};
    ASSERT_EQ(sky_client_subscribe_vulkan(vulkan, &exported), SKY_OK) << sky_client_last_error(vulkan);
    for (uint32_t i = 0; i < exported.slot_count; ++i)
        for (int fd : {exported.frame[i].memory_fd, exported.shadow[i].memory_fd})
            if (fd >= 0)
                close(fd);
    if (exported.timeline_semaphore_fd >= 0)
        close(exported.timeline_semaphore_fd);
    // A frame begun after the subscription was served (the export exists from then on).
    uint64_t after = nextFrame(vulkan, 0);
    ASSERT_GT(after, 0u);
    after = nextFrame(vulkan, after + 2);
    ASSERT_GT(after, 0u);
    SkyFrame f{};
    ASSERT_EQ(sky_client_acquire_frame(vulkan, &f), SKY_OK);
    EXPECT_EQ(f.pixels, nullptr);
    EXPECT_EQ(f.layers[SKY_LAYER_DISPLAY].format, 0u);
    EXPECT_GT(f.width, 0u) << "the slot still describes the frame";
    sky_client_release_frame(vulkan, &f);

    SkyClient* shm = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "shm", &shm), SKY_OK);
    ASSERT_EQ(sky_client_subscribe_shm(shm), SKY_OK);
    const uint64_t subscribed = nextFrame(shm, 0);
    ASSERT_GT(subscribed, 0u);
    ASSERT_GT(nextFrame(shm, subscribed + 2), 0u);
    SkyFrame g{};
    ASSERT_EQ(sky_client_acquire_frame(shm, &g), SKY_OK);
    EXPECT_NE(g.pixels, nullptr);
    EXPECT_EQ(g.format, SKY_FORMAT_RGBA8_SRGB);
    sky_client_release_frame(shm, &g);
    sky_client_close(shm);
    sky_client_close(vulkan);
    EXPECT_EQ(d.stop(), 0);
}

// subscribe with transport vulkan: the reply describes one exported image per slot (and a shadow image
// per slot with shadow maps on) and the fds arrive with it; frames keep coming afterwards (the export
// runs inside the frame loop). The import itself is tested by the client library's tests.
TEST(ServiceFrames, VulkanSubscribeSendsFds)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(20);
    cfg.extraService = "shadow_map_size = 16\nshadow_map_extent_m = 20000\n";
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    std::vector<int> fds;
    nlohmann::json r = c.requestWithFds({{"type", "subscribe"}, {"transport", "vulkan"}, {"id", "v"}}, fds);
    ASSERT_EQ(r.value("type", ""), "subscribed") << r;
    EXPECT_EQ(r["id"], "v");
    EXPECT_EQ(r["transport"], "vulkan");
    ASSERT_EQ(r["images"].size(), 3u) << r;
    EXPECT_EQ(r["slots"], 3);
    size_t expected = 3 + 3 + (r["timeline_semaphore"].get<bool>() ? 1 : 0);
    EXPECT_EQ(fds.size(), expected);
    for (int fd : fds)
        close(fd);
    nlohmann::json s = c.request({{"type", "status"}});
    uint64_t frame = s["frame_id"];
    ASSERT_TRUE(waitForStatus(c, [&](const nlohmann::json& j) { return j["frame_id"].get<uint64_t>() > frame + 3; },
                              10000, &s))
        << s;
    EXPECT_TRUE(s["last_render_error"].is_null()) << s;
    EXPECT_EQ(d.stop(), 0);
}
