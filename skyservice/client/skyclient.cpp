// SPDX-License-Identifier: MIT
// libskyclient (skyclient.h): the control socket as blocking-with-timeout requests, and the frame
// ring mapped read-only. Everything waits in poll() with a deadline; nothing raises SIGPIPE.
#pragma GCC visibility push(default)
#include "skyservice/client/skyclient.h"

#include "skyservice/client/export_reply.h"
#pragma GCC visibility pop

#include "skyservice/ipc/fd_passing.h"
#include "skyservice/ipc/shm_ring.h"
#include "weather_ingest/civil_time.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <new>
#include <poll.h>
#include <string>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <vector>

using json = nlohmann::json;

struct SkyClient
{
    int fd = -1;
    std::string input;           ///< received bytes not yet consumed as lines
    std::vector<int> pendingFds; ///< fds received with the bytes in `input` (SCM_RIGHTS)
    std::string lastError;
    uint64_t nextId = 1;
    sky::ShmRingReader ring;
};

namespace
{

using Clock = std::chrono::steady_clock;

/// Replies longer than this are not ours to buffer (the service's lines are ≤ 64 KiB by protocol).
constexpr size_t kMaxReplyBytes = 1 << 20;
// Longest sleep on the ring's futex in sky_client_wait_frame before the socket is looked at again.
constexpr int kWaitSliceMs = 20;

/// Why the last sky_client_connect of this thread failed (there is no client to hold it).
thread_local std::string tConnectError;

SkyResult fail(SkyClient* c, SkyResult result, std::string message)
{
    c->lastError = std::move(message);
    return result;
}

void closeFds(std::vector<int>& fds)
{
    for (int fd : fds)
        ::close(fd);
    fds.clear();
}

void dropConnection(SkyClient* c)
{
    if (c->fd >= 0)
        ::close(c->fd);
    c->fd = -1;
    c->input.clear();
    closeFds(c->pendingFds);
}

int remainingMs(Clock::time_point deadline)
{
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    return left <= 0 ? 0 : int(left);
}

/// Reads what is there (waiting up to `timeoutMs`). SKY_OK also when nothing came in time.
SkyResult readSome(SkyClient* c, int timeoutMs)
{
    pollfd p{c->fd, POLLIN, 0};
    int ready = ::poll(&p, 1, timeoutMs);
    if (ready < 0 && errno != EINTR)
        return fail(c, SKY_ERR_CLOSED, std::string("poll: ") + std::strerror(errno));
    if (ready <= 0)
        return SKY_OK;
    char buffer[16384];
    ssize_t n = sky::receiveWithFds(c->fd, buffer, sizeof buffer, c->pendingFds);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
        return SKY_OK;
    if (n <= 0)
    {
        std::string why = n == 0 ? "the service closed the connection" : std::string("recv: ") + std::strerror(errno);
        dropConnection(c);
        return fail(c, SKY_ERR_CLOSED, why);
    }
    if (c->input.size() + size_t(n) > kMaxReplyBytes)
    {
        dropConnection(c);
        return fail(c, SKY_ERR_PROTOCOL, "the service sent a line longer than 1 MiB");
    }
    c->input.append(buffer, size_t(n));
    return SKY_OK;
}

SkyResult sendLine(SkyClient* c, const std::string& line, Clock::time_point deadline)
{
    size_t sent = 0;
    while (sent < line.size())
    {
        ssize_t n = ::send(c->fd, line.data() + sent, line.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0)
        {
            sent += size_t(n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
        {
            pollfd p{c->fd, POLLOUT, 0};
            if (::poll(&p, 1, remainingMs(deadline)) == 0)
                return fail(c, SKY_ERR_TIMEOUT, "the service did not take the request within the timeout");
            continue;
        }
        std::string why = std::string("send: ") + std::strerror(errno);
        dropConnection(c);
        return fail(c, SKY_ERR_CLOSED, "the service closed the connection (" + why + ")");
    }
    return SKY_OK;
}

/// Sends `request` (an id is added) and waits for its reply. The service's error replies become
/// SKY_ERR_REFUSED; lines of type "event" and replies to earlier, timed-out requests are skipped.
/// `fds` receives the fds that came with the reply (only subscribe vulkan has any).
SkyResult request(SkyClient* c, json request, json& reply, std::vector<int>* fds = nullptr)
{
    if (c->fd < 0)
        return fail(c, SKY_ERR_CLOSED, "not connected (the service closed the connection earlier)");
    closeFds(c->pendingFds);  // fds of lines nobody asked for
    const uint64_t id = c->nextId++;
    request["id"] = id;
    const auto deadline = Clock::now() + std::chrono::milliseconds(SKY_CLIENT_REPLY_TIMEOUT_MS);
    SkyResult r = sendLine(c, request.dump(-1, ' ', false, json::error_handler_t::replace) + "\n", deadline);
    if (r != SKY_OK)
        return r;
    for (;;)
    {
        size_t newline;
        while ((newline = c->input.find('\n')) != std::string::npos)
        {
            std::string line = c->input.substr(0, newline);
            c->input.erase(0, newline + 1);
            json j = json::parse(line, nullptr, false);
            if (j.is_discarded() || !j.is_object() || !j.contains("type") || !j["type"].is_string())
            {
                closeFds(c->pendingFds);
                return fail(c, SKY_ERR_PROTOCOL, "the service sent a line that is not a JSON object with a type");
            }
            const std::string type = j["type"].get<std::string>();
            const bool ours = !j.contains("id") || (j["id"].is_number_unsigned() && j["id"].get<uint64_t>() == id);
            if (type == "event" || !ours)
                continue;
            if (fds)
                fds->swap(c->pendingFds);
            closeFds(c->pendingFds);
            if (type == "error")
            {
                std::string message = j.value("message", std::string("(no message)"));
                if (j.contains("field") && j["field"].is_string())
                    message += " [field " + j["field"].get<std::string>() + "]";
                if (j.contains("code") && j["code"].is_string())
                    message = j["code"].get<std::string>() + ": " + message;
                if (fds)
                    closeFds(*fds);
                return fail(c, SKY_ERR_REFUSED, message);
            }
            reply = std::move(j);
            c->lastError.clear();
            return SKY_OK;
        }
        const int left = remainingMs(deadline);
        if (left == 0)
            return fail(c, SKY_ERR_TIMEOUT,
                        "no reply within " + std::to_string(SKY_CLIENT_REPLY_TIMEOUT_MS) + " ms to " +
                            request["type"].get<std::string>());
        r = readSome(c, left);
        if (r != SKY_OK)
            return r;
    }
}

SkyResult expectType(SkyClient* c, const json& reply, const char* type)
{
    if (reply.value("type", std::string()) == type)
        return SKY_OK;
    return fail(c, SKY_ERR_PROTOCOL, std::string("expected a \"") + type + "\" reply, got " + reply.dump());
}

/// Whole seconds, as PROTOCOL.md's ISO 8601 form (the service's parser takes no fraction).
std::string isoTime(double unixTimeS)
{
    return sky::formatIso8601Utc(std::llround(unixTimeS));
}

SkyResult mapRing(SkyClient* c, const json& reply)
{
    if (!reply.contains("shm_name") || !reply["shm_name"].is_string())
        return fail(c, SKY_ERR_PROTOCOL, "the subscribed reply has no shm_name");
    std::string error;
    if (!c->ring.open(reply["shm_name"].get<std::string>(), error))
        return fail(c, SKY_ERR_SHM, error);
    return SKY_OK;
}

json layerNames(uint32_t layers)
{
    json names = json::array();
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        if (layers & (1u << k))
            names.push_back(skyclientdetail::kLayerNames[k]);
    return names;
}

SkyResult subscribeVulkan(SkyClient* client, uint32_t layers, SkyExportedFrames& f)
{
    json reply;
    std::vector<int> fds;
    SkyResult r = request(client, {{"type", "subscribe"}, {"transport", "vulkan"}, {"layers", layerNames(layers)}},
                          reply, &fds);
    if (r == SKY_OK)
        r = expectType(client, reply, "subscribed");
    if (r != SKY_OK)
    {
        closeFds(fds);
        return r;
    }
    const std::string why = skyclientdetail::readExportReply(reply, layers, fds, f);
    if (!why.empty())
    {
        closeFds(fds);
        return fail(client, SKY_ERR_PROTOCOL, why);
    }
    if ((r = mapRing(client, reply)) != SKY_OK)
    {
        closeFds(fds);
        return r;
    }
    return SKY_OK;
}

}  // namespace

extern "C" {

SkyResult sky_client_connect(const char* socket_path, const char* client_name, SkyClient** out_client)
{
    tConnectError.clear();
    if (!out_client)
        return tConnectError = "out_client is null", SKY_ERR_ARGUMENT;
    *out_client = nullptr;
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (!socket_path || !*socket_path || std::strlen(socket_path) >= sizeof address.sun_path)
        return tConnectError = "socket path is null, empty or too long", SKY_ERR_ARGUMENT;
    std::memcpy(address.sun_path, socket_path, std::strlen(socket_path) + 1);

    auto* c = new (std::nothrow) SkyClient;
    if (!c)
        return tConnectError = "out of memory", SKY_ERR_ARGUMENT;
    c->fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    // A Unix socket connects at once or not at all; EAGAIN only means the backlog is full for now.
    const auto deadline = Clock::now() + std::chrono::milliseconds(SKY_CLIENT_REPLY_TIMEOUT_MS);
    int rc;
    while ((rc = ::connect(c->fd, reinterpret_cast<const sockaddr*>(&address), sizeof address)) != 0 &&
           (errno == EAGAIN || errno == EINTR) && remainingMs(deadline) > 0)
        ::usleep(2000);
    if (c->fd < 0 || rc != 0)
    {
        tConnectError = std::string("no service at ") + socket_path + ": " + std::strerror(errno);
        sky_client_close(c);
        return SKY_ERR_CONNECT;
    }
    json hello = {{"type", "hello"}, {"protocol", SKY_CLIENT_PROTOCOL_VERSION}};
    if (client_name)
        hello["client"] = std::string(client_name).substr(0, 64);
    json reply;
    SkyResult r = request(c, hello, reply);
    if (r == SKY_OK && (reply.value("type", std::string()) != "hello" ||
                        reply.value("protocol", 0) != SKY_CLIENT_PROTOCOL_VERSION))
    {
        c->lastError = "the service answered hello with " + reply.dump();
        r = SKY_ERR_PROTOCOL;
    }
    if (r != SKY_OK)
    {
        tConnectError = "handshake with " + std::string(socket_path) + " failed: " + c->lastError;
        sky_client_close(c);
        return r == SKY_ERR_PROTOCOL ? SKY_ERR_PROTOCOL : SKY_ERR_CONNECT;
    }
    *out_client = c;
    return SKY_OK;
}

void sky_client_close(SkyClient* client)
{
    if (!client)
        return;
    dropConnection(client);
    client->ring.close();
    delete client;
}

const char* sky_client_last_error(const SkyClient* client)
{
    return client ? client->lastError.c_str() : tConnectError.c_str();
}

SkyResult sky_client_set_view(SkyClient* client, const SkyView* view)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!view)
        return fail(client, SKY_ERR_ARGUMENT, "view is null");
    if (view->asymmetric > 1)
        return fail(client, SKY_ERR_ARGUMENT, "view.asymmetric must be 0 or 1 (zero the view before filling it)");
    const bool asymmetric = view->asymmetric == 1;
    const double values[] = {view->lat_deg,   view->lon_deg,  view->alt_m,    view->heading_deg, view->pitch_deg,
                             view->roll_deg,  asymmetric ? 0.0 : view->fov_deg, view->left_deg,  view->right_deg,
                             view->up_deg,    view->down_deg};
    for (double v : values)
        if (!std::isfinite(v))
            return fail(client, SKY_ERR_ARGUMENT, "view has a value that is not finite");
    json v = {{"lat", view->lat_deg},         {"lon", view->lon_deg},     {"alt", view->alt_m},
              {"heading", view->heading_deg}, {"pitch", view->pitch_deg}, {"roll", view->roll_deg},
              {"width", view->width},         {"height", view->height}};
    if (asymmetric)
    {
        v["left"] = view->left_deg;
        v["right"] = view->right_deg;
        v["up"] = view->up_deg;
        v["down"] = view->down_deg;
    }
    else
        v["fov"] = view->fov_deg;
    json reply;
    SkyResult r = request(client, {{"type", "set_view"}, {"view", v}}, reply);
    return r == SKY_OK ? expectType(client, reply, "ok") : r;
}

SkyResult sky_client_set_time(SkyClient* client, double unix_time_s, double rate)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!std::isfinite(unix_time_s) || !std::isfinite(rate))
        return fail(client, SKY_ERR_ARGUMENT, "time and rate must be finite");
    json reply;
    SkyResult r = request(client, {{"type", "set_time"}, {"time", isoTime(unix_time_s)}, {"rate", rate}}, reply);
    return r == SKY_OK ? expectType(client, reply, "ok") : r;
}

