// SPDX-License-Identifier: MIT
// End-to-end: weather loading (request and watched folder), SIGHUP and SIGTERM.
#include "tests/service/service_harness.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <set>
#include <sys/stat.h>
#include <thread>

using namespace skytest;
using nlohmann::json;

namespace
{

constexpr int64_t kMidsummerNoon = 1782043200;  // 2026-06-21T12:00:00Z

std::string readFile(const std::string& path)
{
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

// A corrupt snapshot is refused (old weather kept, status names the error); a good one replaces the
// weather (status shows the new valid time) and frames keep coming through both.
TEST(ServiceControl, LoadWeatherBadThenGood)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(20);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    json s = c.request({{"type", "status"}});
    ASSERT_EQ(s["weather"]["source"], "builtin") << s;

    std::string bad = tmp.path + "/corrupt.skywx";
    std::ofstream(bad) << "\x89SKYWX\r\n but the rest is garbage";
    json r = c.request({{"type", "load_weather"}, {"path", bad}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    EXPECT_EQ(r["queued"], true);
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 10000, &s)) << s;
    EXPECT_EQ(s["weather"]["source"], "builtin");
    EXPECT_NE(s["weather"]["last_error"].get<std::string>().find("corrupt.skywx"), std::string::npos) << s;

    std::string good = tmp.path + "/good.skywx";
    ASSERT_TRUE(writeBuiltinSnapshot(good, kMidsummerNoon - 6 * 3600, error)) << error;
    r = c.request({{"type", "load_weather"}, {"path", good}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    ASSERT_TRUE(waitForStatus(c, [&](const json& j) { return j["weather"]["source"] == good; }, 10000, &s)) << s;
    EXPECT_EQ(s["weather"]["valid_time"], "2026-06-21T06:00:00Z");
    EXPECT_TRUE(s["weather"]["last_error"].is_null());
    // The frames draw it once its window is ready (made on the worker thread, not by a frame).
    ASSERT_TRUE(waitForStatus(
        c, [&](const json& j) { return j["weather"]["frame"].is_object() && j["weather"]["frame"]["source"] == good; },
        10000, &s))
        << s;
    EXPECT_EQ(s["weather"]["frame"]["version"], s["weather"]["version"]) << s;
    EXPECT_EQ(s["windows"]["made_on_frame_path"], 1) << "only the first frame makes its window: " << s;
    EXPECT_GE(s["windows"]["from_worker"], 1) << s;
    uint64_t frame = s["frame_id"];
    ASSERT_TRUE(waitForStatus(c, [&](const json& j) { return j["frame_id"].get<uint64_t>() > frame + 3; }, 10000, &s));
    EXPECT_EQ(d.stop(), 0);
}

// With the clock running (rate 120: a re-sample every 0.5 s of real time) the weather is re-sampled
// every 60 s of simulated time, each sample prepared ahead on the worker thread: the frames draw a new
// valid time every time, and no frame makes a window itself after the first.
TEST(ServiceControl, RunningClockResamplesOffTheFramePath)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(20), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    json s;
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["frame"].is_object(); }, 10000, &s)) << s;
    ASSERT_EQ(s["windows"]["made_on_frame_path"], 1) << s;
    json r = c.request({{"type", "set_time"}, {"rate", 120}});  // no time given: no jump, the clock runs on
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    std::set<std::string> validTimes{s["weather"]["frame"]["valid_time"].get<std::string>()};
    ASSERT_TRUE(waitForStatus(
        c,
        [&](const json& j) {
            validTimes.insert(j["weather"]["frame"]["valid_time"].get<std::string>());
            return validTimes.size() >= 4;
        },
        30000, &s))
        << s;
    EXPECT_EQ(s["windows"]["made_on_frame_path"], 1) << "a re-sample made its window on the frame path: " << s;
    EXPECT_GE(s["windows"]["from_worker"], 3) << s;
    EXPECT_LE(s["weather"]["frame"]["valid_time"].get<std::string>(), s["time"].get<std::string>()) << s;
    EXPECT_EQ(d.stop(), 0);
}

