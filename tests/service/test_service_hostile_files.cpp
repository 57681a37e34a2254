// SPDX-License-Identifier: MIT
// End-to-end: hostile weather files and configs. The daemon keeps serving, says what was
// wrong, and never wedges its weather loader.
#include "tests/service/service_harness.h"

#include "weather_ingest/crc32c.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

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

/// A snapshot whose header (checksum included) is valid and whose metadata declares a level field of
/// 8192 x 8192 x 1000 floats; the file is a hole of that length (12 KB stored).
bool writeHugeSparseSnapshot(const std::string& path)
{
    const uint64_t values = uint64_t(8192) * 8192 * 1000;
    json meta = {{"validTimeUnixS", 0},
                 {"grid", {{"lat0Deg", 81.9}, {"lon0Deg", 0.0}, {"dLatDeg", -0.02}, {"dLonDeg", 0.04}, {"nLat", 8192},
                           {"nLon", 8192}}},
                 {"layers", json::array()},
                 {"levelFields", {{{"name", "q"}, {"units", "kg/kg"}, {"pressurePa", std::vector<float>(1000, 5e4f)}}}},
                 {"provenance", json::object()},
                 {"arrays", {{{"name", "levelFields/0/values"}, {"type", "f32"}, {"count", values}}}}};
    const std::string text = meta.dump();
    const uint64_t total = 32 + 4 + text.size() + values * 4;
    uint8_t header[32] = {0x89, 'S', 'K', 'Y', 'W', 'X', '\r', '\n'};
    const uint32_t version = 1, count = 1, metaBytes = uint32_t(text.size());
    const uint64_t payloadBytes = total - 32;
    std::memcpy(header + 8, &version, 4);
    std::memcpy(header + 12, &count, 4);
    std::memcpy(header + 16, &payloadBytes, 8);
    const uint32_t headerCrc = sky::crc32c(header, 28);
    std::memcpy(header + 28, &headerCrc, 4);
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    bool ok = fd >= 0 && ::write(fd, header, 32) == 32 && ::write(fd, &metaBytes, 4) == 4 &&
              ::write(fd, text.data(), text.size()) == ssize_t(text.size()) && ::ftruncate(fd, off_t(total)) == 0;
    if (fd >= 0)
        ::close(fd);
    return ok;
}

}  // namespace

// Regression: the loader thread allocated the declared 256 GB, std::bad_alloc escaped it and the
// daemon aborted (rc 134). Now the file is refused, named in status, and the daemon keeps serving.
TEST(ServiceHostile, HugeDeclaredSnapshotIsRefusedAndTheDaemonLives)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    const std::string huge = tmp.path + "/huge.skywx";
    ASSERT_TRUE(writeHugeSparseSnapshot(huge));
    json r = c.request({{"type", "load_weather"}, {"path", huge}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    json s;
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 20000, &s))
        << s << readFile(d.logPath);
    EXPECT_EQ(s["weather"]["source"], "builtin");
    EXPECT_TRUE(d.running());
    EXPECT_EQ(d.stop(), 0) << readFile(d.logPath);
}

// Regression: load_weather of a FIFO blocked the loader thread in open() for good: every later
// load was dropped, and SIGTERM hung. A FIFO renamed into the watched folder did the same. Both are
// refused at once now (the watcher does not even queue it), and a good file loads right after.
TEST(ServiceHostile, FifoNeverWedgesTheWeatherLoader)
{
    TempDir tmp;
    const std::string wx = tmp.path + "/weather";
    std::filesystem::create_directory(wx);
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    cfg.weatherDir = wx;
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    const std::string fifo = tmp.path + "/pipe.skywx";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    json r = c.request({{"type", "load_weather"}, {"path", fifo}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    json s;
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 10000, &s))
        << s;
    ASSERT_EQ(::rename(fifo.c_str(), (wx + "/pipe.skywx").c_str()), 0);
    const std::string good = wx + "/good.skywx";
    ASSERT_TRUE(writeBuiltinSnapshot(good, kMidsummerNoon, error)) << error;
    ASSERT_TRUE(waitForStatus(c, [&](const json& j) { return j["weather"]["source"] == good; }, 10000, &s)) << s;
    EXPECT_EQ(d.stop(), 0) << readFile(d.logPath);
}

