// SPDX-License-Identifier: MIT
// Zero-copy frame export (skyservice/ipc/PROTOCOL.md) on the available Vulkan device
// (lavapipe in CI), validation on in both processes: two rendered frames with shadow maps are exported,
// their fds cross a real socketpair as SCM_RIGHTS into a forked and exec'd child, which imports them with
// skyclient_vulkan into its own VkInstance/VkDevice and reads them back: the bytes must equal the
// renderer's own readback exactly; so must the compositing layers' images (sky, clouds, depth), read
// back or drawn only for the export. Also: a device without VK_KHR_external_memory_fd fails cleanly with
// the extension's name, oversized frames are refused, and destroy leaves nothing tracked.
#include "skyservice/render/frame_export.h"
#include "tests/export/import_child.h"
#include "tests/gpu/gpu_fixture.h"
#include "tests/gpu/scenes.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace sky;
using namespace sky::testscenes;
using namespace sky::exporttest;

namespace
{

constexpr uint32_t kWidth = 96, kHeight = 54, kShadowSize = 32;

class FrameExportTest : public GpuFixture
{
protected:
    RenderResult render(double headingDeg, bool shadowMap = true, uint32_t readback = kReadEverything)
    {
        ViewRequest v = lookUp(45.0, 7.0, 500.0, 15.0, "2024-06-21T09:00:00Z");
        v.pose.headingDeg = headingDeg;
        v.width = kWidth;
        v.height = kHeight;
        v.shadowMap = shadowMap;
        v.shadowMapSize = kShadowSize;
        v.shadowMapExtentM = 40000.0;
        v.readback = readback;
        QualitySettings q = testQuality();
        q.maxViewSteps = 32;
        q.shadowSteps = 32;
        RenderResult result;
        SkyStatus s = renderView(*renderer, v, q, result);
        EXPECT_TRUE(s.ok()) << s.message;
        return result;
    }

    static size_t exportAllocations(Renderer& r)
    {
        std::lock_guard<std::mutex> lock(r.memory.mutex);
        return size_t(std::count_if(r.memory.liveBytes.begin(), r.memory.liveBytes.end(),
                                    [](const auto& kv) { return kv.first.rfind("export ", 0) == 0; }));
    }
};

bool readAll(int fd, void* out, size_t bytes)
{
    auto* p = static_cast<uint8_t*>(out);
    while (bytes > 0)
    {
        ssize_t n = read(fd, p, bytes);
        if (n <= 0)
            return false;
        p += n;
        bytes -= size_t(n);
    }
    return true;
}

/// What the import child read back.
struct ChildResult
{
    bool gotReport = false, gotData = false;
    int exitStatus = 0;
    ChildReport report;
    std::vector<uint8_t> data;  ///< plan.slots * slotBytes(plan)
};

/// The client: exec'd (not just forked) so that it shares nothing with this process but the socket. It
/// gets the `subscribed` description and the fds (sent as the daemon does, then closed here).
ChildResult importInChild(const ReadPlan& plan, const nlohmann::json& description, std::vector<int>& fds)
{
    ChildResult out;
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0)
        return out;
    std::string self = "/proc/self/exe", fdArg = std::to_string(sv[1]);
    std::vector<std::string> args = {self,
                                     "--import-child",
                                     fdArg,
                                     std::to_string(plan.slots),
                                     std::to_string(plan.width),
                                     std::to_string(plan.height),
                                     std::to_string(plan.shadowSize),
                                     std::to_string(plan.lastFrameId),
                                     std::to_string(plan.layers)};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t child = fork();
    if (child == 0)
    {
        close(sv[0]);
        execv(self.c_str(), argv.data());
        _exit(127);
    }
    close(sv[1]);
    const bool sent = child > 0 && sendLineWithFds(sv[0], description.dump() + "\n", fds);
    for (int fd : fds)
        close(fd);
    fds.clear();
    out.gotReport = sent && readAll(sv[0], &out.report, sizeof out.report);
    out.data.resize(plan.slots * slotBytes(plan));
    out.gotData = out.gotReport && out.report.status == 0 && readAll(sv[0], out.data.data(), out.data.size());
    close(sv[0]);
    if (child > 0)
        waitpid(child, &out.exitStatus, 0);
    return out;
}

template <typename T>
std::vector<T> slice(const std::vector<uint8_t>& data, size_t offset, size_t count)
{
    std::vector<T> values(count);
    std::memcpy(values.data(), data.data() + offset, count * sizeof(T));
    return values;
}

}  // namespace

