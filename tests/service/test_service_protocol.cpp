// SPDX-License-Identifier: MIT
// End-to-end over a raw socket: every malformed message of PROTOCOL.md gets its error code and changes
// nothing; a client that never reads is cut off without the service ever blocking.
#include "tests/service/service_harness.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fcntl.h>
#include <sys/socket.h>

using namespace skytest;
using nlohmann::json;

namespace
{

/// What a malformed request must not change (frame counters and uptime move on their own).
json stableState(const json& status)
{
    return {status["view"], status["time"], status["rate"], status["weather"]["source"],
            status["weather"]["valid_time"], status["clients"]};
}

}  // namespace

TEST(ServiceProtocol, MalformedMessagesChangeNothing)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, DaemonConfig{}, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.connect(d.socketPath));

    // Before hello.
    json r = c.request({{"type", "status"}, {"id", 7}});
    EXPECT_EQ(r.value("code", ""), "not_hello") << r;
    EXPECT_EQ(r["id"], 7);
    r = c.request({{"type", "hello"}, {"protocol", 2}});
    EXPECT_EQ(r.value("code", ""), "bad_version") << r;
    r = c.request({{"type", "hello"}, {"protocol", 1}, {"client", "malformed"}});
    ASSERT_EQ(r.value("type", ""), "hello") << r;
    EXPECT_EQ(r["max_width"], 128);

    json before = c.request({{"type", "status"}});
    ASSERT_EQ(before.value("type", ""), "status") << before;

    struct Case
    {
        std::string line, code, field;
    };
    const std::string big(70000, 'x');
    std::vector<Case> cases = {
        {"this is not json", "bad_json", ""},
        {"[1,2,3]", "bad_json", ""},
        {"{\"type\":\"set_view\"", "bad_json", ""},
        {"{}", "unknown_type", ""},
        {"{\"type\":\"fly_to_the_moon\"}", "unknown_type", ""},
        {"{\"type\":42}", "unknown_type", ""},
        {"{\"type\":\"set_view\"}", "missing_field", "view"},
        {"{\"type\":\"set_view\",\"view\":5}", "bad_type", "view"},
        {"{\"type\":\"set_view\",\"view\":{\"lat\":\"north\"}}", "bad_type", "view.lat"},
        {"{\"type\":\"set_view\",\"view\":{\"lat\":91}}", "out_of_range", "view.lat"},
        // Atomic: lat is fine, lon is not, so lat must not change either.
        {"{\"type\":\"set_view\",\"view\":{\"lat\":10,\"lon\":1000}}", "out_of_range", "view.lon"},
        {"{\"type\":\"set_view\",\"view\":{\"width\":100000}}", "out_of_range", "view.width"},
        {"{\"type\":\"set_view\",\"view\":{\"width\":129}}", "out_of_range", "view.width"},
        {"{\"type\":\"set_view\",\"view\":{\"fov\":0}}", "out_of_range", "view.fov"},
        {"{\"type\":\"set_view\",\"view\":{\"width\":64.5}}", "bad_type", "view.width"},
        // Asymmetric frusta: the parser's checks, then the service's own (open bounds, left + right).
        {"{\"type\":\"set_view\",\"view\":{\"left\":40,\"right\":0,\"up\":20}}", "missing_field", "view.down"},
        {"{\"type\":\"set_view\",\"view\":{\"fov\":50,\"left\":40,\"right\":0,\"up\":20,\"down\":20}}",
         "out_of_range", "view.fov"},
        {"{\"type\":\"set_view\",\"view\":{\"left\":85,\"right\":0,\"up\":20,\"down\":20}}", "out_of_range",
         "view.left"},
        {"{\"type\":\"set_view\",\"view\":{\"lat\":10,\"left\":40,\"right\":-39.5,\"up\":20,\"down\":20}}",
         "out_of_range", "view"},
        {"{\"type\":\"set_time\",\"time\":\"2026-13-45T00:00:00Z\"}", "out_of_range", "time"},
        {"{\"type\":\"set_time\",\"time\":\"yesterday\"}", "out_of_range", "time"},
        {"{\"type\":\"set_time\",\"time\":12}", "bad_type", "time"},
        {"{\"type\":\"set_time\",\"rate\":1e9}", "out_of_range", "rate"},
        {"{\"type\":\"load_weather\"}", "missing_field", "path"},
        {"{\"type\":\"load_weather\",\"path\":7}", "bad_type", "path"},
        {"{\"type\":\"subscribe\",\"transport\":\"pigeon\"}", "out_of_range", "transport"},
        {"{\"type\":\"subscribe\",\"transport\":\"files\",\"dir\":\"/tmp\",\"every\":0}", "out_of_range", "every"},
        {"{\"type\":\"hello\",\"protocol\":\"one\"}", "bad_type", "protocol"},
        {big, "too_long", ""},
    };
    for (const Case& k : cases)
    {
        json e = c.requestLine(k.line);
        ASSERT_TRUE(e.is_object()) << "no reply to " << k.line.substr(0, 80);
        EXPECT_EQ(e.value("type", ""), "error") << k.line.substr(0, 80);
        EXPECT_EQ(e.value("code", ""), k.code) << k.line.substr(0, 80) << " -> " << e;
        if (!k.field.empty())
        {
            EXPECT_EQ(e.value("field", ""), k.field) << k.line.substr(0, 80) << " -> " << e;
        }
        EXPECT_FALSE(e.value("message", "").empty());
    }
    // A flood of requests: every one answered, in order, the connection still fine afterwards.
    std::string flood;
    for (int i = 0; i < 2000; ++i)
        flood += "{\"type\":\"render_me\",\"id\":" + std::to_string(i) + "}\n";
    ASSERT_TRUE(c.sendRaw(flood));
    for (int i = 0; i < 2000; ++i)
    {
        auto line = c.readLine();
        ASSERT_TRUE(line) << "reply " << i;
        json e = json::parse(*line, nullptr, false);
        ASSERT_EQ(e["id"], i);
        ASSERT_EQ(e["code"], "unknown_type");
    }
    json after = c.request({{"type", "status"}});
    ASSERT_EQ(after.value("type", ""), "status") << after;
    EXPECT_EQ(stableState(before), stableState(after));

    // A display wall's channel: status gives the view as set_view took it, and fov makes it symmetric again.
    json ok = c.request({{"type", "set_view"}, {"view", {{"left", 40}, {"right", 0}, {"up", 20}, {"down", 15}}}});
    EXPECT_EQ(ok.value("type", ""), "ok") << ok;
    json view = c.request({{"type", "status"}})["view"];
    EXPECT_EQ(view.value("left", 0.0), 40.0) << view;
    EXPECT_EQ(view.value("down", 0.0), 15.0) << view;
    EXPECT_FALSE(view.contains("fov")) << view;
    ok = c.request({{"type", "set_view"}, {"view", {{"fov", 50}}}});
    EXPECT_EQ(ok.value("type", ""), "ok") << ok;
    view = c.request({{"type", "status"}})["view"];
    EXPECT_EQ(view.value("fov", 0.0), 50.0) << view;
    EXPECT_FALSE(view.contains("left")) << view;

    // Eight too-long lines in a row close the connection; others are unaffected.
    RawClient other;
    ASSERT_TRUE(other.open(d.socketPath));
    for (int i = 0; i < 8; ++i)
        c.sendRaw(big + "\n");
    EXPECT_TRUE(c.closedByPeer(5000));
    EXPECT_EQ(other.request({{"type", "status"}}).value("type", ""), "status");
    EXPECT_EQ(d.stop(), 0);
}