SkyResult sky_client_load_weather(SkyClient* client, const char* snapshot_path)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!snapshot_path)
        return fail(client, SKY_ERR_ARGUMENT, "snapshot_path is null");
    json reply;
    SkyResult r = request(client, {{"type", "load_weather"}, {"path", snapshot_path}}, reply);
    return r == SKY_OK ? expectType(client, reply, "ok") : r;
}

SkyResult sky_client_request_frame(SkyClient* client, uint64_t* out_frame_id)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    json reply;
    SkyResult r = request(client, {{"type", "render"}}, reply);
    if (r != SKY_OK || (r = expectType(client, reply, "ok")) != SKY_OK)
        return r;
    if (!reply.contains("frame_id") || !reply["frame_id"].is_number_unsigned())
        return fail(client, SKY_ERR_PROTOCOL, "the render reply has no frame_id");
    if (out_frame_id)
        *out_frame_id = reply["frame_id"].get<uint64_t>();
    return SKY_OK;
}

SkyResult sky_client_write_files(SkyClient* client, const char* prefix)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!prefix)
        return fail(client, SKY_ERR_ARGUMENT, "prefix is null");
    json reply;
    SkyResult r = request(client, {{"type", "write_files"}, {"prefix", prefix}}, reply);
    return r == SKY_OK ? expectType(client, reply, "ok") : r;
}

