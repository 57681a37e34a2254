// SPDX-License-Identifier: MIT
// End-to-end: a test host drives the real daemon over CIGI 3.3 on UDP. The ownship, the time and
// one global Stratus layer (base 1000 m, 600 m thick, 100 %) reach the frames: from 3000 m the deck lies
// below the horizon, from 500 m the sky is overcast; a Start of Frame comes back for every frame;
// Environmental Conditions Requests are answered from the same weather; a host of either byte order is
// answered in its own; bad datagrams are counted and the daemon renders on; two daemons fed one host
// stream each render their own View Definition. Tiny frames on lavapipe, quality "test", render rate 0
// (each host datagram and each client `render` asks for one frame).
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/client/skyclient.h"
#include "tests/cigi/cigi_host_datagram.h"
#include "tests/service/cigi_test_host.h"
#include "tests/service/service_harness.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <thread>

using namespace skytest;
using namespace sky::cigi;
using namespace sky::cigi::test;

namespace
{

constexpr double kLat = 44.3, kLon = 7.5;
constexpr uint32_t kDate = 6212026; // 21 June 2026, at 12:00 UTC: the sun high over the Alps
constexpr int kReplyTimeoutMs = 60000;

double undulationM(double lat, double lon)
{
    static GeoidGrid grid = []
    {
        GeoidGrid g;
        std::string error;
        g.load(defaultEgm96GridPath(), error);
        return g;
    }();
    return grid.undulationM(lat, lon);
}

/// A daemon with [cigi] on, rendering on request, and a libskyclient client subscribed to the clouds layer.
struct Ig
{
    TempDir tmp;
    Daemon daemon;
    uint16_t port = 0;
    SkyClient* client = nullptr;

    ~Ig() { sky_client_close(client); }

    bool start(uint16_t hostPort, int viewId, uint32_t width, uint32_t height, std::string& error)
    {
        port = freeUdpPort();
        DaemonConfig c = tinyFrames(0);
        c.width = width;
        c.height = height;
        c.extraSections = "[cigi]\nport = " + std::to_string(port) + "\nhost_port = " + std::to_string(hostPort) +
                          "\nview_id = " + std::to_string(viewId) + "\n";
        if (!daemon.start(tmp.path, c, error))
            return false;
        if (sky_client_connect(daemon.socketPath.c_str(), "cigi-test", &client) != SKY_OK ||
            sky_client_subscribe_shm_layers(client, 1u << SKY_LAYER_CLOUDS) != SKY_OK)
        {
            error = "client: " + std::string(sky_client_last_error(client));
            return false;
        }
        return true;
    }

    nlohmann::json status()
    {
        std::vector<char> buffer(1 << 16);
        if (sky_client_status(client, buffer.data(), buffer.size()) != SKY_OK)
            return {};
        return nlohmann::json::parse(buffer.data(), nullptr, false);
    }

    std::string log() const
    {
        std::ifstream in(daemon.logPath);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
};

/// A frame's clouds layer: premultiplied rgb + alpha per pixel, and the eye it was drawn from.
struct CloudFrame
{
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;
    double altM = 0;

