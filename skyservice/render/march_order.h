// SPDX-License-Identifier: MIT
// The launch order of the cloud march's workgroup rows (shaders/shared/march_order.h): costliest first,
// from the lookups the previous frame of the same shape counted.
#pragma once

#include "skyservice/vk/resources.h"

#include <cstdint>
#include <vector>

namespace sky
{

/// The march-order buffer and what it holds.
struct MarchOrder
{
    /// MarchOrderBlock (MARCH_ORDER_BUFFER_BYTES), device-local: the march reads the order at the start of
    /// every invocation and adds to the lookups, which in host-visible memory (PCIe on a discrete GPU)
    /// would cross the bus in every invocation, slowing the whole frame (BENCHMARKS.md).
    Buffer buffer;
    Buffer readback;  ///< host-visible copy of the lookups of the last march (MARCH_ORDER_MAX_ROWS words)
    /// Workgroup rows of the frame whose lookups the buffer holds (0: none measured yet). A frame with
    /// another number of rows (another size or march block) starts from the interleaved order.
    uint32_t measuredRows = 0;
};

/// The order without measurements: top and bottom rows in turn toward the middle (0, n-1, 1, n-2, ...),
/// so that a contiguous half of the dispatch holds sky and ground alike.
std::vector<uint32_t> interleavedRowOrder(uint32_t rows);

/**
 * Rows by their lookups, costliest first, for a device that runs `ranges` contiguous ranges of the
 * dispatch side by side: 1 on a GPU (whose scheduler starts workgroups in dispatch order as others
 * finish); lavapipe's thread count on it, which gives each thread one range. The rows are dealt to the
 * ranges (sizes as even as the count allows) each to the range with the least cost so far that has room,
 * and listed costliest first within each range. Ties keep the image order, so the order is a pure function
 * of the counts. Returns a permutation of 0..rows-1.
 */
std::vector<uint32_t> costliestFirstRowOrder(const uint32_t* rowLookups, uint32_t rows, uint32_t ranges);

/// How many contiguous ranges `ctx`'s device runs a dispatch in (see costliestFirstRowOrder).
uint32_t dispatchRanges(const Context& ctx);

SkyStatus createMarchOrder(const Context& ctx, MemoryTracker& tracker, MarchOrder& order);
void destroyMarchOrder(const Context& ctx, MemoryTracker& tracker, MarchOrder& order);

/// Records, ahead of a march of `rows` workgroup rows, the upload of the order it runs in (costliest
/// first from the last measurement when `costOrdered` and the shape matches, else interleaved) and the
/// zeroing of the lookups, then a barrier before compute. Returns the order.
std::vector<uint32_t> prepareMarchOrder(MarchOrder& order, VkCommandBuffer cmd, uint32_t rows, uint32_t ranges,
                                        bool costOrdered);

/// Records, after the march, the copy of its lookups to the host-visible readback buffer.
void recordMarchLookupsReadback(const MarchOrder& order, VkCommandBuffer cmd);

/// After the march's frame finished on the GPU: the lookups of its `rows` rows (image order), kept for
/// the next frame's order.
std::vector<uint32_t> collectMarchLookups(MarchOrder& order, uint32_t rows);

}  // namespace sky
