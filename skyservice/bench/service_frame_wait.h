// SPDX-License-Identifier: MIT
// The zero-copy transport's "frame complete" for sky-service-bench: where the service exports a timeline
// semaphore, a slot may be published in the ring before the GPU finished it, and a client must wait
// for the semaphore to reach the frame id (skyclient_vulkan.h). This imports that semaphore into a
// minimal Vulkan device of the bench's own, on the service's GPU, and waits on it. Without a semaphore
// (lavapipe), publication in the ring already means the GPU finished, and nothing is created.
#pragma once

#include "skyservice/client/skyclient.h"

#include <cstdint>
#include <string>
#include <vulkan/vulkan.h>

namespace sky
{

class FrameCompletionWait
{
  public:
    FrameCompletionWait() = default;
    FrameCompletionWait(const FrameCompletionWait&) = delete;
    FrameCompletionWait& operator=(const FrameCompletionWait&) = delete;
    ~FrameCompletionWait();

    /**
     * Takes every fd of `frames`: the images' are closed (the bench times delivery, it does not read
     * the images), the semaphore's is imported.
     *
     * @param[in,out] frames from sky_client_subscribe_vulkan; every fd in it is -1 afterwards.
     * @param[out] error on failure, which step failed (instance, device, import) and why.
     **********************************************************************/
    bool open(SkyExportedFrames& frames, std::string& error);

    /// True when the service exported a timeline semaphore (and it was imported).
    bool hasSemaphore() const { return semaphore_ != VK_NULL_HANDLE; }

    /**
     * Waits until the service's timeline semaphore reaches `frameId`; returns at once without one.
     *
     * @param[in] frameId SkyFrame::frame_id of the acquired frame.
     * @param[in] timeoutNs how long to wait (ns).
     * @param[out] error on failure or timeout, what happened.
     **********************************************************************/
    bool wait(uint64_t frameId, uint64_t timeoutNs, std::string& error);

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkSemaphore semaphore_ = VK_NULL_HANDLE;
};

} // namespace sky
