// SPDX-License-Identifier: MIT
// A stand-in for the daemon in libskyclient's tests: the real ControlSocketServer, parseRequest and
// ShmRingWriter, with canned answers and no renderer. Its poll() runs on its own thread; frames are
// published by the test thread only (the ring has one writer).
#pragma once

#include "skyservice/ipc/control_socket.h"
#include "skyservice/ipc/protocol.h"
#include "skyservice/ipc/shm_ring.h"

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace sky::test
{

class FakeService
{
public:
    /// Listens at `socketPath`, creates a ring of `slots` slots (64x32, shadow 8) under a unique name.
    FakeService(const std::string& socketPath, uint32_t slots = 3);
    ~FakeService() { stop(); }

    /// Stops polling and closes every connection and the socket (the "service went away").
    void stop();
    /// Publishes a frame whose pixel bytes are all `frameId & 0xff` and shadow texels `frameId`.
    void publish(uint64_t frameId, uint32_t width = 32, uint32_t height = 16);

    ShmRingWriter ring;
    std::atomic<int> requests{0};
    /// The last set_time "time" string the fake received.
    std::string lastTime() const;
    /// The last set_view "view" the fake received.
    ViewUpdate lastView() const;

private:
    void onLine(ClientId client, std::string_view line);
    void subscribeVulkan(ClientId client, const Request& request);

    ControlSocketServer server_;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    std::vector<ClientId> helloDone_;
    mutable std::mutex mutex_;
    std::string lastTime_;
    ViewUpdate lastView_;
};

}  // namespace sky::test