// A snapshot file written into weather_dir (atomically, as sky-ingest does) is picked up by itself.
TEST(ServiceControl, WeatherDirIsWatched)
{
    TempDir tmp;
    std::string wx = tmp.path + "/weather";
    std::filesystem::create_directory(wx);
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    cfg.weatherDir = wx;
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    std::string dropped = wx + "/gfs-latest.skywx";
    ASSERT_TRUE(writeBuiltinSnapshot(dropped, kMidsummerNoon + 3 * 3600, error)) << error;
    json s;
    ASSERT_TRUE(waitForStatus(c, [&](const json& j) { return j["weather"]["source"] == dropped; }, 10000, &s)) << s;
    EXPECT_EQ(s["weather"]["valid_time"], "2026-06-21T15:00:00Z");
    // A file that is not a snapshot, dropped the same way, is logged and ignored.
    std::ofstream(wx + "/junk.skywx") << "junk";
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 10000, &s)) << s;
    EXPECT_EQ(s["weather"]["source"], dropped);
    EXPECT_EQ(d.stop(), 0);
    EXPECT_NE(readFile(d.logPath).find("junk.skywx"), std::string::npos);
}

// SIGHUP with a broken config: logged, the service keeps running with the old one. SIGHUP with a good
// one applies it (here: the render rate, visible in status).
TEST(ServiceControl, SighupReloads)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    std::string original = readFile(d.configPath);
    std::ofstream(d.configPath) << original << "\n[march]\nmax_view_step = 3\n";
    ::kill(d.pid, SIGHUP);
    RawClient c;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    ASSERT_TRUE(d.running());
    ASSERT_TRUE(c.open(d.socketPath));
    json s = c.request({{"type", "status"}});
    EXPECT_EQ(s["render_rate_hz"], 0.0) << s;
    EXPECT_NE(readFile(d.logPath).find("max_view_step"), std::string::npos);

    std::string faster = original;
    faster.replace(faster.find("render_rate_hz = 0"), 18, "render_rate_hz = 5");
    std::ofstream(d.configPath) << faster;
    ::kill(d.pid, SIGHUP);
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["render_rate_hz"] == 5.0; }, 5000, &s)) << s;
    EXPECT_EQ(d.stop(), 0);
}

// The noise textures are made from noise.seed once, at start: a SIGHUP that changes the seed is refused,
// naming the key, while the rest of the file applies (the render rate), and frames go on.
TEST(ServiceControl, SighupRefusesANewNoiseSeed)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    std::string changed = readFile(d.configPath);
    changed.replace(changed.find("render_rate_hz = 0"), 18, "render_rate_hz = 5");
    std::ofstream(d.configPath) << changed << "\n[noise]\nseed = 99\n";
    ::kill(d.pid, SIGHUP);
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    json s;
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["render_rate_hz"] == 5.0; }, 5000, &s)) << s;
    EXPECT_NE(readFile(d.logPath).find("noise.seed changed (1 -> 99): takes effect after a restart"),
              std::string::npos)
        << readFile(d.logPath);
    const uint64_t framesBefore = s["frame_id"].get<uint64_t>();
    ASSERT_TRUE(waitForStatus(c, [&](const json& j) { return j["frame_id"].get<uint64_t>() > framesBefore; }, 5000, &s))
        << s;
    EXPECT_EQ(d.stop(), 0);
}

// SIGTERM: exit 0, the socket file and the shared-memory object are gone, no device memory left (the
// daemon exits 1 when its tracker is not back to zero).
TEST(ServiceControl, SigtermCleansUp)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(20);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    json sub = c.request({{"type", "subscribe"}, {"transport", "shm"}});
    ASSERT_EQ(sub.value("type", ""), "subscribed") << sub;
    std::string shm = "/dev/shm" + sub["shm_name"].get<std::string>();
    struct stat st{};
    ASSERT_EQ(stat(shm.c_str(), &st), 0) << shm;
    ASSERT_EQ(stat(d.socketPath.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
    EXPECT_EQ(d.stop(SIGTERM), 0) << readFile(d.logPath);
    EXPECT_NE(stat(shm.c_str(), &st), 0) << shm << " still exists";
    EXPECT_NE(stat(d.socketPath.c_str(), &st), 0) << "socket still exists";
    EXPECT_TRUE(c.closedByPeer(1000));
    EXPECT_NE(readFile(d.logPath).find("stopped cleanly"), std::string::npos);
}

// A bad config is refused before anything starts: exit 2, the file and the field named.
TEST(ServiceControl, BadConfigRefused)
{
    TempDir tmp;
    std::string path = tmp.path + "/bad.toml";
    std::ofstream(path) << "[service]\nrender_rate_hz = -3\n";
    std::string cmd = serviceBinary() + " --config " + path + " > " + tmp.path + "/out.log 2>&1";
    int status = std::system(cmd.c_str());
    EXPECT_EQ(WEXITSTATUS(status), 2);
    std::string out = readFile(tmp.path + "/out.log");
    EXPECT_NE(out.find("bad.toml"), std::string::npos) << out;
    EXPECT_NE(out.find("service.render_rate_hz"), std::string::npos) << out;
}