// Regression: a client could queue any number of write_files (the render thread takes jobs before
// frames: 200 stalled rendering for 1.7 s) and any number of files subscriptions (each one costs every
// frame). Now a client has at most 8 jobs queued and 4 files subscriptions (the same dir again replaces
// its subscription); the rest are answered busy, and SIGTERM with jobs queued still exits cleanly.
TEST(ServiceHostile, PerClientWorkIsBounded)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    json r = c.request({{"type", "render"}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    std::string flood;
    for (int i = 0; i < 100; ++i)
        flood += json({{"type", "write_files"}, {"id", i}, {"prefix", "f" + std::to_string(i)}}).dump() + "\n";
    ASSERT_TRUE(c.sendRaw(flood));
    int ok = 0, busy = 0;
    for (int i = 0; i < 100; ++i)
    {
        auto line = c.readLine(20000);
        ASSERT_TRUE(line) << "reply " << i;
        json e = json::parse(*line, nullptr, false);
        if (e.value("type", "") == "ok")
            ++ok;
        else if (e.value("message", "").find("busy") != std::string::npos)
            ++busy;
    }
    EXPECT_GT(busy, 0) << ok << " written";
    EXPECT_EQ(ok + busy, 100);

    for (int i = 0; i < 5; ++i)
        std::filesystem::create_directory(d.filesRoot() + "/d" + std::to_string(i));
    for (int i = 0; i < 3; ++i)  // the same dir three times: one subscription
    {
        r = c.request({{"type", "subscribe"}, {"transport", "files"}, {"dir", "d4"}, {"every", 1000}});
        EXPECT_EQ(r.value("type", ""), "ok") << r;
    }
    for (int i = 0; i < 4; ++i)
    {
        const std::string dir = "d" + std::to_string(i);
        r = c.request({{"type", "subscribe"}, {"transport", "files"}, {"dir", dir}, {"every", 1000}});
        EXPECT_EQ(r.value("type", ""), i < 3 ? "ok" : "error") << i << " " << r;
    }
    EXPECT_NE(r.value("message", "").find("busy"), std::string::npos) << r;

    ASSERT_TRUE(c.sendRaw(flood));  // queued jobs when SIGTERM comes: dropped, the exit is clean
    EXPECT_EQ(d.stop(), 0) << readFile(d.logPath);
}

// Regression: write_files wrote wherever the prefix pointed (absolute, "..", through links) and
// replaced any file the daemon's user could write. Now every name is relative to files_root, resolved
// beneath it without following links, a file the daemon did not write is never replaced, and each file
// request is logged with the peer's uid.
TEST(ServiceHostile, FileOutputStaysBeneathFilesRoot)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    ASSERT_EQ(c.request({{"type", "render"}}).value("type", ""), "ok");
    const std::string outside = tmp.path + "/outside";
    std::filesystem::create_directory(outside);
    ASSERT_EQ(::symlink(outside.c_str(), (d.filesRoot() + "/link").c_str()), 0);
    std::ofstream(d.filesRoot() + "/victim.json") << "keep";
    auto writeFiles = [&](const std::string& prefix) {
        return c.request({{"type", "write_files"}, {"prefix", prefix}}, 20000);
    };
    for (const std::string& bad : {outside + "/abs", std::string("../outside/up"), std::string("a/../../up")})
    {
        json r = writeFiles(bad);
        EXPECT_EQ(r.value("code", ""), "out_of_range") << bad << " -> " << r;
        EXPECT_EQ(r.value("field", ""), "prefix") << r;
    }
    json r = writeFiles("link/through");
    EXPECT_EQ(r.value("type", ""), "error") << r;
    EXPECT_NE(r.value("message", "").find("not a folder"), std::string::npos) << r;
    EXPECT_TRUE(std::filesystem::is_empty(outside)) << "a file was written outside files_root";
    r = writeFiles("victim");
    EXPECT_EQ(r.value("type", ""), "error") << r;
    EXPECT_NE(r.value("message", "").find("not written by this service"), std::string::npos) << r;
    EXPECT_EQ(readFile(d.filesRoot() + "/victim.json"), "keep");
    // Its own files it writes, and may write again.
    r = writeFiles("mine");
    EXPECT_EQ(r.value("type", ""), "ok") << r;
    r = writeFiles("mine");
    EXPECT_EQ(r.value("type", ""), "ok") << r;
    EXPECT_TRUE(std::filesystem::is_regular_file(d.filesRoot() + "/mine.png"));
    r = c.request({{"type", "subscribe"}, {"transport", "files"}, {"dir", "link"}, {"every", 1}});
    EXPECT_EQ(r.value("type", ""), "error") << r;
    EXPECT_EQ(d.stop(), 0);
    EXPECT_NE(readFile(d.logPath).find("write_files mine (client 2, uid " + std::to_string(::getuid()) + ")"),
              std::string::npos)
        << readFile(d.logPath);
}

