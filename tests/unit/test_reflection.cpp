// SPDX-License-Identifier: MIT
// SPIR-V reflection (skyservice/vk/programs.cpp) on the project's own compiled shaders: the interface
// dispatch() checks against must be what the GLSL declares.
#include "shaders/shared/atmosphere_params.h"
#include "shaders/shared/noise_params.h"
#include "skyservice/vk/programs.h"

#include <fstream>
#include <gtest/gtest.h>

namespace
{

std::vector<uint32_t> loadSpirv(const std::string& name)
{
    std::ifstream f(sky::spirvDirectory() + "/" + name + ".spv", std::ios::binary | std::ios::ate);
    std::vector<uint32_t> words(size_t(f.tellg()) / 4);
    f.seekg(0);
    f.read(reinterpret_cast<char*>(words.data()), std::streamsize(words.size() * 4));
    return words;
}

}  // namespace

TEST(Reflection, CloudMarchInterface)
{
    sky::ShaderInterface iface;
    std::string error;
    ASSERT_TRUE(sky::reflectSpirv(loadSpirv("cloud_march"), iface, error)) << error;
    ASSERT_EQ(iface.bindings.size(), 15u);
    EXPECT_EQ(iface.bindings[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
    EXPECT_EQ(iface.bindings[2], VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    EXPECT_EQ(iface.bindings[8], VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    EXPECT_EQ(iface.bindings[10], VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);  // the light volume
    EXPECT_EQ(iface.bindings[11], VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);  // the column bounds
    EXPECT_EQ(iface.bindings[12], VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);  // the light volume's far cascade
    EXPECT_EQ(iface.bindings[13], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);          // the row order (march_order.h)
    EXPECT_EQ(iface.bindings[14], VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);           // the cloud's front distance
    EXPECT_EQ(iface.localSize[0], uint32_t(WORKGROUP_SIZE_2D));
    EXPECT_EQ(iface.pushConstantSize, 0u);
}

// The variant for lavapipe reads the same parameter blocks as storage buffers (bindings.h PARAMS_BLOCK).
TEST(Reflection, StorageVariantReadsParametersFromStorageBuffers)
{
    for (const char* name : {"cloud_march", "composite", "reconstruct", "shadow_map", "sky_view_lut", "light_volume"})
    {
        sky::ShaderInterface plain, storage;
        std::string error;
        ASSERT_TRUE(sky::reflectSpirv(loadSpirv(name), plain, error)) << error;
        ASSERT_TRUE(sky::reflectSpirv(loadSpirv(std::string(name) + ".storage"), storage, error)) << error;
        ASSERT_EQ(plain.bindings.size(), storage.bindings.size()) << name;
        int uniforms = 0;
        for (size_t i = 0; i < plain.bindings.size(); ++i)
            if (plain.bindings[i] == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
            {
                ++uniforms;
                EXPECT_EQ(storage.bindings[i], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) << name << " binding " << i;
            }
            else
                EXPECT_EQ(storage.bindings[i], plain.bindings[i]) << name << " binding " << i;
        EXPECT_GE(uniforms, 1) << name;
    }
}

TEST(Reflection, PushConstantSizesMatchSharedStructs)
{
    sky::ShaderInterface iface;
    std::string error;
    ASSERT_TRUE(sky::reflectSpirv(loadSpirv("sky_view_lut"), iface, error)) << error;
    EXPECT_EQ(iface.pushConstantSize, sizeof(SkyViewPushConstants));
    ASSERT_TRUE(sky::reflectSpirv(loadSpirv("base_noise"), iface, error)) << error;
    EXPECT_EQ(iface.pushConstantSize, sizeof(NoisePush));
    EXPECT_EQ(iface.localSize[0], uint32_t(NOISE_WORKGROUP_SIZE));  // 8x1x1: fast on lavapipe (noise_params.h)
}

TEST(Reflection, RejectsGarbage)
{
    sky::ShaderInterface iface;
    std::string error;
    EXPECT_FALSE(sky::reflectSpirv({1, 2, 3, 4, 5, 6}, iface, error));
    EXPECT_NE(error.find("magic"), std::string::npos);
    // Cut the module after its 12th instruction (in the declarations, which reflection reads) and end it
    // with an instruction claiming 65535 words.
    std::vector<uint32_t> truncated = loadSpirv("composite");
    size_t at = 5;  // after the header
    for (int k = 0; k < 12; ++k)
        at += truncated[at] >> 16;
    truncated.resize(at);
    truncated.push_back(0xffff0001u);
    EXPECT_FALSE(sky::reflectSpirv(truncated, iface, error));
}