    float alpha(uint32_t x, uint32_t y) const { return rgba[(size_t(y) * width + x) * 4 + 3]; }
    /// Mean alpha of rows [y0, y1).
    double meanAlpha(uint32_t y0, uint32_t y1) const
    {
        double sum = 0;
        for (uint32_t y = y0; y < y1; ++y)
            for (uint32_t x = 0; x < width; ++x)
                sum += double(alpha(x, y));
        return sum / double((y1 - y0) * width);
    }
};

/// Renders (client `render`) until the frame draws the host's weather (`source`, ready, faded in) from an
/// eye at `altM`, then returns the next frame.
bool settledFrame(Ig& ig, double altM, CloudFrame& out, std::string& error, const std::string& source = "cigi")
{
    // A bound, not a measurement: the weather's window is made on a worker thread, slow on a loaded machine.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline)
    {
        nlohmann::json s = ig.status();
        const nlohmann::json& w = s["weather"];
        const bool settled = w["frame"].is_object() && w["frame"]["source"] == source &&
                             w["frame"]["version"] == w["version"] && w["pending"] == false &&
                             s["cigi"]["applied"]["fading"] == false &&
                             std::fabs(s["view"]["alt"].get<double>() - altM) < 0.01;
        uint64_t id = 0;
        if (sky_client_request_frame(ig.client, &id) != SKY_OK ||
            sky_client_wait_frame(ig.client, id - 1, 60000) != SKY_OK)
        {
            error = "no frame: " + std::string(sky_client_last_error(ig.client));
            return false;
        }
        if (!settled)
        {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            continue;
        }
        SkyFrame f{};
        if (sky_client_acquire_frame(ig.client, &f) != SKY_OK || f.frame_id < id)
        {
            error = "frame " + std::to_string(id) + " not acquired";
            return false;
        }
        const SkyFrameLayer& layer = f.layers[SKY_LAYER_CLOUDS];
        out.width = f.width;
        out.height = f.height;
        out.altM = f.view.alt_m;
        out.rgba.clear();
        for (uint32_t y = 0; layer.pixels && y < f.height; ++y)
            for (uint32_t x = 0; x < f.width * 4; ++x)
            {
                uint16_t h = 0;
                std::memcpy(&h, layer.pixels + size_t(y) * layer.row_bytes + x * 2, 2);
                out.rgba.push_back(glm::unpackHalf1x16(h));
            }
        sky_client_release_frame(ig.client, &f);
        if (layer.format != SKY_FORMAT_RGBA16F_PREMULTIPLIED)
        {
            error = "the frame has no clouds layer";
            return false;
        }
        return true;
    }
    error = "the frames never drew the host's weather from " + std::to_string(altM) + " m: " + ig.status().dump();
    return false;
}

HostDatagram deckScene(ByteOrder order, uint32_t hostFrame, double altMslM)
{
    HostDatagram d(order, hostFrame);
    d.add(ownshipAt(0, kLat, kLon, altMslM))
        .add(celestialAt(kDate, 12, 0))
        .add(cloudLayer(1, CloudType::Stratus, 1000, 600, 100));
    return d;
}

} // namespace

// From 3000 m the Stratus deck fills the view below the horizon and nothing is above it; from 500 m the
// sky is overcast and the ground below is clear. The first datagram is big-endian, the second little-endian:
// each is answered in its own order. Every frame sends one Start of Frame, numbered from 0.
TEST(ServiceCigi, StratusDeckBelowFrom3000mAndOvercastFrom500m)
{
    CigiTestHost host;
    std::string error;
    ASSERT_TRUE(host.open(error)) << error;
    Ig ig;
    ASSERT_TRUE(ig.start(host.port(), 0, 32, 18, error)) << error;
    size_t sofs = 0, skipped = 0;

    ASSERT_TRUE(host.send(deckScene(ByteOrder::Big, 1, 3000).bytes(), ig.port));
    std::optional<IgReply> r = host.receiveForHostFrame(1, kReplyTimeoutMs, &skipped);
    ASSERT_TRUE(r) << "no Start of Frame for host frame 1";
    ++sofs;
    EXPECT_EQ(r->order, ByteOrder::Big);
    EXPECT_EQ(r->sof.igMode, 1);
    EXPECT_EQ(r->sof.igStatus, 0);
    CloudFrame above;
    ASSERT_TRUE(settledFrame(ig, 3000 + undulationM(kLat, kLon), above, error)) << error;
    EXPECT_NEAR(above.altM, 3000 + undulationM(kLat, kLon), 0.01);
    const uint32_t h = above.height;
    std::printf("from 3000 m: cloud alpha %.3f below the horizon, %.3f above\n", above.meanAlpha(h / 2 + 2, h),
                above.meanAlpha(0, h / 2 - 2));
    EXPECT_GT(above.meanAlpha(h / 2 + 2, h), 0.9) << "no deck below the horizon from 3000 m";
    EXPECT_LT(above.meanAlpha(0, h / 2 - 2), 0.1) << "cloud above the eye at 3000 m";

    ASSERT_TRUE(host.send(deckScene(ByteOrder::Little, 2, 500).bytes(), ig.port));
    r = host.receiveForHostFrame(2, kReplyTimeoutMs, &skipped);
    ASSERT_TRUE(r) << "no Start of Frame for host frame 2";
    ++sofs;
    EXPECT_EQ(r->order, ByteOrder::Little);
    CloudFrame below;
    ASSERT_TRUE(settledFrame(ig, 500 + undulationM(kLat, kLon), below, error)) << error;
    std::printf("from 500 m: cloud alpha %.3f below the horizon, %.3f above\n", below.meanAlpha(h / 2 + 2, h),
                below.meanAlpha(0, h / 2 - 2));
    EXPECT_GT(below.meanAlpha(0, h / 2 - 2), 0.9) << "the sky is not overcast from 500 m";
    EXPECT_LT(below.meanAlpha(h / 2 + 2, h), 0.1) << "cloud between the eye and the ground at 500 m";

    // One Start of Frame per frame: the status's frame count, IG frame numbers 0, 1, 2, ... The daemon may
    // render another frame of its own (a fade step) while the test counts: count until the replies are
    // quiet and the status's count equals them.
    uint32_t lastIgFrame = r->sof.igFrameNumber;
    nlohmann::json status;
    uint64_t frames = 0;
    for (int round = 0; round < 20; ++round)
    {
        while (std::optional<IgReply> more = host.receive(300))
        {
            ++sofs;
            EXPECT_EQ(more->sof.igFrameNumber, lastIgFrame + 1);
            lastIgFrame = more->sof.igFrameNumber;
            EXPECT_EQ(more->sof.lastHostFrameNumber, 2u);
        }
        status = ig.status();
        frames = status["frames_rendered"].get<uint64_t>();
        if (sofs + skipped >= frames)
            break;
    }
    EXPECT_EQ(sofs + skipped, frames) << "one Start of Frame per frame rendered";
    EXPECT_EQ(lastIgFrame + 1, frames);
    nlohmann::json cigi = status["cigi"];
    // The counters are read while frames go on: one may be a frame ahead of the other.
    const uint64_t sent = cigi["start_of_frames_sent"].get<uint64_t>();
    EXPECT_LE(frames, sent + 1);
    EXPECT_LE(sent, frames + 1) << "more Start of Frame datagrams than frames";
    EXPECT_EQ(cigi["errors_total"].get<uint64_t>(), 0u);
    EXPECT_EQ(ig.status()["weather"]["source"], "cigi");
    EXPECT_EQ(ig.daemon.stop(), 0);
}

// With a snapshot file loaded the host's deck is laid over it (skyservice/service/cigi_weather_merge.h):
// the file stays loaded (status names both) and the frames draw the deck.
TEST(ServiceCigi, HostsDeckIsLaidOverALoadedFile)
{
    CigiTestHost host;
    std::string error;
    ASSERT_TRUE(host.open(error)) << error;
    Ig ig;
    ASSERT_TRUE(ig.start(host.port(), 0, 32, 18, error)) << error;
    const std::string file = ig.tmp.path + "/model.skywx";
    ASSERT_TRUE(writeBuiltinSnapshot(file, 1782043200, error)) << error; // 2026-06-21T12:00:00Z
    RawClient c;
    ASSERT_TRUE(c.open(ig.daemon.socketPath));
    ASSERT_EQ(c.request({{"type", "load_weather"}, {"path", file}}).value("type", ""), "ok");
    nlohmann::json s;
    ASSERT_TRUE(waitForStatus(c, [&](const nlohmann::json& j) { return j["weather"]["source"] == file; }, 10000, &s))
        << s;
    ASSERT_TRUE(host.send(deckScene(ByteOrder::Big, 1, 3000).bytes(), ig.port));
    CloudFrame above;
    ASSERT_TRUE(settledFrame(ig, 3000 + undulationM(kLat, kLon), above, error, file + " + cigi")) << error;
    const uint32_t h = above.height;
    EXPECT_GT(above.meanAlpha(h / 2 + 2, h), 0.9) << "no deck below the horizon from 3000 m";
    s = ig.status();
    EXPECT_EQ(s["weather"]["source"], file + " + cigi");
    EXPECT_TRUE(s["cigi"]["applied"]["over_gridded"].get<bool>());
    EXPECT_EQ(ig.daemon.stop(), 0);
}

// Inside the deck (1300 m) the visibility is its extinction's 5 % contrast distance, under 200 m; above it
// (3000 m) the clear air's, over 10 km. Asked big-endian and little-endian, answered in the asker's order.
TEST(ServiceCigi, EnvironmentalConditionsRequestsInBothByteOrders)
{
    CigiTestHost host;
    std::string error;
    ASSERT_TRUE(host.open(error)) << error;
    Ig ig;
    ASSERT_TRUE(ig.start(host.port(), 0, 16, 9, error)) << error;

    HostDatagram inside = deckScene(ByteOrder::Big, 10, 3000);
    inside.add(conditionsRequest(21, kLat, kLon, 1300, kRequestWeather | kRequestAerosol));
    ASSERT_TRUE(host.send(inside.bytes(), ig.port));
    std::optional<IgReply> r = host.receiveForHostFrame(10, kReplyTimeoutMs);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->order, ByteOrder::Big);
    ASSERT_EQ(r->weather.size(), 1u);
    EXPECT_EQ(r->weather[0].requestId, 21);
    EXPECT_LT(r->weather[0].visibilityM, 200.0f);
    EXPECT_GT(r->weather[0].visibilityM, 10.0f);
    EXPECT_EQ(r->weather[0].humidityPct, 100);
    EXPECT_NEAR(r->weather[0].airTemperatureC, 15.0 - 6.5 * 1.3, 0.01);
    ASSERT_EQ(r->aerosol.size(), 1u);
    EXPECT_EQ(r->aerosol[0].layerId, 1);
    EXPECT_GT(r->aerosol[0].aerosolGPerM3, 0.0f);

