// SPDX-License-Identifier: MIT
// libskyclient (skyservice/client/skyclient.h) against the in-test fake service: the handshake,
// requests and their error mapping, a service that goes away (no SIGPIPE), the shared-memory
// transport with torn-read detection, wait timeouts, and the Vulkan transport's fds.
#include "skyservice/client/skyclient.h"
#include "tests/ipc/fake_service.h"
#include "tests/ipc/ipc_test_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace sky
{
namespace
{

struct ClientTest : ::testing::Test
{
    test::TempDir dir;
    std::string path = dir.file("fake.sock");
    std::unique_ptr<test::FakeService> service = std::make_unique<test::FakeService>(path);
    SkyClient* client = nullptr;

    void SetUp() override { ASSERT_EQ(sky_client_connect(path.c_str(), "gtest", &client), SKY_OK) << sky_client_last_error(nullptr); }
    void TearDown() override { sky_client_close(client); }
};

SkyView testView()
{
    SkyView v{};
    v.lat_deg = 47.5;
    v.lon_deg = 8.5;
    v.alt_m = 1200;
    v.heading_deg = 90;
    v.fov_deg = 60;
    v.width = 64;
    v.height = 32;
    return v;
}

TEST(Client, ConnectFailuresAreNamed)
{
    test::TempDir dir;
    SkyClient* c = reinterpret_cast<SkyClient*>(0x1);
    EXPECT_EQ(sky_client_connect(dir.file("nobody.sock").c_str(), "x", &c), SKY_ERR_CONNECT);
    EXPECT_EQ(c, nullptr);
    EXPECT_NE(std::string(sky_client_last_error(nullptr)).find("nobody.sock"), std::string::npos);
    EXPECT_EQ(sky_client_connect(nullptr, "x", &c), SKY_ERR_ARGUMENT);
    EXPECT_EQ(sky_client_connect("/tmp/x", "x", nullptr), SKY_ERR_ARGUMENT);
    sky_client_close(nullptr);
}

TEST_F(ClientTest, HelloThenRequests)
{
    EXPECT_EQ(service->requests.load(), 1) << "connect says hello";
    SkyView v = testView();
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_OK) << sky_client_last_error(client);
    EXPECT_STREQ(sky_client_last_error(client), "");
    // 2026-06-21T12:00:00Z; the fake sends an "event" line before the reply, which must be skipped.
    EXPECT_EQ(sky_client_set_time(client, 1782043200.2, 60.0), SKY_OK) << sky_client_last_error(client);
    EXPECT_EQ(service->lastTime(), "2026-06-21T12:00:00Z");
    uint64_t frameId = 0;
    EXPECT_EQ(sky_client_request_frame(client, &frameId), SKY_OK);
    EXPECT_EQ(frameId, 42u);
    EXPECT_EQ(sky_client_load_weather(client, "/w/new.skywx"), SKY_OK);
    EXPECT_EQ(sky_client_write_files(client, "/tmp/out/a"), SKY_OK);
    char status[256];
    ASSERT_EQ(sky_client_status(client, status, sizeof status), SKY_OK);
    EXPECT_NE(std::string(status).find("\"frame_id\":7"), std::string::npos) << status;
    char tiny[8];
    EXPECT_EQ(sky_client_status(client, tiny, sizeof tiny), SKY_ERR_ARGUMENT);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("bytes"), std::string::npos);
    EXPECT_EQ(sky_client_set_view(client, nullptr), SKY_ERR_ARGUMENT);
    v.lat_deg = std::nan("");
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_ARGUMENT) << "a NaN is refused before it is sent";
}

// A display wall's channel: the four half-angles go instead of fov; a flag neither 0 nor 1 (a view not
// zeroed) is refused before anything is sent.
TEST_F(ClientTest, AsymmetricViewSendsTheHalfAngles)
{
    SkyView v = testView();
    v.asymmetric = 1;
    v.left_deg = 40;
    v.right_deg = 0;
    v.up_deg = 20;
    v.down_deg = 15;
    ASSERT_EQ(sky_client_set_view(client, &v), SKY_OK) << sky_client_last_error(client);
    ViewUpdate sent = service->lastView();
    ASSERT_TRUE(sent.left && sent.right && sent.up && sent.down);
    EXPECT_EQ(*sent.left, 40.0);
    EXPECT_EQ(*sent.right, 0.0);
    EXPECT_EQ(*sent.up, 20.0);
    EXPECT_EQ(*sent.down, 15.0);
    EXPECT_FALSE(sent.fov.has_value());
    EXPECT_EQ(*sent.width, 64u);

    v.asymmetric = 0;
    ASSERT_EQ(sky_client_set_view(client, &v), SKY_OK) << sky_client_last_error(client);
    sent = service->lastView();
    EXPECT_EQ(*sent.fov, 60.0);
    EXPECT_FALSE(sent.left.has_value());

    const int before = service->requests.load();
    v.asymmetric = 7;
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_ARGUMENT);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("asymmetric"), std::string::npos);
    v.asymmetric = 1;
    v.up_deg = std::nan("");
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_ARGUMENT);
    EXPECT_EQ(service->requests.load(), before);
    v.up_deg = 90;  // the service's range check answers
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_REFUSED);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("view.up"), std::string::npos);
}

