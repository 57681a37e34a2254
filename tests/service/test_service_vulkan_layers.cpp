// SPDX-License-Identifier: MIT
// End-to-end: compositing layers through the zero-copy transport. The daemon exports the layers a vulkan
// subscriber asks for; this process (another than the daemon) imports them with skyclient_vulkan into its
// own VkDevice (validation on, tests/export/import_child.h) and compares them with the shared-memory
// layers of the same frame.
#include "skyservice/client/skyclient.h"
#include "tests/export/import_child.h"
#include "tests/service/service_harness.h"

#include <gtest/gtest.h>

#include <cstring>
#include <unistd.h>

using namespace skytest;
using sky::exporttest::ChildReport;
using sky::exporttest::ReadPlan;

namespace
{

constexpr uint32_t kWidth = 96, kHeight = 54;  // the service's max is 128x72: the top-left corner
constexpr uint32_t kLayers = (1u << SKY_LAYER_CLOUDS) | (1u << SKY_LAYER_DEPTH);

SkyView cloudyView()
{
    SkyView v{};
    v.lat_deg = 46.0;
    v.lon_deg = 8.0;
    v.alt_m = 2500;
    v.heading_deg = 200;
    v.pitch_deg = 5;
    v.fov_deg = 60;
    v.width = kWidth;
    v.height = kHeight;
    return v;
}

/// A layer of an acquired shm frame, rows packed (8 bytes a pixel).
std::vector<uint8_t> packed(const SkyFrame& f, uint32_t layer)
{
    const SkyFrameLayer& l = f.layers[layer];
    std::vector<uint8_t> bytes;
    for (uint32_t y = 0; y < f.height && l.pixels; ++y)
        bytes.insert(bytes.end(), l.pixels + size_t(y) * l.row_bytes, l.pixels + size_t(y) * l.row_bytes + f.width * 8);
    return bytes;
}

/// Asks for a frame and waits until it is published; false on timeout.
bool renderOne(SkyClient* c, uint64_t& id)
{
    return sky_client_request_frame(c, &id) == SKY_OK && sky_client_wait_frame(c, id - 1, 30000) == SKY_OK;
}

/// Imports `exported` (its fds become the importer's) and returns the layers of `slot`, packed: clouds then depth.
bool importLayers(SkyExportedFrames& exported, uint32_t slot, uint64_t frameId, std::vector<uint8_t>& clouds,
                  std::vector<uint8_t>& depth, std::string& error)
{
    ReadPlan plan{exported.slot_count, kWidth, kHeight, 0, kLayers, frameId};
    ChildReport report;
    std::vector<uint8_t> data;
    if (!sky::exporttest::importAndRead(exported, plan, report, data) || report.validationMessages != 0)
    {
        error = std::string(report.error) + " (" + std::to_string(report.validationMessages) + " validation messages)";
        return false;
    }
    const size_t frameBytes = size_t(kWidth) * kHeight * 4, layerBytes = size_t(kWidth) * kHeight * 8;
    const uint8_t* at = data.data() + slot * sky::exporttest::slotBytes(plan) + frameBytes;
    clouds.assign(at, at + layerBytes);
    depth.assign(at + layerBytes, at + 2 * layerBytes);
    return true;
}

}  // namespace

