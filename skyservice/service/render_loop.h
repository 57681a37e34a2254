// SPDX-License-Identifier: MIT
// The render thread: the only thread that touches the Renderer. It renders at the configured rate (or
// when a `render` request asks), each frame from a copy of the latest view, time and weather taken under
// ServiceState's mutex, and publishes it into the shared-memory ring (beginSlot -> the zero-copy export
// of the same slot when a vulkan subscriber exists -> endSlot). Between frames it does the render jobs
// (write_files, the lazy creation of the frame export) and the files subscriptions.
#pragma once

#include "skyservice/ipc/shm_ring.h"
#include "skyservice/render/renderer.h"
#include "skyservice/service/files_root.h"
#include "skyservice/service/service_state.h"

#include <functional>
#include <memory>
#include <thread>

namespace sky
{

class RenderLoop
{
public:
    struct Setup
    {
        Renderer* renderer = nullptr;
        ShmRingWriter* ring = nullptr;
        ServiceState* state = nullptr;
        FilesRoot* filesRoot = nullptr;      ///< every file is written beneath it (null: none)
        std::function<void()> repliesReady;  ///< called after a reply was queued in state->replies
        uint32_t exportSlots = 3;            ///< images of the zero-copy export (the ring's slot count)
        uint32_t exportMaxWidth = 0, exportMaxHeight = 0, exportShadowSize = 0;
        /// Called on the render thread after each frame is counted (ok or failed), without ServiceState's
        /// mutex held: the CIGI link's Start of Frame. Optional.
        std::function<void(uint64_t frameId, bool ok)> frameEnded;
    };

    RenderLoop();
    RenderLoop(const RenderLoop&) = delete;
    RenderLoop& operator=(const RenderLoop&) = delete;
    ~RenderLoop();

    void start(const Setup& setup);
    /// Finishes the frame in progress, joins, and destroys the frame export (if one was created).
    void stop();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::thread thread_;
};

}  // namespace sky
