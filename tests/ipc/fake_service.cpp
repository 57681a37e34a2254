// SPDX-License-Identifier: MIT
#include "tests/ipc/fake_service.h"
#include "tests/ipc/ipc_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sys/mman.h>
#include <unistd.h>

namespace sky::test
{

FakeService::FakeService(const std::string& socketPath, uint32_t slots)
{
    std::string error;
    ShmRingConfig rc;
    rc.name = uniqueShmName();
    rc.slotCount = slots;
    rc.maxWidth = 64;
    rc.maxHeight = 32;
    rc.maxShadowSize = 8;
    if (!ring.create(rc, error))
        ADD_FAILURE() << error;
    if (!server_.listen(socketPath, 0600, {}, error))
        ADD_FAILURE() << error;
    thread_ = std::thread([this] {
        ControlSocketServer::Handlers h;
        h.line = [this](ClientId c, std::string_view line) { onLine(c, line); };
        h.disconnected = [this](ClientId c) {
            helloDone_.erase(std::remove(helloDone_.begin(), helloDone_.end(), c), helloDone_.end());
        };
        while (!stop_.load())
            server_.poll(20, h);
    });
}

void FakeService::stop()
{
    stop_ = true;
    server_.wake();
    if (thread_.joinable())
        thread_.join();
    server_.close();
}

std::string FakeService::lastTime() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return lastTime_;
}

ViewUpdate FakeService::lastView() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return lastView_;
}

void FakeService::publish(uint64_t frameId, uint32_t width, uint32_t height)
{
    std::vector<uint8_t> pixels(size_t(width) * height * 4, uint8_t(frameId & 0xff));
    std::vector<float> shadow(64, float(frameId));
    ShmFrame f;
    f.frameId = frameId;
    f.simTimeUnixS = 1782043200.0;
    f.view.lat_deg = 47.5;
    f.view.fov_deg = 60;
    f.width = width;
    f.height = height;
    f.pixels = pixels.data();
    f.shadowTransmittance = shadow.data();
    f.shadow.size_texels = 8;
    f.shadow.centre_lat_deg = 47.5;
    f.shadow.extent_m = 50000;
    std::string error;
    if (!ring.publish(f, error))
        ADD_FAILURE() << error;
}

void FakeService::onLine(ClientId client, std::string_view line)
{
    ++requests;
    Request r;
    ProtocolError e;
    ProtocolLimits limits;
    limits.maxWidth = 64;
    limits.maxHeight = 32;
    if (!parseRequest(line, limits, r, e))
    {
        server_.send(client, errorReply(e));
        return;
    }
    const bool hello = std::find(helloDone_.begin(), helloDone_.end(), client) != helloDone_.end();
    if (!hello && r.type != RequestType::Hello)
    {
        e.code = "not_hello";
        e.message = "the first request must be hello";
        e.id = r.id;
        server_.send(client, errorReply(e));
        return;
    }
    switch (r.type)
    {
    case RequestType::Hello:
        helloDone_.push_back(client);
        server_.admit(client);
        server_.send(client, replyWithId(r, {{"type", "hello"}, {"protocol", 1}, {"service", "fake"},
                                             {"device", "none"}, {"max_width", 64}, {"max_height", 32}}));
        return;
    case RequestType::SetTime:
    {
        std::lock_guard<std::mutex> lock(mutex_);
        lastTime_ = r.timeIso.value_or("");
    }
        // Unsolicited lines a future service may send: the client must skip them.
        server_.send(client, R"({"type":"event","event":"weather_changed"})");
        server_.send(client, okReply(r));
        return;
    case RequestType::LoadWeather:
        if (r.path == "/hang-up")  // the service goes away mid-request
        {
            server_.disconnect(client);
            return;
        }
        server_.send(client, okReply(r, {{"queued", true}}));
        return;
    case RequestType::Subscribe:
        if (r.transport == Transport::Vulkan)
            return subscribeVulkan(client, r);
        server_.send(client, replyWithId(r, {{"type", "subscribed"}, {"transport", "shm"}, {"shm_name", ring.name()},
                                             {"slots", ring.slotCount()}, {"total_bytes", ring.totalBytes()}}));
        return;
    case RequestType::Render: server_.send(client, okReply(r, {{"frame_id", 42}})); return;
    case RequestType::Status:
        server_.send(client, replyWithId(r, {{"type", "status"}, {"frame_id", 7}, {"clients", 1}}));
        return;
    case RequestType::WriteFiles:
        if (r.path.find("..") != std::string::npos)
        {
            e.code = "failed";
            e.message = "prefix '" + r.path + "' is not writable";
            e.field = "prefix";
            e.id = r.id;
            server_.send(client, errorReply(e));
            return;
        }
        server_.send(client, okReply(r));
        return;
    case RequestType::SetView:
    {
        std::lock_guard<std::mutex> lock(mutex_);
        lastView_ = r.view;
    }
        server_.send(client, okReply(r));
        return;
    }
}

void FakeService::subscribeVulkan(ClientId client, const Request& r)
{
    // Memory fds are stood in for by memfds whose content names them, so the test can check the order.
    std::vector<int> fds;
    auto named = [&](const std::string& text) {
        int fd = ::memfd_create("fake-export", MFD_CLOEXEC);
        if (::write(fd, text.data(), text.size()) != ssize_t(text.size()))
            ADD_FAILURE() << "memfd write";
        fds.push_back(fd);
    };
    nlohmann::json images = nlohmann::json::array();
    const uint32_t slots = ring.slotCount();
    for (uint32_t i = 0; i < slots; ++i)
    {
        nlohmann::json image = {{"allocation_bytes", 65536 + i}, {"memory_type_bits", 7}, {"vk_format", 37},
                                {"width", 64},                   {"height", 32},          {"linear_tiling", true},
                                {"row_pitch", 256}};
        // Slot 1 has no shadow map, the others have one (both cases of the fd order).
        image["shadow"] = i == 1 ? nlohmann::json(nullptr)
                                 : nlohmann::json({{"allocation_bytes", 4096}, {"memory_type_bits", 1}, {"vk_format", 100},
                                                   {"width", 8}, {"height", 8}, {"linear_tiling", false}, {"row_pitch", 0}});
        images.push_back(image);
    }
    for (uint32_t i = 0; i < slots; ++i)
        named("frame" + std::to_string(i));
    for (uint32_t i = 0; i < slots; ++i)
        if (i != 1)
            named("shadow" + std::to_string(i));
    named("semaphore");
    nlohmann::json body = {{"type", "subscribed"},
                           {"transport", "vulkan"},
                           {"shm_name", ring.name()},
                           {"slots", slots},
                           {"total_bytes", ring.totalBytes()},
                           {"images", images},
                           {"timeline_semaphore", true},
                           {"device_uuid", "000102030405060708090a0b0c0d0e0f"},
                           {"driver_uuid", "ffeeddccbbaa99887766554433221100"}};
    server_.send(client, replyWithId(r, body), fds);
    for (int fd : fds)
        ::close(fd);
}

}  // namespace sky::test