// A vulkan subscriber of clouds + depth and a shm subscriber of the same layers: the imported images of a
// frame's slot hold exactly the ring's layers of that frame. The reply carries the layer images (and no
// sky). Then the shm subscriber leaves: the next frame (same view, frozen time) draws the layers for the
// export only, reads none back into the ring, and its exported layers are still the same bytes.
TEST(ServiceVulkanLayers, ExportedLayersEqualTheShmLayersOfTheSameFrame)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, DaemonConfig{}, error)) << error;
    SkyClient* vulkan = nullptr;
    SkyClient* shm = nullptr;
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "vulkan-layers", &vulkan), SKY_OK);
    ASSERT_EQ(sky_client_connect(d.socketPath.c_str(), "shm-layers", &shm), SKY_OK);
    SkyView v = cloudyView();
    ASSERT_EQ(sky_client_set_view(shm, &v), SKY_OK) << sky_client_last_error(shm);
    ASSERT_EQ(sky_client_set_time(shm, 1782043200.0 + 3600.0 * 4, 0.0), SKY_OK);  // 2026-06-21T16:00:00Z

    SkyExportedFrames exported{};
    EXPECT_EQ(sky_client_subscribe_vulkan_layers(vulkan, 1u << 9, &exported), SKY_ERR_ARGUMENT);
    ASSERT_EQ(sky_client_subscribe_vulkan_layers(vulkan, kLayers, &exported), SKY_OK) << sky_client_last_error(vulkan);
    ASSERT_EQ(exported.layers, kLayers | (1u << SKY_LAYER_DISPLAY));
    for (uint32_t i = 0; i < exported.slot_count; ++i)
    {
        EXPECT_GE(exported.layer[SKY_LAYER_CLOUDS][i].memory_fd, 0);
        EXPECT_GE(exported.layer[SKY_LAYER_DEPTH][i].memory_fd, 0);
        EXPECT_EQ(exported.layer[SKY_LAYER_SKY][i].memory_fd, -1);
        EXPECT_EQ(exported.layer[SKY_LAYER_DISPLAY][i].memory_fd, -1);
        EXPECT_EQ(exported.layer[SKY_LAYER_CLOUDS][i].vk_format, 97u);  // VK_FORMAT_R16G16B16A16_SFLOAT
        EXPECT_EQ(exported.layer[SKY_LAYER_DEPTH][i].vk_format, 103u);  // VK_FORMAT_R32G32_SFLOAT
        EXPECT_EQ(exported.layer[SKY_LAYER_DEPTH][i].width, 128u);
    }
    ASSERT_EQ(sky_client_subscribe_shm_layers(shm, kLayers | (1u << SKY_LAYER_DISPLAY)), SKY_OK)
        << sky_client_last_error(shm);

    uint64_t id = 0;
    ASSERT_TRUE(renderOne(shm, id)) << sky_client_last_error(shm);
    SkyFrame f{}, g{};
    ASSERT_EQ(sky_client_acquire_frame(shm, &f), SKY_OK);
    ASSERT_EQ(sky_client_acquire_frame(vulkan, &g), SKY_OK);
    ASSERT_EQ(f.frame_id, g.frame_id);
    ASSERT_EQ(f.width, kWidth);
    ASSERT_EQ(f.layers[SKY_LAYER_CLOUDS].format, SKY_FORMAT_RGBA16F_PREMULTIPLIED);
    ASSERT_EQ(f.layers[SKY_LAYER_DEPTH].format, SKY_FORMAT_RG32F_METRES);
    const std::vector<uint8_t> shmClouds = packed(f, SKY_LAYER_CLOUDS), shmDepth = packed(f, SKY_LAYER_DEPTH);
    std::vector<uint8_t> clouds, depth;
    ASSERT_TRUE(importLayers(exported, g.slot, g.frame_id, clouds, depth, error)) << error;
    EXPECT_EQ(sky_client_release_frame(shm, &f), SKY_OK);
    EXPECT_EQ(sky_client_release_frame(vulkan, &g), SKY_OK) << "rendering on request: nothing overwrote the slot";
    EXPECT_TRUE(clouds == shmClouds) << "the exported clouds layer differs from the ring's";
    EXPECT_TRUE(depth == shmDepth) << "the exported depth layer differs from the ring's";
    // Something worth comparing: cloud in view (depth > 0 somewhere).
    size_t cloudy = 0;
    for (size_t i = 0; i < shmDepth.size() / 8; ++i)
    {
        float front = 0;
        std::memcpy(&front, shmDepth.data() + i * 8, 4);
        cloudy += front > 0.0f;
    }
    EXPECT_GT(cloudy, shmDepth.size() / 8 / 10) << "too little cloud in view";
    sky_client_close(shm);

    // The vulkan subscriber alone: the layers are drawn for the export, not read back. New fds for it.
    SkyExportedFrames again{};
    ASSERT_EQ(sky_client_subscribe_vulkan_layers(vulkan, kLayers, &again), SKY_OK) << sky_client_last_error(vulkan);
    ASSERT_TRUE(renderOne(vulkan, id)) << sky_client_last_error(vulkan);
    ASSERT_EQ(sky_client_acquire_frame(vulkan, &g), SKY_OK);
    EXPECT_GE(g.frame_id, id);
    EXPECT_EQ(g.layers[SKY_LAYER_CLOUDS].pixels, nullptr) << "no shm subscriber: nothing read back";
    EXPECT_EQ(g.layers[SKY_LAYER_DEPTH].pixels, nullptr);
    std::vector<uint8_t> clouds2, depth2;
    ASSERT_TRUE(importLayers(again, g.slot, g.frame_id, clouds2, depth2, error)) << error;
    EXPECT_EQ(sky_client_release_frame(vulkan, &g), SKY_OK);
    EXPECT_TRUE(clouds2 == shmClouds) << "the drawn-only clouds layer differs (same view and time)";
    EXPECT_TRUE(depth2 == shmDepth) << "the drawn-only depth layer differs (same view and time)";

    RawClient raw;
    ASSERT_TRUE(raw.open(d.socketPath));
    nlohmann::json s = raw.request({{"type", "status"}});
    EXPECT_TRUE(s["last_render_error"].is_null()) << s;
    sky_client_close(vulkan);
    EXPECT_EQ(d.stop(), 0);
}