TEST_F(ClientTest, ErrorRepliesAreRefusedWithTheServiceMessage)
{
    SkyView v = testView();
    v.lat_deg = 95;
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_REFUSED);
    const std::string message = sky_client_last_error(client);
    EXPECT_NE(message.find("view.lat"), std::string::npos) << message;
    EXPECT_NE(message.find("out_of_range"), std::string::npos) << message;
    EXPECT_EQ(sky_client_write_files(client, "../escape"), SKY_ERR_REFUSED);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("not writable"), std::string::npos);
    EXPECT_EQ(sky_client_load_weather(client, "relative.skywx"), SKY_ERR_REFUSED);
    // The connection goes on after errors.
    v = testView();
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_OK) << sky_client_last_error(client);
}

TEST_F(ClientTest, ServiceGoingAwayIsClosedNeverSigpipe)
{
    // SIGPIPE keeps its default action (terminate): a send without MSG_NOSIGNAL would kill this test.
    ASSERT_EQ(signal(SIGPIPE, SIG_DFL), SIG_DFL);
    EXPECT_EQ(sky_client_load_weather(client, "/hang-up"), SKY_ERR_CLOSED);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("closed"), std::string::npos);
    SkyView v = testView();
    EXPECT_EQ(sky_client_set_view(client, &v), SKY_ERR_CLOSED);

    SkyClient* second = nullptr;
    ASSERT_EQ(sky_client_connect(path.c_str(), "second", &second), SKY_OK);
    service->stop();
    // The first send after the peer closed may still succeed (it lands in a dead buffer); repeated
    // requests must end in SKY_ERR_CLOSED, not in a signal.
    SkyResult r = SKY_OK;
    for (int i = 0; i < 5 && r != SKY_ERR_CLOSED; ++i)
        r = sky_client_set_view(second, &v);
    EXPECT_EQ(r, SKY_ERR_CLOSED) << sky_client_last_error(second);
    sky_client_close(second);
}

TEST_F(ClientTest, SharedMemoryAcquireReleaseAndTorn)
{
    SkyFrame f{};
    EXPECT_EQ(sky_client_acquire_frame(client, &f), SKY_ERR_ARGUMENT) << "not subscribed yet";
    ASSERT_EQ(sky_client_subscribe_shm(client), SKY_OK) << sky_client_last_error(client);
    EXPECT_EQ(sky_client_acquire_frame(client, &f), SKY_ERR_NO_FRAME);
    service->publish(5, 40, 20);
    ASSERT_EQ(sky_client_wait_frame(client, 0, 1000), SKY_OK);
    ASSERT_EQ(sky_client_acquire_frame(client, &f), SKY_OK) << sky_client_last_error(client);
    EXPECT_EQ(f.frame_id, 5u);
    EXPECT_EQ(f.width, 40u);
    EXPECT_EQ(f.height, 20u);
    EXPECT_EQ(f.row_bytes, 160u);
    EXPECT_EQ(f.format, uint32_t(SKY_FORMAT_RGBA8_SRGB));
    EXPECT_EQ(f.view.lat_deg, 47.5);
    EXPECT_EQ(f.sim_time_unix_s, 1782043200.0);
    ASSERT_NE(f.pixels, nullptr);
    EXPECT_EQ(f.pixels[19 * 160 + 159], 5);
    ASSERT_EQ(f.shadow_size, 8u);
    ASSERT_NE(f.shadow_transmittance, nullptr);
    EXPECT_EQ(f.shadow_transmittance[63], 5.0f);
    EXPECT_EQ(f.shadow.extent_m, 50000.0);
    EXPECT_EQ(sky_client_release_frame(client, &f), SKY_OK);

    // Held across two more frames (3 slots): intact. Across a third: torn.
    ASSERT_EQ(sky_client_acquire_frame(client, &f), SKY_OK);
    service->publish(6);
    service->publish(7);
    EXPECT_EQ(sky_client_release_frame(client, &f), SKY_OK);
    service->publish(8);
    EXPECT_EQ(sky_client_release_frame(client, &f), SKY_ERR_TORN);
    EXPECT_NE(std::string(sky_client_last_error(client)).find("overwritten"), std::string::npos);
    ASSERT_EQ(sky_client_acquire_frame(client, &f), SKY_OK);
    EXPECT_EQ(f.frame_id, 8u);
    EXPECT_EQ(f.pixels[0], 8);
    SkyFrame bogus = f;
    bogus.slot = 99;
    EXPECT_EQ(sky_client_release_frame(client, &bogus), SKY_ERR_ARGUMENT);
}

