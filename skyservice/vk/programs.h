// SPDX-License-Identifier: MIT
// Compute programs: SPIR-V loading, reflection, pipelines and dispatch() (docs/style.md §9).
// The shader defines the interface: descriptor types, push-constant size and local size are reflected
// from the SPIR-V, and dispatch() checks every call against them. Descriptors are pushed
// (VK_KHR_push_descriptor), so no pools or sets are managed anywhere.
#pragma once

#include "skyservice/vk/resources.h"

#include <initializer_list>
#include <string>
#include <vector>

namespace sky
{

struct Program
{
    std::string name;
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    std::vector<VkDescriptorType> bindings;  ///< binding i has type bindings[i]
    uint32_t pushConstantSize = 0;           ///< bytes
    uint32_t localSize[3] = {1, 1, 1};
    /// The driver compiler's statistics, "name value, ..." per executable ("" unless the context captures
    /// them: ContextOptions::pipelineStatistics).
    std::string statistics;
};

/// What reflection found in a SPIR-V module (exposed for tests).
struct ShaderInterface
{
    std::vector<VkDescriptorType> bindings;
    uint32_t pushConstantSize = 0;
    uint32_t localSize[3] = {1, 1, 1};
};
bool reflectSpirv(const std::vector<uint32_t>& words, ShaderInterface& out, std::string& error);

/// Folder holding the compiled SPIR-V: $SKY_SPIRV_DIR if set, else the build's spirv/ folder.
std::string spirvDirectory();

/// Loads <spirvDirectory()>/<name>.spv and builds the pipeline. Fails with a message naming the file.
SkyStatus createProgram(const Context& ctx, Program& out, const char* name);
void destroyProgram(const Context& ctx, Program& program);

/// One descriptor: an image (storage or sampled, with its sampler) or a buffer.
struct DescriptorInfo
{
    VkDescriptorImageInfo image = {};
    VkDescriptorBufferInfo buffer = {};

    DescriptorInfo(const Image& img) { image = {VK_NULL_HANDLE, img.view, VK_IMAGE_LAYOUT_GENERAL}; }
    /// Sampled: through the image's sampled view where it has one (ImageDesc::sampledFormat).
    DescriptorInfo(const Image& img, VkSampler sampler)
    {
        image = {sampler, img.sampledView ? img.sampledView : img.view, VK_IMAGE_LAYOUT_GENERAL};
    }
    DescriptorInfo(const Buffer& buf) { buffer = {buf.buffer, 0, buf.size}; }
};

/// Binds `program`, pushes its descriptors and constants and dispatches enough groups to cover
/// threadsX x threadsY x threadsZ invocations (group counts from the reflected local size).
/// Aborts when the constants' size or the descriptor count does not match the shader.
void dispatch(const Context& ctx, VkCommandBuffer cmd, const Program& program, uint32_t threadsX, uint32_t threadsY,
              uint32_t threadsZ, const void* constants, uint32_t constantsSize,
              std::initializer_list<DescriptorInfo> descriptors);

template <typename T>
void dispatch(const Context& ctx, VkCommandBuffer cmd, const Program& program, uint32_t threadsX, uint32_t threadsY,
              uint32_t threadsZ, const T& constants, std::initializer_list<DescriptorInfo> descriptors)
{
    dispatch(ctx, cmd, program, threadsX, threadsY, threadsZ, &constants, uint32_t(sizeof(T)), descriptors);
}

}  // namespace sky