// The reply of a vulkan subscribe with layers, raw: the layers named, per slot a description of each
// layer's image, and the fds in PROTOCOL.md's order and number (frames, layers, semaphore); a bad layer
// name is refused naming the field.
TEST(ServiceVulkanLayers, ReplyDescribesTheLayerImages)
{
    TempDir tmp;
    Daemon d;
    std::string error;
    ASSERT_TRUE(d.start(tmp.path, tinyFrames(), error)) << error;
    RawClient c;
    ASSERT_TRUE(c.open(d.socketPath));
    using nlohmann::json;
    json bad = c.request({{"type", "subscribe"}, {"transport", "vulkan"}, {"layers", json::array({"clouds", "fog"})}});
    EXPECT_EQ(bad.value("code", ""), "out_of_range") << bad;
    EXPECT_EQ(bad.value("field", ""), "layers") << bad;
    std::vector<int> fds;
    const json ask = {
        {"type", "subscribe"}, {"transport", "vulkan"}, {"layers", json::array({"depth", "sky"})}, {"id", 4}};
    json r = c.requestWithFds(ask, fds);
    ASSERT_EQ(r.value("type", ""), "subscribed") << r;
    EXPECT_EQ(r["layers"], nlohmann::json::array({"display", "sky", "depth"}));
    ASSERT_EQ(r["images"].size(), 3u);
    for (const nlohmann::json& image : r["images"])
    {
        EXPECT_EQ(image["layers"].size(), 2u) << image;
        EXPECT_EQ(image["layers"]["sky"]["vk_format"], 97) << image;
        EXPECT_EQ(image["layers"]["depth"]["vk_format"], 103) << image;
        EXPECT_EQ(image["layers"]["depth"]["height"], 72) << image;
        EXPECT_FALSE(image["layers"].contains("clouds"));
    }
    EXPECT_EQ(fds.size(), 3u + 2u * 3u + (r["timeline_semaphore"].get<bool>() ? 1u : 0u));
    for (int fd : fds)
        close(fd);
    EXPECT_EQ(d.stop(), 0);
}