SkyResult sky_client_status(SkyClient* client, char* buffer, size_t buffer_bytes)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!buffer || buffer_bytes == 0)
        return fail(client, SKY_ERR_ARGUMENT, "buffer is null or empty");
    json reply;
    SkyResult r = request(client, {{"type", "status"}}, reply);
    if (r != SKY_OK || (r = expectType(client, reply, "status")) != SKY_OK)
        return r;
    reply.erase("id");
    const std::string text = reply.dump(-1, ' ', false, json::error_handler_t::replace);
    if (text.size() + 1 > buffer_bytes)
        return fail(client, SKY_ERR_ARGUMENT, "the status needs a buffer of " + std::to_string(text.size() + 1) + " bytes");
    std::memcpy(buffer, text.c_str(), text.size() + 1);
    return SKY_OK;
}

SkyResult sky_client_subscribe_files(SkyClient* client, const char* dir, uint32_t every, const char* format)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!dir || !format)
        return fail(client, SKY_ERR_ARGUMENT, "dir or format is null");
    json reply;
    SkyResult r = request(client, {{"type", "subscribe"}, {"transport", "files"}, {"dir", dir}, {"every", every},
                                   {"format", format}},
                          reply);
    return r == SKY_OK ? expectType(client, reply, "ok") : r;
}