TEST_F(FrameExportTest, ImportsIntoAnotherProcessExactly)
{
    Renderer& r = *renderer;
    ASSERT_TRUE(r.ctx.externalMemoryFd) << "the device lacks VK_KHR_external_memory_fd";
    setWeather(r, uniformLayer(0.6f, CloudType::Cumulus, 1200.0f, 2600.0f));
    FrameExport e;
    SkyStatus s = createFrameExport(r, e, 2, 128, 64, 48);  // frames smaller than the ring: top-left corner
    ASSERT_TRUE(s.ok()) << s.message;

    RenderResult frames[2];
    for (uint32_t slot = 0; slot < 2; ++slot)
    {
        frames[slot] = render(slot == 0 ? 0.0 : 120.0);
        ASSERT_EQ(frames[slot].shadowMapSize, kShadowSize);
        s = exportFrame(r, e, slot, slot + 1, frames[slot]);
        ASSERT_TRUE(s.ok()) << s.message;
    }
    // The two slots must be told apart: different views, and a shadow map with structure.
    ASSERT_NE(frames[0].displayRgba8, frames[1].displayRgba8);
    auto [lo, hi] = std::minmax_element(frames[0].shadowTransmittance.begin(), frames[0].shadowTransmittance.end());
    EXPECT_GT(*hi - *lo, 0.01f) << "a flat shadow map proves little";

    // The daemon's part of a vulkan subscribe: describe, send with SCM_RIGHTS, close our copies.
    nlohmann::json description;
    std::vector<int> fds;
    std::string error;
    ASSERT_TRUE(describeFrameExport(r, e, description, fds, error)) << error;
    ASSERT_EQ(description["images"].size(), 2u);
    EXPECT_EQ(description["images"][0]["width"], 128);
    EXPECT_EQ(description["images"][0]["vk_format"], int(VK_FORMAT_R8G8B8A8_UNORM));
    EXPECT_EQ(description["images"][1]["shadow"]["vk_format"], int(VK_FORMAT_R32_SFLOAT));
    EXPECT_EQ(description["images"][1]["shadow"]["width"], 48);
    EXPECT_TRUE(description["images"][1]["layers"].empty()) << "no layers asked for";
    EXPECT_EQ(description["timeline_semaphore"].get<bool>(), e.timeline != VK_NULL_HANDLE);
    EXPECT_EQ(description["device_uuid"].get<std::string>().size(), 32u);
    ASSERT_EQ(fds.size(), 4u + (e.timeline ? 1u : 0u));
    ReadPlan plan{2, kWidth, kHeight, kShadowSize, 0, 2};
    ChildResult child = importInChild(plan, description, fds);
    const ChildReport& report = child.report;
    ASSERT_TRUE(child.gotReport) << "the import child sent no report (exit status " << child.exitStatus << ")";
    ASSERT_EQ(report.status, 0) << report.error;
    ASSERT_TRUE(child.gotData);
    EXPECT_TRUE(WIFEXITED(child.exitStatus) && WEXITSTATUS(child.exitStatus) == 0);
    EXPECT_EQ(report.validationMessages, 0u) << "validation messages in the importing process";
    if (e.timeline)  // devices with VK_KHR_external_semaphore_fd: the child saw our signal of frame id 2
    {
        EXPECT_EQ(report.timelineValue, 2u);
    }
    std::printf("export: %s, timeline semaphore %s\n", r.ctx.deviceName.c_str(), e.timeline ? "exported" : "none");

    const std::vector<uint8_t>& data = child.data;
    size_t offset = 0;
    for (uint32_t slot = 0; slot < 2; ++slot)
    {
        const RenderResult& f = frames[slot];
        ASSERT_EQ(f.displayRgba8.size(), size_t(kWidth) * kHeight * 4);
        EXPECT_EQ(std::memcmp(data.data() + offset, f.displayRgba8.data(), f.displayRgba8.size()), 0)
            << "slot " << slot << ": the imported frame differs from the renderer's readback";
        offset += f.displayRgba8.size();
        std::vector<float> shadow(size_t(kShadowSize) * kShadowSize);
        std::memcpy(shadow.data(), data.data() + offset, shadow.size() * sizeof(float));
        offset += shadow.size() * sizeof(float);
        EXPECT_EQ(shadow, f.shadowTransmittance) << "slot " << slot << ": the imported shadow map differs";
    }
    destroyFrameExport(r, e);
    EXPECT_EQ(exportAllocations(r), 0u);
}

