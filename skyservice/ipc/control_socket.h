// SPDX-License-Identifier: MIT
// The control socket's transport (protocol: skyservice/ipc/PROTOCOL.md): a Unix domain stream server
// that splits each client's bytes into lines (bounded), queues replies (bounded), passes file
// descriptors (SCM_RIGHTS) and never blocks on a client. One thread calls poll(); send() may be
// called from the handler. What the lines mean is protocol.h's and the service's business.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace sky
{

using ClientId = uint64_t;

struct ControlSocketLimits
{
    size_t maxLineBytes = 65536;        ///< longer lines are answered "too_long" and skipped to the newline
    size_t maxQueuedReplyBytes = 1 << 20;  ///< a client with more unread replies is disconnected
    uint32_t maxQueuedReplies = 4096;   ///< … or more unsent replies (each one is a queue entry)
    uint32_t maxQueuedFds = 24;         ///< … or more unsent file descriptors (a Vulkan subscribe reply: <= 21)
    uint32_t acceptBackoffMs = 100;     ///< out of descriptors (EMFILE) on accept: no accept for this long
    uint32_t maxConsecutiveTooLong = 8; ///< then the client is disconnected
    uint32_t maxClients = 64;           ///< further connections are accepted, told "busy", and closed
    uint32_t maxClientsPerUid = 48;     ///< one peer uid's share of maxClients (0: no share)
    uint32_t helloTimeoutMs = 10000;    ///< a connection not admit()ted by then is told so and closed
    uint32_t idleWithoutHelloMs = 3000; ///< … as is one not admitted that sends nothing for this long
};

class ControlSocketServer
{
public:
    ControlSocketServer() = default;
    ControlSocketServer(const ControlSocketServer&) = delete;
    ControlSocketServer& operator=(const ControlSocketServer&) = delete;
    ~ControlSocketServer() { close(); }

    /// Binds and listens at `path` with permission `mode`. A stale socket file (nobody answers) is
    /// replaced; a live one (another service) is refused. False + error naming the path.
    bool listen(const std::string& path, uint32_t mode, const ControlSocketLimits& limits, std::string& error);
    /// Closes every connection and unlinks the path. Safe to call twice.
    void close();

    struct Handlers
    {
        std::function<void(ClientId)> connected;
        /// One complete line without its newline. Lines over the limit never reach here (the server
        /// answers them itself with a too_long error).
        std::function<void(ClientId, std::string_view line)> line;
        std::function<void(ClientId)> disconnected;
    };
    /// Waits up to timeoutMs for activity (accept, read, write), then dispatches it. Returns early
    /// when wake() is called from another thread.
    void poll(int timeoutMs, const Handlers& handlers);
    /// Thread-safe: makes a poll() in progress return.
    void wake();

    /// Queues `line` (a newline is appended) and, with it, `fds` (sent as SCM_RIGHTS with the line's
    /// first byte; the server dups them, the caller keeps its own). False when the client is gone or
    /// over its reply limit (it is then disconnected).
    bool send(ClientId client, std::string_view line, const std::vector<int>& fds = {});
    void disconnect(ClientId client);
    /// The client said hello: the hello and idle timeouts no longer apply to it.
    void admit(ClientId client);
    size_t clientCount() const { return clients_.size(); }
    /// Uid of the peer (SO_PEERCRED), for the log.
    uint32_t peerUid(ClientId client) const;

private:
    struct Connection;
    void acceptClients(const Handlers& handlers);
    /// Closes connections past their hello or idle deadline; returns ms until the next deadline (-1: none).
    int expireUnadmitted();
    std::string path_;
    int listenFd_ = -1;
    int64_t acceptPausedUntilMs_ = 0;  ///< steady-clock ms; accepting waits after EMFILE/ENFILE
    int wakeFd_ = -1;
    ControlSocketLimits limits_;
    ClientId nextId_ = 1;
    std::unordered_map<ClientId, Connection*> clients_;
};

}  // namespace sky