SkyResult sky_client_subscribe_shm(SkyClient* client)
{
    return sky_client_subscribe_shm_layers(client, 1u << SKY_LAYER_DISPLAY);
}

SkyResult sky_client_subscribe_shm_layers(SkyClient* client, uint32_t layers)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (layers == 0 || layers >= (1u << SKY_LAYER_COUNT))
        return fail(client, SKY_ERR_ARGUMENT, "layers must be a non-empty set of (1u << SKY_LAYER_*)");
    json reply;
    SkyResult r = request(client, {{"type", "subscribe"}, {"transport", "shm"}, {"layers", layerNames(layers)}}, reply);
    if (r != SKY_OK || (r = expectType(client, reply, "subscribed")) != SKY_OK)
        return r;
    return mapRing(client, reply);
}

SkyResult sky_client_wait_frame(SkyClient* client, uint64_t after_frame_id, int timeout_ms)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!client->ring.valid())
        return fail(client, SKY_ERR_ARGUMENT, "not subscribed (sky_client_subscribe_shm or _vulkan first)");
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms < 0 ? 0 : timeout_ms);
    for (;;)
    {
        if (client->ring.latestFrameId() > after_frame_id)
            return client->lastError.clear(), SKY_OK;
        if (timeout_ms >= 0 && Clock::now() >= deadline)
            return fail(client, SKY_ERR_TIMEOUT, "no frame after " + std::to_string(after_frame_id) + " within " +
                                                     std::to_string(timeout_ms) + " ms");
        // The service wakes the ring's futex on every publish: sleep on it, in slices that look at the
        // socket between them, so that a service that goes away ends the wait within a slice. An older
        // service without the futex: a 1 ms poll on the socket.
        if (client->ring.canWaitForPublish())
        {
            const int sliceMs =
                timeout_ms < 0 ? kWaitSliceMs : std::min(kWaitSliceMs, std::max(1, remainingMs(deadline)));
            if (client->ring.waitForFrameAfter(after_frame_id, sliceMs) > after_frame_id)
                continue;
            if (client->fd >= 0)
                if (SkyResult r = readSome(client, 0); r != SKY_OK)
                    return r;
        }
        else if (client->fd >= 0)
        {
            SkyResult r = readSome(client, 1);
            if (r != SKY_OK)
                return r;
        }
        else
            ::usleep(1000);
    }
}

