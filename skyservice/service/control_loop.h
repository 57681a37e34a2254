// SPDX-License-Identifier: MIT
// The control socket's request dispatch (skyservice/ipc/PROTOCOL.md): one line in, one reply out, on
// the thread that calls ControlSocketServer::poll. Requests that change the next frame are applied
// under ServiceState's mutex, all fields or none; requests that need the renderer (write_files,
// subscribe vulkan) become RenderJobs whose replies come back through ServiceState::replies.
#pragma once

#include "skyservice/ipc/control_socket.h"
#include "skyservice/ipc/protocol.h"
#include "skyservice/ipc/shm_ring.h"
#include "skyservice/service/cigi_link.h"
#include "skyservice/service/files_root.h"
#include "skyservice/service/log_limiter.h"
#include "skyservice/service/service_state.h"
#include "skyservice/service/weather_loader.h"

#include <string>
#include <unordered_map>

namespace sky
{

struct ControlContext
{
    ControlSocketServer* server = nullptr;
    ServiceState* state = nullptr;
    WeatherLoader* loader = nullptr;
    const ShmRingWriter* ring = nullptr;
    const CigiLink* cigi = nullptr;  ///< null: no [cigi] port
    const FilesRoot* filesRoot = nullptr;
    ProtocolLimits limits;
    uint32_t maxQueuedJobsPerClient = 8;          ///< write_files + subscribe vulkan waiting for the render thread
    uint32_t maxFilesSubscriptionsPerClient = 4;  ///< distinct dirs; the same dir again replaces its subscription
    std::string deviceName, driver;
    SteadyClock::time_point startedAt = SteadyClock::now();
};

class ControlLoop
{
public:
    explicit ControlLoop(const ControlContext& context) : c_(context) {}

    /// The handlers to pass to ControlSocketServer::poll.
    ControlSocketServer::Handlers handlers();
    /// Sends the replies the render thread queued (call after each poll).
    void sendPendingReplies();
    /// The status reply's body (without id), also logged on SIGHUP.
    nlohmann::json statusJson();
    /// Logs how many connection and files-request lines the limiters held back (call after each poll).
    void logHeldBack();

private:
    struct Client
    {
        bool hello = false;
        std::string name;
    };

    void onLine(ClientId client, std::string_view line);
    void dispatch(ClientId client, const Request& request);
    void sendError(ClientId client, const nlohmann::json& id, const std::string& code, const std::string& message,
                   const std::string& field = "");
    void setView(ClientId client, const Request& request);
    void setTime(ClientId client, const Request& request);
    void subscribe(ClientId client, const Request& request);
    /// Queues a render-thread job unless the client already has maxQueuedJobsPerClient waiting (then busy).
    void queueJob(ClientId client, const Request& request, RenderJob job);

    ControlContext c_;
    std::unordered_map<ClientId, Client> clients_;
    // A local peer can connect, or ask for files, in a loop: the first lines of a window are logged
    // as they come (normal use stays line by line), a flood only as a count.
    LogLimiter connectionLog_{5.0, 10};
    LogLimiter filesRequestLog_{5.0, 10};
};

}  // namespace sky