// The compositing layers: slot 0's frame reads them back (kRead*, what shm subscribers get), slot 1's
// draws them for the export only (kDraw*, no readback). The imported images must hold exactly what the
// renderer's layer images held: the readback for slot 0, a one-shot read of its images for slot 1.
TEST_F(FrameExportTest, LayersImportIntoAnotherProcessExactly)
{
    Renderer& r = *renderer;
    setWeather(r, uniformLayer(0.6f, CloudType::Cumulus, 1200.0f, 2600.0f));
    FrameExport e;
    SkyStatus s = createFrameExport(r, e, 2, 128, 64, 48);
    ASSERT_TRUE(s.ok()) << s.message;
    s = ensureExportedLayers(r, e, kExportAllLayers);
    ASSERT_TRUE(s.ok()) << s.message;

    const RenderResult read = render(0.0, true, kReadDisplay | kReadSky | kReadCloudLayer | kReadDepthLayer);
    ASSERT_EQ(read.cloudLayerRgbaHalf.size(), size_t(kWidth) * kHeight * 4);
    ASSERT_EQ(read.depthLayerM.size(), size_t(kWidth) * kHeight * 2);
    s = exportFrame(r, e, 0, 1, read, kExportAllLayers);
    ASSERT_TRUE(s.ok()) << s.message;

    const RenderResult drawn = render(120.0, true, kReadDisplay | kDrawSky | kDrawCloudLayer | kDrawDepthLayer);
    EXPECT_TRUE(drawn.cloudLayerRgbaHalf.empty() && drawn.depthLayerM.empty()) << "drawn only: nothing read back";
    s = exportFrame(r, e, 1, 2, drawn, kExportAllLayers);
    ASSERT_TRUE(s.ok()) << s.message;
    std::vector<uint8_t> drawnBytes[kExportLayerCount];
    const Image* images[kExportLayerCount] = {&r.composite.skyImage, &r.composite.cloudLayerImage,
                                              &r.composite.depthLayerImage};
    for (uint32_t k = 0; k < kExportLayerCount; ++k)
        ASSERT_TRUE(readbackImage(r.ctx, r.memory, *images[k], drawnBytes[k]).ok());

    // Clouds and depth only for this subscriber: the sky's images exist but are not sent.
    const uint32_t asked = (1u << kExportClouds) | (1u << kExportDepth);
    nlohmann::json description;
    std::vector<int> fds;
    std::string error;
    ASSERT_TRUE(describeFrameExport(r, e, asked, description, fds, error)) << error;
    const nlohmann::json& layers = description["images"][1]["layers"];
    EXPECT_FALSE(layers.contains("sky"));
    EXPECT_EQ(layers["clouds"]["vk_format"], int(VK_FORMAT_R16G16B16A16_SFLOAT));
    EXPECT_EQ(layers["depth"]["vk_format"], int(VK_FORMAT_R32G32_SFLOAT));
    EXPECT_EQ(layers["depth"]["width"], 128);
    EXPECT_EQ(layers["depth"]["height"], 64);
    ASSERT_EQ(fds.size(), 2u + 2u + 2u * 2u + (e.timeline ? 1u : 0u)) << "frames, shadows, clouds, depth";

    ReadPlan plan{2, kWidth, kHeight, kShadowSize, (1u << SKY_LAYER_CLOUDS) | (1u << SKY_LAYER_DEPTH), 2};
    ChildResult child = importInChild(plan, description, fds);
    ASSERT_TRUE(child.gotReport) << "the import child sent no report (exit status " << child.exitStatus << ")";
    ASSERT_EQ(child.report.status, 0) << child.report.error;
    ASSERT_TRUE(child.gotData);
    EXPECT_EQ(child.report.validationMessages, 0u) << "validation messages in the importing process";

    const size_t pixels = size_t(kWidth) * kHeight;
    const size_t layersAt = pixels * 4 + size_t(kShadowSize) * kShadowSize * 4;  // after frame and shadow
    // Slot 0: the readback.
    EXPECT_EQ(slice<uint16_t>(child.data, layersAt, pixels * 4), read.cloudLayerRgbaHalf) << "slot 0 clouds";
    EXPECT_EQ(slice<float>(child.data, layersAt + pixels * 8, pixels * 2), read.depthLayerM) << "slot 0 depth";
    // Slot 1: the renderer's images (kDraw*).
    const size_t slot1 = slotBytes(plan);
    EXPECT_EQ(slice<uint8_t>(child.data, slot1 + layersAt, pixels * 8), drawnBytes[kExportClouds]) << "slot 1 clouds";
    EXPECT_EQ(slice<uint8_t>(child.data, slot1 + layersAt + pixels * 8, pixels * 8), drawnBytes[kExportDepth])
        << "slot 1 depth";
    // Something to compare: clouds with alpha in view, fronts nearer than the weighted distances.
    size_t cloudy = 0;
    for (size_t i = 0; i < pixels; ++i)
        cloudy += read.depthLayerM[2 * i] > 0.0f && read.depthLayerM[2 * i] <= read.depthLayerM[2 * i + 1] ? 1 : 0;
    EXPECT_GT(cloudy, pixels / 10) << "too few cloud pixels for the comparison to mean much";
    EXPECT_NE(read.displayRgba8, drawn.displayRgba8);

    // A layer asked for that the frame did not draw is refused, naming it.
    const RenderResult plain = render(0.0, true, kReadDisplay);
    s = exportFrame(r, e, 0, 3, plain, 1u << kExportDepth);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message.find("depth"), std::string::npos) << s.message;
    destroyFrameExport(r, e);
    EXPECT_EQ(exportAllocations(r), 0u);
}