SkyResult sky_client_acquire_frame(SkyClient* client, SkyFrame* out_frame)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!out_frame)
        return fail(client, SKY_ERR_ARGUMENT, "out_frame is null");
    if (!client->ring.valid())
        return fail(client, SKY_ERR_ARGUMENT, "not subscribed (sky_client_subscribe_shm or _vulkan first)");
    // The newest slot is never the one being written (round robin), so a retry is needed only when the
    // writer lapped us between two loads; a few tries are plenty.
    for (int attempt = 0; attempt < 100; ++attempt)
    {
        sky::ShmFrameView v;
        if (!client->ring.acquire(v))
        {
            if (v.corrupt && client->ring.stillValid(v))  // a stable slot whose fields do not fit it
                return fail(client, SKY_ERR_SHM,
                            "frame " + std::to_string(v.slot->frame_id) +
                                ": its size, row or offset fields do not fit its slot (corrupt ring)");
            if (client->ring.latestFrameId() == 0)
                return fail(client, SKY_ERR_NO_FRAME, "no frame has been published yet");
            continue;
        }
        const SkyShmSlot& s = *v.slot;
        SkyFrame f{};
        f.frame_id = s.frame_id;
        f.sim_time_unix_s = s.sim_time_unix_s;
        f.exposure = s.exposure;
        f.view = s.view;
        f.format = s.format;
        f.width = s.view.width;
        f.height = s.view.height;
        f.row_bytes = s.row_bytes;
        f.pixels = v.pixels;
        f.shadow = s.shadow;
        f.shadow_size = v.shadow ? s.shadow.size_texels : 0;
        f.shadow_transmittance = v.shadow;
        for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        {
            f.layers[k].pixels = v.layers[k];
            f.layers[k].format = v.layers[k] ? s.layers[k].format : 0u;
            f.layers[k].row_bytes = v.layers[k] ? s.layers[k].row_bytes : 0u;
        }
        f.slot = v.slotIndex;
        f.sequence = v.sequence;
        if (!client->ring.stillValid(v))
            continue;  // the fields above were copied while the writer came round
        *out_frame = f;
        client->lastError.clear();
        return SKY_OK;
    }
    return fail(client, SKY_ERR_NO_FRAME, "the writer kept overwriting the newest slot; try again");
}

SkyResult sky_client_release_frame(SkyClient* client, const SkyFrame* frame)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!frame || !client->ring.valid() || frame->slot >= client->ring.slotCount())
        return fail(client, SKY_ERR_ARGUMENT, "not a frame of this client's ring");
    sky::ShmFrameView v;
    v.slot = client->ring.slot(frame->slot);  // the geometry checked when the ring was mapped
    v.slotIndex = frame->slot;
    v.sequence = frame->sequence;
    if (!client->ring.stillValid(v))
        return fail(client, SKY_ERR_TORN, "frame " + std::to_string(frame->frame_id) +
                                              " was overwritten while it was held: discard what was read");
    client->lastError.clear();
    return SKY_OK;
}

SkyResult sky_client_subscribe_vulkan(SkyClient* client, SkyExportedFrames* out_frames)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!out_frames)
        return fail(client, SKY_ERR_ARGUMENT, "out_frames is null");
    SkyExportedFrames f{};
    SkyResult r = subscribeVulkan(client, 1u << SKY_LAYER_DISPLAY, f);
    // A program built before SkyExportedFrames grew passes the smaller struct: only its fields are written.
    if (r == SKY_OK)
        std::memcpy(static_cast<void*>(out_frames), &f, offsetof(SkyExportedFrames, layers));
    return r;
}

SkyResult sky_client_subscribe_vulkan_layers(SkyClient* client, uint32_t layers, SkyExportedFrames* out_frames)
{
    if (!client)
        return SKY_ERR_ARGUMENT;
    if (!out_frames)
        return fail(client, SKY_ERR_ARGUMENT, "out_frames is null");
    if (layers >= (1u << SKY_LAYER_COUNT))
        return fail(client, SKY_ERR_ARGUMENT, "layers must be a set of (1u << SKY_LAYER_*)");
    SkyExportedFrames f{};
    SkyResult r = subscribeVulkan(client, layers | (1u << SKY_LAYER_DISPLAY), f);
    if (r == SKY_OK)
        *out_frames = f;
    return r;
}

}  // extern "C"
