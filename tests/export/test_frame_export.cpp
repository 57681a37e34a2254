// SPDX-License-Identifier: MIT
// Zero-copy frame export (issue 6, skyservice/ipc/PROTOCOL.md) on the available Vulkan device
// (lavapipe in CI), validation on in both processes: two rendered frames with shadow maps are exported,
// their fds cross a real socketpair as SCM_RIGHTS into a forked and exec'd child, which imports them with
// skyclient_vulkan into its own VkInstance/VkDevice and reads them back: the bytes must equal the
// renderer's own readback exactly. Also: a device without VK_KHR_external_memory_fd fails cleanly with
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
    RenderResult render(double headingDeg, bool shadowMap = true)
    {
        ViewRequest v = lookUp(45.0, 7.0, 500.0, 15.0, "2024-06-21T09:00:00Z");
        v.pose.headingDeg = headingDeg;
        v.width = kWidth;
        v.height = kHeight;
        v.shadowMap = shadowMap;
        v.shadowMapSize = kShadowSize;
        v.shadowMapExtentM = 40000.0;
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

    // The client: exec'd (not just forked) so that it shares nothing with this process but the socket.
    int sv[2];
    ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
    std::string self = "/proc/self/exe", fdArg = std::to_string(sv[1]);
    std::string w = std::to_string(kWidth), h = std::to_string(kHeight), sz = std::to_string(kShadowSize);
    char* argv[] = {self.data(), const_cast<char*>("--import-child"), fdArg.data(), const_cast<char*>("2"), w.data(),
                    h.data(), sz.data(), const_cast<char*>("2"), nullptr};
    pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0)
    {
        close(sv[0]);
        execv(self.c_str(), argv);
        _exit(127);
    }
    close(sv[1]);

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
    EXPECT_EQ(description["timeline_semaphore"].get<bool>(), e.timeline != VK_NULL_HANDLE);
    EXPECT_EQ(description["device_uuid"].get<std::string>().size(), 32u);
    ASSERT_EQ(fds.size(), 4u + (e.timeline ? 1u : 0u));
    bool sent = sendLineWithFds(sv[0], description.dump() + "\n", fds);
    for (int fd : fds)
        close(fd);
    ASSERT_TRUE(sent);

    ChildReport report;
    bool gotReport = readAll(sv[0], &report, sizeof report);
    std::vector<uint8_t> data(2 * (size_t(kWidth) * kHeight * 4 + size_t(kShadowSize) * kShadowSize * 4));
    bool gotData = gotReport && report.status == 0 && readAll(sv[0], data.data(), data.size());
    close(sv[0]);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(gotReport) << "the import child sent no report (exit status " << status << ")";
    ASSERT_EQ(report.status, 0) << report.error;
    ASSERT_TRUE(gotData);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    EXPECT_EQ(report.validationMessages, 0u) << "validation messages in the importing process";
    if (e.timeline)  // devices with VK_KHR_external_semaphore_fd: the child saw our signal of frame id 2
    {
        EXPECT_EQ(report.timelineValue, 2u);
    }
    std::printf("export: %s, timeline semaphore %s\n", r.ctx.deviceName.c_str(), e.timeline ? "exported" : "none");

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
    //   --import-child FD SLOTS WIDTH HEIGHT SHADOW_SIZE LAST_FRAME_ID
    if (argc == 8 && std::strcmp(argv[1], "--import-child") == 0)
        return runImportChild(std::atoi(argv[2]), uint32_t(std::atoi(argv[3])), uint32_t(std::atoi(argv[4])),
                              uint32_t(std::atoi(argv[5])), uint32_t(std::atoi(argv[6])),
                              std::strtoull(argv[7], nullptr, 10));
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
