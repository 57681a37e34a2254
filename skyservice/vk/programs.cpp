// SPDX-License-Identifier: MIT
#include "skyservice/vk/programs.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>

namespace sky
{
namespace
{

// SPIR-V opcodes and enums used by the reflection below (SPIR-V specification, section 3).
enum : uint32_t
{
    OpTypeInt = 21,
    OpTypeFloat = 22,
    OpTypeVector = 23,
    OpTypeMatrix = 24,
    OpTypeImage = 25,
    OpTypeSampler = 26,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeStruct = 30,
    OpTypePointer = 32,
    OpConstant = 43,
    OpExecutionMode = 16,
    OpExecutionModeId = 331,
    ExecutionModeLocalSizeId = 38,
    OpVariable = 59,
    OpDecorate = 71,
    OpMemberDecorate = 72,
    ExecutionModeLocalSize = 17,
    DecorationBlock = 2,
    DecorationBufferBlock = 3,
    DecorationMatrixStride = 7,
    DecorationArrayStride = 6,
    DecorationBinding = 33,
    DecorationDescriptorSet = 34,
    DecorationOffset = 35,
    StorageUniformConstant = 0,
    StorageUniform = 2,
    StoragePushConstant = 9,
    StorageStorageBuffer = 12,
};

struct Id
{
    uint32_t opcode = 0;
    std::vector<uint32_t> operands;  // words after the opcode word
    int binding = -1;
    int set = -1;
    uint32_t arrayStride = 0;
    bool block = false;
    bool bufferBlock = false;
    std::map<uint32_t, uint32_t> memberOffsets;
    std::map<uint32_t, uint32_t> memberMatrixStride;
};

uint32_t typeSize(const std::vector<Id>& ids, uint32_t type, uint32_t matrixStride)
{
    const Id& t = ids[type];
    switch (t.opcode)
    {
    case OpTypeInt:
    case OpTypeFloat:
        return t.operands[1] / 8;
    case OpTypeVector:
        return typeSize(ids, t.operands[1], 0) * t.operands[2];
    case OpTypeMatrix:
        return (matrixStride ? matrixStride : typeSize(ids, t.operands[1], 0)) * t.operands[2];
    case OpTypeArray:
    {
        const Id& length = ids[t.operands[2]];
        uint32_t count = length.opcode == OpConstant ? length.operands[2] : 1;
        uint32_t stride = t.arrayStride ? t.arrayStride : typeSize(ids, t.operands[1], 0);
        return stride * count;
    }
    case OpTypeStruct:
    {
        uint32_t size = 0;
        for (uint32_t m = 1; m < t.operands.size(); ++m)
        {
            auto off = t.memberOffsets.find(m - 1);
            auto ms = t.memberMatrixStride.find(m - 1);
            uint32_t end = (off == t.memberOffsets.end() ? 0 : off->second) +
                           typeSize(ids, t.operands[m], ms == t.memberMatrixStride.end() ? 0 : ms->second);
            size = std::max(size, end);
        }
        return size;
    }
    default:
        return 0;
    }
}

// What one pass over the module's instructions records: every id's declaration and decorations, the
// variables in declaration order, and the LocalSizeId constants still to be resolved.
struct ParsedModule
{
    uint32_t bound = 0;
    std::vector<Id> ids;
    std::vector<uint32_t> variables;
    uint32_t localSizeIds[3] = {0, 0, 0};
};

// Records one OpDecorate on its target id.
void recordDecoration(const uint32_t* op, uint32_t nops, ParsedModule& module)
{
    if (nops < 2 || op[0] >= module.bound)
        return;
    Id& id = module.ids[op[0]];
    if (op[1] == DecorationBinding && nops >= 3)
        id.binding = int(op[2]);
    else if (op[1] == DecorationDescriptorSet && nops >= 3)
        id.set = int(op[2]);
    else if (op[1] == DecorationBlock)
        id.block = true;
    else if (op[1] == DecorationBufferBlock)
        id.bufferBlock = true;
    else if (op[1] == DecorationArrayStride && nops >= 3)
        id.arrayStride = op[2];
}

// Records one instruction. OpExecutionMode's literal local size goes straight to out.
void recordInstruction(uint32_t opcode, const uint32_t* op, uint32_t nops, ParsedModule& module,
                       ShaderInterface& out)
{
    switch (opcode)
    {
    case OpExecutionMode:
        if (nops >= 5 && op[1] == ExecutionModeLocalSize)
            out.localSize[0] = op[2], out.localSize[1] = op[3], out.localSize[2] = op[4];
        break;
    case OpExecutionModeId:
        // SPIR-V 1.6 (Vulkan 1.3 target) states the local size by constant ids.
        if (nops >= 5 && op[1] == ExecutionModeLocalSizeId)
            module.localSizeIds[0] = op[2], module.localSizeIds[1] = op[3], module.localSizeIds[2] = op[4];
        break;
    case OpDecorate:
        recordDecoration(op, nops, module);
        break;
    case OpMemberDecorate:
        if (nops >= 4 && op[0] < module.bound)
        {
            if (op[2] == DecorationOffset)
                module.ids[op[0]].memberOffsets[op[1]] = op[3];
            else if (op[2] == DecorationMatrixStride)
                module.ids[op[0]].memberMatrixStride[op[1]] = op[3];
        }
        break;
    case OpTypeInt:
    case OpTypeFloat:
    case OpTypeVector:
    case OpTypeMatrix:
    case OpTypeImage:
    case OpTypeSampler:
    case OpTypeSampledImage:
    case OpTypeArray:
    case OpTypeStruct:
    case OpTypePointer:
        if (nops >= 1 && op[0] < module.bound)
        {
            module.ids[op[0]].opcode = opcode;
            module.ids[op[0]].operands.assign(op, op + nops);
        }
        break;
    case OpConstant:
    case OpVariable:
        if (nops >= 2 && op[1] < module.bound)
        {
            module.ids[op[1]].opcode = opcode;
            module.ids[op[1]].operands.assign(op, op + nops);
            if (opcode == OpVariable)
                module.variables.push_back(op[1]);
        }
        break;
    default:
        break;
    }
}

// Walks the instructions after the five-word header.
bool parseInstructions(const std::vector<uint32_t>& words, ParsedModule& module, ShaderInterface& out,
                       std::string& error)
{
    module.bound = words[3];
    module.ids.resize(module.bound);
    for (size_t i = 5; i < words.size();)
    {
        uint32_t opcode = words[i] & 0xffff;
        uint32_t count = words[i] >> 16;
        if (count == 0 || i + count > words.size())
        {
            error = "truncated SPIR-V instruction";
            return false;
        }
        recordInstruction(opcode, &words[i + 1], count - 1, module, out);
        i += count;
    }
    return true;
}

// Replaces the literal local size by the constants LocalSizeId names, where it names them.
bool resolveLocalSizeIds(const ParsedModule& module, ShaderInterface& out, std::string& error)
{
    const std::vector<Id>& ids = module.ids;
    for (int k = 0; k < 3; ++k)
        if (module.localSizeIds[k])
        {
            if (module.localSizeIds[k] >= module.bound || ids[module.localSizeIds[k]].opcode != OpConstant ||
                ids[module.localSizeIds[k]].operands.size() < 3)
            {
                error = "LocalSizeId does not name a constant";
                return false;
            }
            out.localSize[k] = ids[module.localSizeIds[k]].operands[2];
        }
    return true;
}

// The descriptor type of a resource variable from its storage class and pointee type; false when the
// renderer does not support it.
bool descriptorTypeOf(uint32_t storage, const Id& type, VkDescriptorType& dt)
{
    if (storage == StorageUniformConstant && type.opcode == OpTypeImage)
        dt = type.operands[6] == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    else if (storage == StorageUniformConstant && type.opcode == OpTypeSampledImage)
        dt = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    else if (storage == StorageUniformConstant && type.opcode == OpTypeSampler)
        dt = VK_DESCRIPTOR_TYPE_SAMPLER;
    else if (storage == StorageUniform && type.block)
        dt = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    else if ((storage == StorageUniform && type.bufferBlock) || storage == StorageStorageBuffer)
        dt = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    else
        return false;
    return true;
}

// Sizes the push-constant block and maps each bound resource variable to its descriptor type.
bool collectResources(const ParsedModule& module, ShaderInterface& out, std::map<int, VkDescriptorType>& bindings,
                      std::string& error)
{
    const std::vector<Id>& ids = module.ids;
    for (uint32_t v : module.variables)
    {
        const Id& var = ids[v];
        uint32_t storage = var.operands[2];
        const Id& ptr = ids[var.operands[0]];
        if (ptr.opcode != OpTypePointer)
            continue;
        uint32_t pointee = ptr.operands[2];
        const Id& type = ids[pointee];
        if (storage == StoragePushConstant)
        {
            out.pushConstantSize = typeSize(ids, pointee, 0);
            continue;
        }
        if (var.binding < 0)
            continue;
        if (var.set > 0)
        {
            error = "descriptor set " + std::to_string(var.set) + " used: only set 0 is supported";
            return false;
        }
        VkDescriptorType dt;
        if (!descriptorTypeOf(storage, type, dt))
        {
            error = "unsupported resource at binding " + std::to_string(var.binding);
            return false;
        }
        bindings[var.binding] = dt;
    }
    return true;
}

// Lists the descriptor types in binding order: ShaderInterface::bindings is indexed by binding number
// (skyservice/vk/programs.h), so a gap cannot be expressed.
bool numberBindings(const std::map<int, VkDescriptorType>& bindings, ShaderInterface& out, std::string& error)
{
    for (const auto& [binding, type] : bindings)
    {
        if (binding != int(out.bindings.size()))
        {
            error = "bindings must be numbered 0..n-1 without gaps (missing " + std::to_string(out.bindings.size()) +
                    ")";
            return false;
        }
        out.bindings.push_back(type);
    }
    return true;
}

}  // namespace

bool reflectSpirv(const std::vector<uint32_t>& words, ShaderInterface& out, std::string& error)
{
    out = ShaderInterface{};
    if (words.size() < 5 || words[0] != 0x07230203)
    {
        error = "not a SPIR-V module (bad magic number)";
        return false;
    }
    ParsedModule module;
    if (!parseInstructions(words, module, out, error) || !resolveLocalSizeIds(module, out, error))
        return false;
    std::map<int, VkDescriptorType> bindings;
    return collectResources(module, out, bindings, error) && numberBindings(bindings, out, error);
}

std::string spirvDirectory()
{
    const char* env = std::getenv("SKY_SPIRV_DIR");
    return env && *env ? env : SKY_SPIRV_DIR;
}

namespace
{

std::string statisticValue(const VkPipelineExecutableStatisticKHR& s)
{
    switch (s.format)
    {
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: return s.value.b32 ? "true" : "false";
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: return std::to_string(s.value.i64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: return std::to_string(s.value.u64);
    case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: return std::to_string(s.value.f64);
    default: return "?";
    }
}

// "name value, ..." of each executable of the pipeline (a compute pipeline has one), "" when the context
// does not capture them.
std::string pipelineStatistics(const Context& ctx, VkPipeline pipeline)
{
    if (!ctx.getPipelineExecutableProperties)
        return "";
    VkPipelineInfoKHR info = {VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
    info.pipeline = pipeline;
    uint32_t count = 0;
    if (ctx.getPipelineExecutableProperties(ctx.device, &info, &count, nullptr) != VK_SUCCESS)
        return "";
    std::string out;
    for (uint32_t e = 0; e < count; ++e)
    {
        VkPipelineExecutableInfoKHR exec = {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
        exec.pipeline = pipeline;
        exec.executableIndex = e;
        uint32_t n = 0;
        if (ctx.getPipelineExecutableStatistics(ctx.device, &exec, &n, nullptr) != VK_SUCCESS)
            continue;
        std::vector<VkPipelineExecutableStatisticKHR> stats(n, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        if (ctx.getPipelineExecutableStatistics(ctx.device, &exec, &n, stats.data()) != VK_SUCCESS)
            continue;
        for (uint32_t k = 0; k < n; ++k)
            out += (out.empty() ? "" : ", ") + std::string(stats[k].name) + " " + statisticValue(stats[k]);
    }
    return out;
}

}  // namespace

SkyStatus createProgram(const Context& ctx, Program& out, const char* name)
{
    out = Program{};
    std::string path = spirvDirectory() + "/" + name + (ctx.paramsInStorageBuffers ? ".storage.spv" : ".spv");
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file)
        return SkyStatus::failure("cannot open shader " + path + " (set SKY_SPIRV_DIR?)", VK_ERROR_INITIALIZATION_FAILED);
    auto bytes = size_t(file.tellg());
    std::vector<uint32_t> words(bytes / 4);
    file.seekg(0);
    file.read(reinterpret_cast<char*>(words.data()), std::streamsize(words.size() * 4));
    ShaderInterface iface;
    std::string error;
    if (!reflectSpirv(words, iface, error))
        return SkyStatus::failure(path + ": " + error, VK_ERROR_INITIALIZATION_FAILED);

    VkShaderModuleCreateInfo moduleInfo = {VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    moduleInfo.codeSize = words.size() * 4;
    moduleInfo.pCode = words.data();
    VK_TRY(vkCreateShaderModule(ctx.device, &moduleInfo, nullptr, &out.module));

    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    for (uint32_t i = 0; i < iface.bindings.size(); ++i)
    {
        VkDescriptorSetLayoutBinding b = {};
        b.binding = i;
        b.descriptorType = iface.bindings[i];
        b.descriptorCount = 1;
        b.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
        layoutBindings.push_back(b);
    }
    VkDescriptorSetLayoutCreateInfo setInfo = {VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(layoutBindings.size());
    setInfo.pBindings = layoutBindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &setInfo, nullptr, &out.setLayout));

    VkPushConstantRange range = {VK_SHADER_STAGE_COMPUTE_BIT, 0, iface.pushConstantSize};
    VkPipelineLayoutCreateInfo layoutInfo = {VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &out.setLayout;
    layoutInfo.pushConstantRangeCount = iface.pushConstantSize ? 1 : 0;
    layoutInfo.pPushConstantRanges = &range;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &layoutInfo, nullptr, &out.layout));

    VkComputePipelineCreateInfo pipelineInfo = {VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    pipelineInfo.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipelineInfo.stage.module = out.module;
    pipelineInfo.stage.pName = "main";
    pipelineInfo.layout = out.layout;
    if (ctx.getPipelineExecutableProperties)
        pipelineInfo.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
    VkResult r = vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &out.pipeline);
    if (r != VK_SUCCESS)
    {
        out.pipeline = VK_NULL_HANDLE;
        destroyProgram(ctx, out);
        return SkyStatus::failure(std::string("cannot create the pipeline for ") + path + ": " + vkResultName(r), r);
    }
    out.name = name;
    out.bindings = iface.bindings;
    out.pushConstantSize = iface.pushConstantSize;
    for (int i = 0; i < 3; ++i)
        out.localSize[i] = iface.localSize[i];
    setObjectName(ctx, VK_OBJECT_TYPE_PIPELINE, uint64_t(out.pipeline), name);
    out.statistics = pipelineStatistics(ctx, out.pipeline);
    return SkyStatus::success();
}

void destroyProgram(const Context& ctx, Program& program)
{
    if (program.pipeline)
        vkDestroyPipeline(ctx.device, program.pipeline, nullptr);
    if (program.layout)
        vkDestroyPipelineLayout(ctx.device, program.layout, nullptr);
    if (program.setLayout)
        vkDestroyDescriptorSetLayout(ctx.device, program.setLayout, nullptr);
    if (program.module)
        vkDestroyShaderModule(ctx.device, program.module, nullptr);
    program = Program{};
}

void dispatch(const Context& ctx, VkCommandBuffer cmd, const Program& program, uint32_t threadsX, uint32_t threadsY,
              uint32_t threadsZ, const void* constants, uint32_t constantsSize,
              std::initializer_list<DescriptorInfo> descriptors)
{
    if (constantsSize != program.pushConstantSize || descriptors.size() != program.bindings.size())
    {
        std::fprintf(stderr, "dispatch(%s): shader wants %u bytes of constants and %zu descriptors, got %u and %zu\n",
                     program.name.c_str(), program.pushConstantSize, program.bindings.size(), constantsSize,
                     descriptors.size());
        std::abort();
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program.pipeline);
    if (!program.bindings.empty())
    {
        std::vector<VkWriteDescriptorSet> writes(descriptors.size());
        uint32_t i = 0;
        for (const DescriptorInfo& d : descriptors)
        {
            VkWriteDescriptorSet& w = writes[i];
            w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstBinding = i;
            w.descriptorCount = 1;
            w.descriptorType = program.bindings[i];
            bool isBuffer = w.descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ||
                            w.descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            if (isBuffer)
                w.pBufferInfo = &d.buffer;
            else
                w.pImageInfo = &d.image;
            ++i;
        }
        ctx.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, program.layout, 0, uint32_t(writes.size()), writes.data());
    }
    if (constantsSize)
        vkCmdPushConstants(cmd, program.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, constantsSize, constants);
    auto groups = [](uint32_t threads, uint32_t local) { return (threads + local - 1) / local; };
    vkCmdDispatch(cmd, groups(threadsX, program.localSize[0]), groups(threadsY, program.localSize[1]),
                  groups(threadsZ, program.localSize[2]));
}

}  // namespace sky
