// SPDX-License-Identifier: MIT
#include "skyservice/render/march_order.h"

#include "shaders/shared/march_order.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <thread>

namespace sky
{

std::vector<uint32_t> interleavedRowOrder(uint32_t rows)
{
    std::vector<uint32_t> order(rows);
    for (uint32_t k = 0; k < rows; ++k)
        order[k] = k % 2 == 0 ? k / 2 : rows - 1 - k / 2;
    return order;
}

std::vector<uint32_t> costliestFirstRowOrder(const uint32_t* rowLookups, uint32_t rows, uint32_t ranges)
{
    std::vector<uint32_t> byCost(rows);
    std::iota(byCost.begin(), byCost.end(), 0u);
    std::stable_sort(byCost.begin(), byCost.end(),
                     [&](uint32_t a, uint32_t b) { return rowLookups[a] > rowLookups[b]; });
    ranges = std::clamp(ranges, 1u, std::max(rows, 1u));
    if (ranges == 1)
        return byCost;
    // Range i holds rows [i * rows / ranges, (i + 1) * rows / ranges) of the dispatch.
    std::vector<std::vector<uint32_t>> dealt(ranges);
    std::vector<uint64_t> cost(ranges, 0);
    for (uint32_t row : byCost)
    {
        uint32_t best = ranges;
        for (uint32_t i = 0; i < ranges; ++i)
        {
            const size_t room = size_t(uint64_t(i + 1) * rows / ranges - uint64_t(i) * rows / ranges);
            if (dealt[i].size() < room && (best == ranges || cost[i] < cost[best]))
                best = i;
        }
        dealt[best].push_back(row);
        cost[best] += rowLookups[row];
    }
    std::vector<uint32_t> order;
    order.reserve(rows);
    for (const auto& range : dealt)
        order.insert(order.end(), range.begin(), range.end());
    return order;
}

uint32_t dispatchRanges(const Context& ctx)
{
    if (ctx.properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU)
        return 1;
    // lavapipe runs LP_NUM_THREADS threads (default: one per CPU), each on a contiguous range.
    if (const char* env = std::getenv("LP_NUM_THREADS"))
    {
        const long n = std::strtol(env, nullptr, 10);
        if (n >= 1 && n <= 256)
            return uint32_t(n);
    }
    return std::max(1u, std::thread::hardware_concurrency());
}

SkyStatus createMarchOrder(const Context& ctx, MemoryTracker& tracker, MarchOrder& order)
{
    SKY_TRY(createBuffer(ctx, tracker, order.buffer, MARCH_ORDER_BUFFER_BYTES,
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                             VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         MemoryUse::DeviceLocal, "march order"));
    SKY_TRY(createBuffer(ctx, tracker, order.readback, MARCH_ORDER_MAX_ROWS * sizeof(uint32_t),
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::HostVisible, "march lookups readback"));
    std::memset(order.readback.mapped, 0, MARCH_ORDER_MAX_ROWS * sizeof(uint32_t));
    order.measuredRows = 0;
    return SkyStatus::success();
}

void destroyMarchOrder(const Context& ctx, MemoryTracker& tracker, MarchOrder& order)
{
    destroyBuffer(ctx, tracker, order.buffer);
    destroyBuffer(ctx, tracker, order.readback);
    order.measuredRows = 0;
}

std::vector<uint32_t> prepareMarchOrder(MarchOrder& order, VkCommandBuffer cmd, uint32_t rows, uint32_t ranges,
                                        bool costOrdered)
{
    rows = std::clamp(rows, 1u, MARCH_ORDER_MAX_ROWS);
    const auto* lookups = static_cast<const uint32_t*>(order.readback.mapped);
    std::vector<uint32_t> rowOrder = costOrdered && order.measuredRows == rows
                                         ? costliestFirstRowOrder(lookups, rows, ranges)
                                         : interleavedRowOrder(rows);
    order.measuredRows = 0;
    constexpr VkDeviceSize lookupsOffset = MARCH_ORDER_MAX_ROWS * sizeof(uint32_t);
    vkCmdUpdateBuffer(cmd, order.buffer.buffer, 0, rowOrder.size() * sizeof(uint32_t), rowOrder.data());
    vkCmdFillBuffer(cmd, order.buffer.buffer, lookupsOffset, lookupsOffset, 0u);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    return rowOrder;
}

void recordMarchLookupsReadback(const MarchOrder& order, VkCommandBuffer cmd)
{
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    const VkBufferCopy copy{MARCH_ORDER_MAX_ROWS * sizeof(uint32_t), 0, MARCH_ORDER_MAX_ROWS * sizeof(uint32_t)};
    vkCmdCopyBuffer(cmd, order.buffer.buffer, order.readback.buffer, 1, &copy);
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
}

std::vector<uint32_t> collectMarchLookups(MarchOrder& order, uint32_t rows)
{
    rows = std::clamp(rows, 1u, MARCH_ORDER_MAX_ROWS);
    const auto* lookups = static_cast<const uint32_t*>(order.readback.mapped);
    order.measuredRows = rows;
    return std::vector<uint32_t>(lookups, lookups + rows);
}

}  // namespace sky