    HostDatagram aboveIt(ByteOrder::Little, 11);
    aboveIt.add(conditionsRequest(22, kLat, kLon, 3000));
    ASSERT_TRUE(host.send(aboveIt.bytes(), ig.port));
    r = host.receiveForHostFrame(11, kReplyTimeoutMs);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->order, ByteOrder::Little);
    ASSERT_EQ(r->weather.size(), 1u);
    EXPECT_EQ(r->weather[0].requestId, 22);
    EXPECT_GT(r->weather[0].visibilityM, 10000.0f);
    EXPECT_TRUE(r->aerosol.empty());
    EXPECT_EQ(ig.status()["cigi"]["responses_sent"].get<uint64_t>(), 3u);

    // The host thins the deck to 60 %: the answer follows (3 / (0.045 x 0.6) = 111 m), and the new weather
    // fades in over steps that reach the frames through the worker thread, as a loaded file does: no frame
    // makes its window.
    CloudFrame frame;
    const double altM = 3000 + undulationM(kLat, kLon);
    ASSERT_TRUE(settledFrame(ig, altM, frame, error)) << error;
    const nlohmann::json before = ig.status()["windows"];
    HostDatagram thinner(ByteOrder::Big, 12);
    thinner.add(cloudLayer(1, CloudType::Stratus, 1000, 600, 60)).add(conditionsRequest(23, kLat, kLon, 1300));
    ASSERT_TRUE(host.send(thinner.bytes(), ig.port));
    r = host.receiveForHostFrame(12, kReplyTimeoutMs);
    ASSERT_TRUE(r);
    ASSERT_EQ(r->weather.size(), 1u);
    EXPECT_NEAR(r->weather[0].visibilityM, 3.0 / (0.045 * 0.6), 0.01);
    ASSERT_TRUE(settledFrame(ig, altM, frame, error)) << error;
    const nlohmann::json after = ig.status()["windows"];
    EXPECT_EQ(after["made_on_frame_path"], before["made_on_frame_path"]) << "the host's weather made a frame wait";
    EXPECT_GT(after["from_worker"].get<uint64_t>(), before["from_worker"].get<uint64_t>());
    EXPECT_GT(ig.status()["cigi"]["applied"]["fade_steps"].get<uint64_t>(), 1u) << "the change did not fade in";
    EXPECT_EQ(ig.daemon.stop(), 0);
}