// Regression: the default ring name carried the daemon's pid: a killed daemon's ring (25 MB at
// 1080p) stayed in /dev/shm for good, as a restart made a new one. The name now follows the socket, so
// the restarted daemon finds the stale ring (its writer is gone), replaces it, and removes it on exit.
TEST(ServiceHostile, KilledDaemonsRingIsReclaimedByTheRestart)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    cfg.defaultShmName = true;
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    auto ringName = [&] {
        RawClient c;
        if (!c.open(d.socketPath))
            return std::string();
        return c.request({{"type", "subscribe"}, {"transport", "shm"}}).value("shm_name", std::string());
    };
    const std::string first = ringName();
    ASSERT_FALSE(first.empty());
    EXPECT_EQ(first.find(std::to_string(d.pid)), std::string::npos) << first;
    d.stop(SIGKILL);
    ASSERT_TRUE(std::filesystem::exists("/dev/shm" + first)) << "a killed daemon leaves its ring";
    ASSERT_TRUE(d.restart(error)) << error;
    EXPECT_EQ(ringName(), first);
    EXPECT_EQ(d.stop(), 0) << readFile(d.logPath);
    EXPECT_FALSE(std::filesystem::exists("/dev/shm" + first)) << first << " leaked";
}

// Regression: a newline in a load_weather path or a client name went into the log as it was, so a
// client could write lines that looked like the service's own. Control characters are escaped now.
TEST(ServiceHostile, ClientTextCannotForgeLogLines)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.connect(d.socketPath));
    const std::string name = "ig\n2026-06-21T12:00:00.000Z error FORGED-NAME";
    json r = c.request({{"type", "hello"}, {"protocol", 1}, {"client", name}});
    ASSERT_EQ(r.value("type", ""), "hello") << r;
    r = c.request({{"type", "load_weather"}, {"path", "/nowhere.skywx\n2026-06-21T12:00:00.000Z error FORGED-PATH"}});
    ASSERT_EQ(r.value("type", ""), "ok") << r;
    json s;
    ASSERT_TRUE(waitForStatus(c, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 10000, &s)) << s;
    c.close();
    EXPECT_EQ(d.stop(), 0);
    std::istringstream log(readFile(d.logPath));
    bool escaped = false;
    for (std::string line; std::getline(log, line);)
    {
        EXPECT_NE(line.rfind("2026-06-21T12:00:00.000Z error FORGED", 0), 0u) << "forged line: " << line;
        escaped = escaped || line.find("\\x0a2026-06-21T12:00:00.000Z error FORGED-PATH") != std::string::npos;
    }
    EXPECT_TRUE(escaped) << readFile(d.logPath);
}

// Why a file was refused tells whether a path exists and what it is: a client of another uid (on a
// socket_mode 0o666 service) is told only "cannot load". Needs root to act as another user.
TEST(ServiceHostile, OtherUsersLearnNothingAboutPaths)
{
    if (::geteuid() != 0)
        GTEST_SKIP() << "needs root to connect as another uid";
    TempDir tmp;
    ::chmod(tmp.path.c_str(), 0755);
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames();
    cfg.extraService = "socket_mode = 0o666";
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient own;
    ASSERT_TRUE(own.open(d.socketPath));
    ASSERT_EQ(own.request({{"type", "load_weather"}, {"path", "/root/no-such.skywx"}}).value("type", ""), "ok");
    json s;
    ASSERT_TRUE(waitForStatus(own, [](const json& j) { return j["weather"]["last_error"].is_string(); }, 10000, &s));
    EXPECT_NE(s["weather"]["last_error"].get<std::string>().find("No such file"), std::string::npos) << s;
    int pipeFds[2];
    ASSERT_EQ(::pipe(pipeFds), 0);
    const pid_t child = ::fork();
    if (child == 0)
    {
        ::close(pipeFds[0]);
        std::string seen = "no connection";
        if (::setgid(65534) == 0 && ::setuid(65534) == 0)
        {
            RawClient other;
            if (other.open(d.socketPath))
                seen = other.request({{"type", "status"}})["weather"]["last_error"].dump();
        }
        ssize_t n = ::write(pipeFds[1], seen.data(), seen.size());
        ::_exit(n == ssize_t(seen.size()) ? 0 : 1);
    }
    ::close(pipeFds[1]);
    std::string seen;
    char buffer[512];
    for (ssize_t n; (n = ::read(pipeFds[0], buffer, sizeof buffer)) > 0;)
        seen.append(buffer, size_t(n));
    ::close(pipeFds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_EQ(seen, "\"/root/no-such.skywx: cannot load\"");
    EXPECT_EQ(d.stop(), 0);
}
