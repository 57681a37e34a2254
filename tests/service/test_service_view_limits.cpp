// SPDX-License-Identifier: MIT
// End-to-end over a raw socket: the field of view's range is the one PROTOCOL.md states and the renderer
// draws (skyservice/render/view_limits.h), and a frame that fails is told to the client that asked for it
// and shown in status.
#include "tests/service/service_harness.h"

#include <gtest/gtest.h>

using namespace skytest;
using nlohmann::json;

namespace
{

/// Asks for a frame and waits until it is published (true) or has failed (false); `status` gets the last.
bool renderOne(RawClient& c, json& status)
{
    json r = c.request({{"type", "render"}});
    if (r.value("type", "") != "ok")
    {
        status = r;
        return false;
    }
    const uint64_t id = r["frame_id"].get<uint64_t>();
    // A bound, not a measurement: a frame on a loaded lavapipe machine.
    waitForStatus(
        c,
        [&](const json& s) {
            return s["frame_id"].get<uint64_t>() >= id ||
                   (s["last_failed_frame"].is_object() && s["last_failed_frame"]["frame_id"].get<uint64_t>() >= id);
        },
        60000, &status);
    return status.is_object() && status["frame_id"].get<uint64_t>() >= id;
}

} // namespace

// PROTOCOL.md gives fov [1, 170]. Before, the renderer's check allowed only (1, 170): set_view took 170 from
// the parser and then refused it as a whole view ("outside (1, 170)", field "view"). Now both ends render,
// and just beyond them set_view itself refuses, naming view.fov and the range.
TEST(ServiceViews, FovAtBothEndsOfItsRangeRenders)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(0), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    for (double fov : {170.0, 1.0})
    {
        json r = c.request({{"type", "set_view"}, {"view", {{"fov", fov}}}});
        ASSERT_EQ(r.value("type", ""), "ok") << "fov " << fov << ": " << r;
        json s;
        EXPECT_TRUE(renderOne(c, s)) << "fov " << fov << ": " << s.dump();
        EXPECT_EQ(s["view"].value("fov", 0.0), fov) << s.dump();
        EXPECT_TRUE(s["last_render_error"].is_null()) << s.dump();
        EXPECT_EQ(s.value("frames_failed", 1), 0) << s.dump();
    }
    for (double fov : {170.001, 0.999})
    {
        json r = c.request({{"type", "set_view"}, {"view", {{"fov", fov}}}});
        EXPECT_EQ(r.value("code", ""), "out_of_range") << r;
        EXPECT_EQ(r.value("field", ""), "view.fov") << r;
        EXPECT_NE(r.value("message", "").find("[1, 170]"), std::string::npos) << r;
    }
    EXPECT_EQ(d.stop(), 0);
}

// A frame that fails (here: every frame, the config's shadow map reaching past a 100 km weather window,
// a combination the config does not refuse) is reported: status counts it and names the frame and why,
// and a write_files waiting for that frame gets `failed` with the reason. Before, the write_files waited
// for a frame that never came (rendering on request only, nothing asked again) and status showed the
// failure only until the next frame.
TEST(ServiceViews, FrameFailureIsReportedInStatusAndToWriteFiles)
{
    TempDir tmp;
    Daemon d;
    DaemonConfig config = tinyFrames(0);
    config.extraService = "shadow_map_size = 16\nshadow_map_extent_m = 500000\n";
    config.extraSections = "[window]\nhalf_extent_m = 100000.0\n";
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, config, error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));

    json s;
    EXPECT_FALSE(renderOne(c, s)) << s.dump();
    ASSERT_TRUE(s["last_failed_frame"].is_object()) << s.dump();
    EXPECT_GE(s["last_failed_frame"]["frame_id"].get<uint64_t>(), 1u) << s.dump();
    EXPECT_NE(s["last_failed_frame"]["error"].get<std::string>().find("shadow map extent"), std::string::npos)
        << s.dump();
    EXPECT_GE(s["frames_failed"].get<uint64_t>(), 1u) << s.dump();
    EXPECT_TRUE(s["last_render_error"].is_string()) << s.dump();
    EXPECT_EQ(s["frames_rendered"].get<uint64_t>(), 0u) << s.dump();

    json r = c.request({{"type", "write_files"}, {"prefix", "shot"}, {"id", 5}}, 60000);
    ASSERT_TRUE(r.is_object()) << "no reply to write_files: the frame it waited for failed unreported";
    EXPECT_EQ(r.value("code", ""), "failed") << r;
    EXPECT_EQ(r["id"], 5);
    EXPECT_NE(r.value("message", "").find("shadow map extent"), std::string::npos) << r;
    EXPECT_EQ(d.stop(), 0);
}