// Short, foreign (bad magic), lying (a NaN latitude), unknown packets: counted by kind in status, each kind
// logged once; the good packets of the datagram still apply, and the daemon answers and renders on.
TEST(ServiceCigi, BadDatagramsAreCountedAndTheDaemonRendersOn)
{
    CigiTestHost host;
    std::string error;
    ASSERT_TRUE(host.open(error)) << error;
    Ig ig;
    ASSERT_TRUE(ig.start(host.port(), 0, 16, 9, error)) << error;

    const std::vector<uint8_t> shortOne = {1, 24, 3, 0, 0x31};
    ASSERT_TRUE(host.send(shortOne, ig.port));
    ASSERT_TRUE(host.send(shortOne, ig.port));
    std::vector<uint8_t> foreign = HostDatagram(ByteOrder::Big, 1).bytes();
    foreign[6] = 0x12;
    foreign[7] = 0x34;
    ASSERT_TRUE(host.send(foreign, ig.port));
    HostDatagram lying(ByteOrder::Little, 2);
    lying.add(ownshipAt(0, std::numeric_limits<double>::quiet_NaN(), kLon, 1000))
        .add(cloudLayer(1, CloudType::Stratus, 1000, 600, 100));
    std::vector<uint8_t> bytes = lying.bytes();
    const std::vector<uint8_t> unknown = {99, 8, 0, 0, 0, 0, 0, 0}; // opcode 99: not in CIGI 3.3
    bytes.insert(bytes.end(), unknown.begin(), unknown.end());
    ASSERT_TRUE(host.send(bytes, ig.port));
    ASSERT_TRUE(host.receiveForHostFrame(2, kReplyTimeoutMs)) << "no Start of Frame after a partly bad datagram";

    nlohmann::json s;
    RawClient raw;
    ASSERT_TRUE(raw.open(ig.daemon.socketPath));
    ASSERT_TRUE(waitForStatus(
        raw, [](const nlohmann::json& j) { return j["cigi"]["datagrams"].get<uint64_t>() == 4; }, 10000, &s))
        << s.dump();
    const nlohmann::json& e = s["cigi"]["errors"];
    EXPECT_EQ(e["short_datagram"].get<uint64_t>(), 2u);
    EXPECT_EQ(e["bad_magic"].get<uint64_t>(), 1u);
    EXPECT_EQ(e["bad_value"].get<uint64_t>(), 1u);
    EXPECT_EQ(e["unknown_opcode"].get<uint64_t>(), 1u);
    EXPECT_EQ(s["cigi"]["datagrams_dropped"].get<uint64_t>(), 3u);
    EXPECT_FALSE(s["cigi"]["ownship"]["valid"].get<bool>()) << "the NaN ownship was applied";
    EXPECT_EQ(s["weather"]["source"], "cigi") << "the good Weather Control of the bad datagram was not applied";

    uint64_t id = 0;
    ASSERT_EQ(sky_client_request_frame(ig.client, &id), SKY_OK);
    ASSERT_EQ(sky_client_wait_frame(ig.client, id - 1, 60000), SKY_OK) << sky_client_last_error(ig.client);
    EXPECT_TRUE(ig.status()["last_render_error"].is_null());
    const std::string log = ig.log();
    size_t shortLogged = 0;
    for (size_t at = log.find("short_datagram"); at != std::string::npos; at = log.find("short_datagram", at + 1))
        ++shortLogged;
    EXPECT_EQ(shortLogged, 1u) << log;
    EXPECT_NE(log.find("bad_magic"), std::string::npos);
    EXPECT_EQ(ig.daemon.stop(), 0);
}