TEST_F(ClientTest, WaitFrameTimesOutAndWakesOnANewFrame)
{
    ASSERT_EQ(sky_client_subscribe_shm(client), SKY_OK) << sky_client_last_error(client);
    service->publish(1);
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(sky_client_wait_frame(client, 1, 60), SKY_ERR_TIMEOUT);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_GE(ms, 59.0);
    EXPECT_LT(ms, 1000.0);
    EXPECT_EQ(sky_client_wait_frame(client, 0, 0), SKY_OK) << "frame 1 is already newer than 0";
    std::thread later([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
        service->publish(2);
    });
    EXPECT_EQ(sky_client_wait_frame(client, 1, 2000), SKY_OK);
    later.join();
    // A service that goes away ends a wait at once, with SKY_ERR_CLOSED.
    service->stop();
    EXPECT_EQ(sky_client_wait_frame(client, 2, 2000), SKY_ERR_CLOSED);
}

TEST_F(ClientTest, VulkanSubscribeReceivesTheFdsInOrder)
{
    SkyExportedFrames frames{};
    ASSERT_EQ(sky_client_subscribe_vulkan(client, &frames), SKY_OK) << sky_client_last_error(client);
    ASSERT_EQ(frames.slot_count, 3u);
    auto content = [](int fd) {
        char buffer[32] = {};
        return ::pread(fd, buffer, sizeof buffer - 1, 0) > 0 ? std::string(buffer) : std::string("(unreadable)");
    };
    for (uint32_t i = 0; i < 3; ++i)
    {
        ASSERT_GE(frames.frame[i].memory_fd, 0);
        EXPECT_EQ(content(frames.frame[i].memory_fd), "frame" + std::to_string(i));
        EXPECT_EQ(frames.frame[i].allocation_bytes, 65536u + i);
        EXPECT_EQ(frames.frame[i].width, 64u);
        EXPECT_EQ(frames.frame[i].linear_tiling, 1u);
        EXPECT_EQ(frames.frame[i].row_pitch, 256u);
        EXPECT_EQ(frames.frame[i].vk_format, 37u);
        EXPECT_TRUE(::fcntl(frames.frame[i].memory_fd, F_GETFD) & FD_CLOEXEC);
    }
    EXPECT_EQ(content(frames.shadow[0].memory_fd), "shadow0");
    EXPECT_EQ(frames.shadow[1].memory_fd, -1);
    EXPECT_EQ(content(frames.shadow[2].memory_fd), "shadow2");
    EXPECT_EQ(frames.shadow[2].vk_format, 100u);
    EXPECT_EQ(frames.shadow[2].linear_tiling, 0u);
    EXPECT_EQ(content(frames.timeline_semaphore_fd), "semaphore");
    EXPECT_EQ(frames.device_uuid[1], 0x01);
    EXPECT_EQ(frames.device_uuid[15], 0x0f);
    EXPECT_EQ(frames.driver_uuid[0], 0xff);
    // The ring was mapped too: acquire works, without pixels in the zero-copy case only if the
    // service publishes none; the fake publishes pixels.
    service->publish(3);
    SkyFrame f{};
    ASSERT_EQ(sky_client_acquire_frame(client, &f), SKY_OK);
    EXPECT_EQ(f.frame_id, 3u);
    EXPECT_EQ(sky_client_release_frame(client, &f), SKY_OK);
    for (uint32_t i = 0; i < 3; ++i)
    {
        ::close(frames.frame[i].memory_fd);
        if (frames.shadow[i].memory_fd >= 0)
            ::close(frames.shadow[i].memory_fd);
    }
    ::close(frames.timeline_semaphore_fd);
}

}  // namespace
}  // namespace sky