TEST_F(FrameExportTest, WithoutExternalMemoryFailsNamingTheExtension)
{
    Renderer& r = *renderer;
    // Simulates a device without the extension (lavapipe has it): the context records what it enabled.
    const bool saved = r.ctx.externalMemoryFd;
    r.ctx.externalMemoryFd = false;
    FrameExport e;
    SkyStatus s = createFrameExport(r, e, 2, 64, 32, 16);
    r.ctx.externalMemoryFd = saved;
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message.find("VK_KHR_external_memory_fd"), std::string::npos) << s.message;
    EXPECT_TRUE(e.frames.empty());
    EXPECT_EQ(exportAllocations(r), 0u);

    nlohmann::json description;
    std::vector<int> fds;
    std::string error;
    EXPECT_FALSE(describeFrameExport(r, e, description, fds, error));
    EXPECT_NE(error.find("VK_KHR_external_memory_fd"), std::string::npos) << error;
    EXPECT_TRUE(fds.empty());
}

TEST_F(FrameExportTest, RefusesFramesLargerThanTheRing)
{
    Renderer& r = *renderer;
    setWeather(r, clearSky());
    FrameExport e;
    ASSERT_TRUE(createFrameExport(r, e, 2, 64, 32, 0).ok());
    RenderResult f = render(0.0, false);
    SkyStatus s = exportFrame(r, e, 0, 1, f);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.message.find("larger"), std::string::npos) << s.message;
    EXPECT_FALSE(exportFrame(r, e, 2, 1, f).ok()) << "slot out of range";
    destroyFrameExport(r, e);
}

TEST_F(FrameExportTest, DestroyLeavesNothingTracked)
{
    Renderer& r = *renderer;
    const VkDeviceSize before = r.memory.totalBytes;
    FrameExport e;
    ASSERT_TRUE(createFrameExport(r, e, 3, 64, 32, 16).ok());
    EXPECT_EQ(exportAllocations(r), 6u);
    VkDeviceSize exported = 0;
    for (const auto& set : {e.frames, e.shadows})
        for (const ExportedImage& image : set)
            exported += image.allocationBytes;
    EXPECT_GE(exported, VkDeviceSize(3 * (64 * 32 * 4 + 16 * 16 * 4)));
    EXPECT_EQ(r.memory.totalBytes - before, exported);
    ASSERT_TRUE(ensureExportedLayers(r, e, 1u << kExportDepth).ok());
    ASSERT_TRUE(ensureExportedLayers(r, e, 1u << kExportDepth).ok()) << "made once";
    EXPECT_EQ(exportAllocations(r), 9u);
    EXPECT_EQ(e.layers[kExportDepth].size(), 3u);
    EXPECT_EQ(e.layers[kExportDepth][0].format, VK_FORMAT_R32G32_SFLOAT);
    EXPECT_TRUE(e.layers[kExportSky].empty());

    // Without shadow maps: no shadow entries, one fd per slot (plus the semaphore when exportable).
    FrameExport plain;
    ASSERT_TRUE(createFrameExport(r, plain, 2, 32, 16, 0).ok());
    nlohmann::json description;
    std::vector<int> fds;
    std::string error;
    ASSERT_TRUE(describeFrameExport(r, plain, description, fds, error)) << error;
    EXPECT_TRUE(description["images"][0]["shadow"].is_null());
    EXPECT_EQ(fds.size(), 2u + (plain.timeline ? 1u : 0u));
    for (int fd : fds)
        close(fd);

    destroyFrameExport(r, plain);
    destroyFrameExport(r, e);
    EXPECT_EQ(exportAllocations(r), 0u);
    EXPECT_EQ(r.memory.totalBytes, before);
    destroyFrameExport(r, e);  // twice is harmless
}

int main(int argc, char** argv)
{
    // The import child (ImportsIntoAnotherProcessExactly exec's this binary):
    //   --import-child FD SLOTS WIDTH HEIGHT SHADOW_SIZE LAST_FRAME_ID LAYERS
    if (argc == 9 && std::strcmp(argv[1], "--import-child") == 0)
    {
        ReadPlan plan;
        plan.slots = uint32_t(std::atoi(argv[3]));
        plan.width = uint32_t(std::atoi(argv[4]));
        plan.height = uint32_t(std::atoi(argv[5]));
        plan.shadowSize = uint32_t(std::atoi(argv[6]));
        plan.lastFrameId = std::strtoull(argv[7], nullptr, 10);
        plan.layers = uint32_t(std::atoi(argv[8]));
        return runImportChild(std::atoi(argv[2]), plan);
    }
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