// A CIGI port another program holds: the daemon refuses to start (exit 1) and says which port and why.
TEST(ServiceCigi, PortInUseIsAClearStartupError)
{
    CigiTestHost squatter;
    std::string error;
    ASSERT_TRUE(squatter.open(error)) << error;
    TempDir tmp;
    Daemon d;
    DaemonConfig c = tinyFrames(0);
    c.extraSections = "[cigi]\nport = " + std::to_string(squatter.port()) + "\n";
    ASSERT_FALSE(d.start(tmp.path, c, error));
    EXPECT_NE(error.find("exited with 1"), std::string::npos) << error;
    EXPECT_NE(error.find("cigi.port " + std::to_string(squatter.port()) + ": bind"), std::string::npos) << error;
}

namespace
{

double peak(const CloudFrame& f)
{
    double p = 1e-6;
    for (float v : f.rgba)
        p = std::max(p, double(v));
    return p;
}

/// Mean absolute clouds-layer difference (rgba, over the peak) between column xa of a and column xb of b.
double columnDifference(const CloudFrame& a, uint32_t xa, const CloudFrame& b, uint32_t xb)
{
    double sum = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t c = 0; c < 4; ++c)
            sum += std::fabs(double(a.rgba[(size_t(y) * a.width + xa) * 4 + c]) -
                             double(b.rgba[(size_t(y) * b.width + xb) * 4 + c]));
    return sum / (4.0 * a.height) / std::max(peak(a), peak(b));
}

