// SPDX-License-Identifier: MIT
// The other side of the frame-export tests: a client process that receives the service's `subscribed`
// description and fds over a Unix socket (SCM_RIGHTS), imports them with skyclient_vulkan into its own
// VkInstance/VkDevice (validation on), copies every slot to host memory and writes the bytes back.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sky::exporttest
{

/// Sends one line and `fds` with one sendmsg (what the control socket does for a vulkan subscribe).
bool sendLineWithFds(int socket, const std::string& line, const std::vector<int>& fds);
/// Receives one line (up to the newline, one recvmsg) and the fds that came with it.
bool receiveLineWithFds(int socket, std::string& line, std::vector<int>& fds);

/// What the child sends back, in this order: ChildReport, then for each slot the frame's
/// width*height*4 bytes and the shadow's shadowSize^2 floats (when status == 0).
struct ChildReport
{
    int32_t status = -1;              ///< 0 = imported and read
    uint32_t validationMessages = 0;  ///< warnings and errors of the child's validation layer
    uint64_t timelineValue = 0;       ///< the imported timeline semaphore's value after the wait (0 = none)
    char error[256] = {};
};

/// The child's main: `socket` is its end of the socketpair; reads `slots` slots of width x height frames
/// and shadowSize^2 shadow maps (top-left corners of the exported images), after waiting for the timeline
/// semaphore (when exported) to reach `lastFrameId`. Returns the exit code.
int runImportChild(int socket, uint32_t slots, uint32_t width, uint32_t height, uint32_t shadowSize,
                   uint64_t lastFrameId);

}  // namespace sky::exporttest
