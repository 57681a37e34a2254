// SPDX-License-Identifier: MIT
// The other side of the frame-export tests: a client process that receives the service's `subscribed`
// description and fds over a Unix socket (SCM_RIGHTS), imports them with skyclient_vulkan into its own
// VkInstance/VkDevice (validation on), copies every slot to host memory and writes the bytes back.
#pragma once

#include "skyservice/client/skyclient.h"

#include <cstdint>
#include <string>
#include <vector>

namespace sky::exporttest
{

/// Sends one line and `fds` with one sendmsg (what the control socket does for a vulkan subscribe).
bool sendLineWithFds(int socket, const std::string& line, const std::vector<int>& fds);
/// Receives one line (up to the newline, one recvmsg) and the fds that came with it.
bool receiveLineWithFds(int socket, std::string& line, std::vector<int>& fds);

/// What to read from every slot (the top-left corners of the exported images).
struct ReadPlan
{
    uint32_t slots = 0;
    uint32_t width = 0, height = 0;  ///< the frame (RGBA8, 4 bytes a pixel)
    uint32_t shadowSize = 0;         ///< 0 = no shadow maps (else shadowSize^2 floats)
    uint32_t layers = 0;             ///< compositing layers, bit k = SKY_LAYER_k: sky, clouds, depth (8 bytes a pixel)
    uint64_t lastFrameId = 0;        ///< waited for on the timeline semaphore, when one is exported
};

/// Bytes of one slot in the data read: its frame, its shadow map, then its layers in SKY_LAYER_* order.
size_t slotBytes(const ReadPlan& plan);

/// What the child sends back, in this order: ChildReport, then the slots' data (slotBytes each, when
/// status == 0).
struct ChildReport
{
    int32_t status = -1;              ///< 0 = imported and read
    uint32_t validationMessages = 0;  ///< warnings and errors of the importer's validation layer
    uint64_t timelineValue = 0;       ///< the imported timeline semaphore's value after the wait (0 = none)
    char error[256] = {};
};

/**
 * The importer's side: makes its own VkInstance/VkDevice (validation on) on the exporting GPU, imports
 * `frames` with skyclient_vulkan (the fds become its), waits for the timeline semaphore (when exported)
 * to reach plan.lastFrameId, and copies every slot into `data`. Everything is destroyed before it returns
 * (report.validationMessages counts the teardown's messages too).
 * @return true when imported and read; false with report.error.
 **********************************************************************/
bool importAndRead(SkyExportedFrames& frames, const ReadPlan& plan, ChildReport& report, std::vector<uint8_t>& data);

/// The child's main: `socket` is its end of the socketpair; receives the description line and fds (the
/// `subscribed` reply's images/timeline_semaphore/uuids, PROTOCOL.md fd order), imports and reads them,
/// sends the report and data back. Returns the exit code.
int runImportChild(int socket, const ReadPlan& plan);

}  // namespace sky::exporttest