/// The seam criterion of tests/gpu/test_channels.cpp: S, the difference between a's last and b's first
/// column, within max(1.5 I, 3.5 % of the peak), I the mean difference of neighbouring columns near a's edge.
void expectNoSeam(const CloudFrame& a, const CloudFrame& b)
{
    const uint32_t w = a.width;
    const double seam = columnDifference(a, w - 1, b, 0);
    double inner = 0;
    for (uint32_t x = w - 9; x < w - 1; ++x)
        inner += columnDifference(a, x, a, x + 1) / 8.0;
    std::printf("seam S %.4f, neighbouring columns I %.4f (share of the peak)\n", seam, inner);
    EXPECT_LE(seam, std::max(1.5 * inner, 0.035));
}

/// A display wall of two daemons (views 0 and 1, 64x36) fed the same host datagram `d` (ownship at 2700 m
/// above a broken stratocumulus deck); their settled frames and the frusta their status reports.
void runWall(const HostDatagram& d, CloudFrame& a, CloudFrame& b, nlohmann::json& fa, nlohmann::json& fb)
{
    CigiTestHost host;
    std::string error;
    ASSERT_TRUE(host.open(error)) << error;
    Ig left, right;
    ASSERT_TRUE(left.start(host.port(), 0, 64, 36, error)) << error;
    ASSERT_TRUE(right.start(host.port(), 1, 64, 36, error)) << error;
    ASSERT_TRUE(host.send(d.bytes(), left.port));
    ASSERT_TRUE(host.send(d.bytes(), right.port));
    const double altM = 2700 + undulationM(kLat, kLon);
    ASSERT_TRUE(settledFrame(left, altM, a, error)) << error;
    ASSERT_TRUE(settledFrame(right, altM, b, error)) << error;
    fa = left.status()["cigi"]["frustum"];
    fb = right.status()["cigi"]["frustum"];
    EXPECT_EQ(left.daemon.stop(), 0);
    EXPECT_EQ(right.daemon.stop(), 0);
}

