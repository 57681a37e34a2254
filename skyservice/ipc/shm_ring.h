// SPDX-License-Identifier: MIT
// The shared-memory frame ring (layout and locking rules: skyservice/ipc/shm_layout.h): the writer the
// service owns, and the reader that libskyclient and the tests use. No Vulkan, no renderer: CPU only.
#pragma once

#include "skyservice/ipc/parallel_copy.h"
#include "skyservice/ipc/shm_layout.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sky
{

struct ShmRingConfig
{
    std::string name;           ///< shm_open name, "/skyservice-<uid>-<hash>" style (leading slash, no other)
    uint32_t slotCount = 3;     ///< >= 2
    uint32_t maxWidth = 1920;   ///< largest frame (pixels)
    uint32_t maxHeight = 1080;
    uint32_t maxShadowSize = 1024;  ///< largest shadow map (texels per side)
    uint32_t bytesPerPixel = 4;     ///< 4 for SKY_FORMAT_RGBA8_SRGB, 8 for SKY_FORMAT_RGBA16F_LINEAR
    uint32_t mode = 0600;       ///< permission bits of the shared-memory object
};

/// One frame to publish. Pointers need only live for the call.
struct ShmFrame
{
    uint64_t frameId = 0;
    double simTimeUnixS = 0;
    double exposure = 1;
    SkyShmView view{};
    uint32_t format = SKY_FORMAT_RGBA8_SRGB;
    uint32_t width = 0, height = 0, rowBytes = 0;
    const void* pixels = nullptr;
    /// The compositing layers (index SKY_LAYER_SKY...; [SKY_LAYER_DISPLAY] is unused: `pixels`), tightly
    /// packed rows in the layer's format (shm_layout.h); null: not in this frame.
    const void* layers[SKY_LAYER_COUNT] = {};
    const float* shadowTransmittance = nullptr;  ///< null: no shadow map
    SkyShmShadowGeoRef shadow{};                 ///< shadow.size_texels texels per side
    /// Non-zero: frames with the same id carry the same shadow texels (a reused drawing,
    /// RenderResult::shadowMapId), so a slot that already holds them is not copied again.
    uint64_t shadowId = 0;
};

/// The service's side. Owns the mapping and the name; never waits for a reader.
class ShmRingWriter
{
public:
    ShmRingWriter() = default;
    ShmRingWriter(const ShmRingWriter&) = delete;
    ShmRingWriter& operator=(const ShmRingWriter&) = delete;
    ~ShmRingWriter() { destroy(); }

    /// Creates (replacing a stale object of the same name; one whose writer_pid still runs, another
    /// service, is refused), sizes and maps the ring; false + error.
    bool create(const ShmRingConfig& config, std::string& error);
    /// Unmaps and unlinks. Safe to call twice.
    void destroy();
    bool valid() const { return header_ != nullptr; }

    /// Opens the next slot for writing (its sequence becomes odd) and returns its index. The zero-copy
    /// exporter writes exported image `index` between beginSlot and endSlot.
    uint32_t beginSlot();
    /// Fills the open slot from `frame`, closes it (sequence even) and publishes it as the latest.
    /// False (slot left unpublished, sequence even again) when the frame is larger than the ring holds.
    bool endSlot(const ShmFrame& frame, std::string& error);
    /// beginSlot + endSlot.
    bool publish(const ShmFrame& frame, std::string& error);

    const std::string& name() const { return config_.name; }
    uint32_t slotCount() const { return config_.slotCount; }
    uint64_t totalBytes() const { return totalBytes_; }
    const ShmRingConfig& config() const { return config_; }

private:
    ShmRingConfig config_;
    SkyShmHeader* header_ = nullptr;
    // The writer's own copy of the geometry: what lies in the mapping may be scribbled by any process
    // that can open it, so the writer never reads an address back from it.
    uint64_t slotsOffset_ = 0, slotStride_ = 0;
    std::unique_ptr<ParallelCopy> copier_;  ///< the frame's images into the slot, on a few threads
    std::vector<CopyJob> copies_;
    SkyShmSlot* slot(uint32_t index) const
    {
        return reinterpret_cast<SkyShmSlot*>(reinterpret_cast<uint8_t*>(header_) + slotsOffset_ + index * slotStride_);
    }
    uint64_t totalBytes_ = 0;
    uint32_t openSlot_ = UINT32_MAX;
    std::vector<uint64_t> slotShadowId_;  ///< ShmFrame::shadowId each slot's shadow texels were copied from
};

/// A reader's view of one acquired slot. `pixels` and `shadow` point into the mapping.
struct ShmFrameView
{
    const SkyShmSlot* slot = nullptr;
    uint32_t slotIndex = 0;
    uint64_t sequence = 0;
    const uint8_t* pixels = nullptr;
    const float* shadow = nullptr;
    const uint8_t* layers[SKY_LAYER_COUNT] = {};  ///< null where the layer is not in the frame
    bool corrupt = false;  ///< acquire() failed on a stable slot whose fields do not fit its stride
};

/// The client's side: maps the ring read-only and checks its header.
class ShmRingReader
{
public:
    ShmRingReader() = default;
    ShmRingReader(const ShmRingReader&) = delete;
    ShmRingReader& operator=(const ShmRingReader&) = delete;
    ~ShmRingReader() { close(); }

    /// Maps `name` read-only; false + error on a missing object, bad magic/version or sizes that do not fit.
    bool open(const std::string& name, std::string& error);
    void close();
    bool valid() const { return header_ != nullptr; }

    uint64_t latestFrameId() const;
    /// True when the writer wakes waiters on each publish (SKY_SHM_FEATURE_PUBLISH_FUTEX).
    bool canWaitForPublish() const;
    /// Waits until a frame newer than `afterFrameId` is published, at most timeoutMs (one futex wait;
    /// spurious wakes return early) and returns the latest frame id. A writer without the futex feature:
    /// sleeps at most 1 ms instead.
    uint64_t waitForFrameAfter(uint64_t afterFrameId, int timeoutMs) const;
    /// The newest complete slot; false when none is published yet or the writer is in it (retry), or
    /// when its fields (width, height, row_bytes, offsets, shadow size) do not fit the slot (out.corrupt).
    /// The ring's geometry is the one checked at open(), never read back from the mapping.
    bool acquire(ShmFrameView& out) const;
    /// The slot `index` (< slotCount()) of the geometry checked at open().
    const SkyShmSlot* slot(uint32_t index) const;
    uint32_t slotCount() const { return slotCount_; }
    /// True when the slot's sequence is still the one seen at acquire (the read was not torn).
    bool stillValid(const ShmFrameView& view) const;
    const SkyShmHeader* header() const { return header_; }

private:
    const SkyShmHeader* header_ = nullptr;
    uint64_t mappedBytes_ = 0;
    // The geometry as checked at open(): anyone who may read the ring may be able to write it too
    // (socket_mode), so the header's copy is never trusted afterwards.
    uint32_t slotCount_ = 0;
    uint64_t slotsOffset_ = 0, slotStride_ = 0;
};

}  // namespace sky