// A client that sends requests but never reads a reply: its replies pile up past 1 MiB and the service
// disconnects it, while another client's requests are answered promptly the whole time.
TEST(ServiceProtocol, NeverReadingClientIsDisconnected)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    DaemonConfig cfg = tinyFrames(20);
    ASSERT_TRUE(d.start(tmp.path, cfg, error)) << error;
    RawClient deaf, other;
    ASSERT_TRUE(deaf.open(d.socketPath));
    ASSERT_TRUE(other.open(d.socketPath));
    int rcv = 4096;  // small receive buffer: the replies pile up in the service, not in the kernel
    setsockopt(deaf.fd, SOL_SOCKET, SO_RCVBUF, &rcv, sizeof rcv);
    fcntl(deaf.fd, F_SETFL, fcntl(deaf.fd, F_GETFL) | O_NONBLOCK);
    const std::string req = "{\"type\":\"status\"}\n";
    std::string batch;
    for (int i = 0; i < 200; ++i)
        batch += req;
    bool cut = false;
    double slowestMs = 0;
    auto start = std::chrono::steady_clock::now();
    while (!cut && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    {
        ssize_t n = ::send(deaf.fd, batch.data(), batch.size(), MSG_NOSIGNAL);
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)
            cut = true;
        auto t0 = std::chrono::steady_clock::now();
        json s = other.request({{"type", "status"}}, 2000);
        slowestMs = std::max(slowestMs, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        ASSERT_EQ(s.value("type", ""), "status") << "service stopped answering";
        if (s.value("clients", 0) == 1)
            cut = true;
    }
    EXPECT_TRUE(cut) << "the deaf client was never disconnected";
    EXPECT_LT(slowestMs, 1000.0) << "another client waited " << slowestMs << " ms";
    EXPECT_TRUE(deaf.closedByPeer(5000));
    EXPECT_EQ(d.stop(), 0);
}