HostDatagram wallScene()
{
    HostDatagram d(ByteOrder::Big, 1);
    d.add(ownshipAt(0, kLat, kLon, 2700))
        .add(celestialAt(kDate, 10, 0))
        .add(cloudLayer(1, CloudType::Stratocumulus, 1500, 600, 70));
    return d;
}

/// Vertical half-angle (degrees) of a symmetric view with square pixels at 64x36 and this horizontal half-angle.
float squareHalfHeightDeg(double halfWidthDeg)
{
    return float(std::atan(std::tan(halfWidthDeg * M_PI / 180.0) * 36.0 / 64.0) * 180.0 / M_PI);
}

} // namespace

// Two daemons, view 0 and view 1, the left and right halves of a display wall (40 degrees each side of the
// shared edge, asymmetric frusta), fed the same host datagram: each takes its own View Definition's
// frustum. The two frames meet at the shared edge (expectNoSeam) once the renderer draws
// ViewRequest::frustum; until then both draw the same symmetric view and the pixel check is skipped.
TEST(ServiceCigi, TwoChannelsRenderTheirOwnViewDefinitions)
{
    // 40 degrees wide, all on one side of the axis: square pixels need tan(half height) = tan(40) 36/64 / 2.
    const float halfHeightDeg = float(std::atan(std::tan(40.0 * M_PI / 180.0) * 36.0 / 64.0 / 2.0) * 180.0 / M_PI);
    HostDatagram d = wallScene();
    d.add(viewDefinition(0, -40, 0, halfHeightDeg, -halfHeightDeg))
        .add(viewDefinition(1, 0, 40, halfHeightDeg, -halfHeightDeg));
    CloudFrame a, b;
    nlohmann::json fa, fb;
    runWall(d, a, b, fa, fb);
    ASSERT_FALSE(HasFatalFailure());
    EXPECT_TRUE(fa["asymmetric"].get<bool>());
    EXPECT_DOUBLE_EQ(fa["left"].get<double>(), 40.0);
    EXPECT_DOUBLE_EQ(fa["right"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(fb["left"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(fb["right"].get<double>(), 40.0);
    for (const nlohmann::json* f : {&fa, &fb})
    {
        EXPECT_NEAR((*f)["up"].get<double>(), halfHeightDeg, 1e-5);
        EXPECT_NEAR((*f)["down"].get<double>(), halfHeightDeg, 1e-5);
    }
    if (a.rgba == b.rgba)
        GTEST_SKIP() << "the renderer does not draw ViewRequest::frustum yet (both channels drew the same "
                        "symmetric view): the seam check runs once it does";
    expectNoSeam(a, b);
}

// The same wall built the other common way: two symmetric 40-degree views, yawed -20 and +20 degrees from
// the ownship by View Control. Runs on any renderer (a symmetric frustum is the vertical field of view).
TEST(ServiceCigi, TwoChannelsYawedByViewControlMeetAtTheSharedEdge)
{
    const float hy = squareHalfHeightDeg(20.0);
    HostDatagram d = wallScene();
    d.add(viewDefinition(0, -20, 20, hy, -hy)).add(viewDefinition(1, -20, 20, hy, -hy));
    for (uint16_t view : {uint16_t(0), uint16_t(1)})
    {
        ViewControl v;
        v.viewId = view;
        v.yawEnable = true;
        v.yawDeg = view == 0 ? -20.0f : 20.0f;
        d.add(v);
    }
    CloudFrame a, b;
    nlohmann::json fa, fb;
    runWall(d, a, b, fa, fb);
    ASSERT_FALSE(HasFatalFailure());
    EXPECT_NE(a.rgba, b.rgba) << "the two channels look the same way";
    expectNoSeam(a, b);
}
