// SPDX-License-Identifier: MIT
// The control socket's transport (control_socket.h). Everything is non-blocking: a client that sends
// too much gets too_long, a client that reads too little is disconnected; poll() is the only wait.
#include "skyservice/ipc/control_socket.h"

#include "skyservice/ipc/fd_passing.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

namespace sky
{

namespace
{

/// Bytes read from one client per poll() before the others get their turn (a flood cannot starve them).
constexpr size_t kReadBudgetBytes = 256 * 1024;
constexpr int kListenBacklog = 64;

int64_t steadyMs()
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

struct PendingLine
{
    std::string data;      ///< the line and its newline
    size_t sent = 0;       ///< bytes of data already written
    std::vector<int> fds;  ///< our dups, closed once they went out with the first byte
};

std::string sysError(const char* what, const std::string& path)
{
    return std::string(what) + " " + path + ": " + std::strerror(errno);
}

void closeAll(std::vector<int>& fds)
{
    for (int fd : fds)
        ::close(fd);
    fds.clear();
}

bool fillAddress(const std::string& path, sockaddr_un& address, std::string& error)
{
    address = sockaddr_un{};
    address.sun_family = AF_UNIX;
    if (path.empty() || path.size() >= sizeof address.sun_path)
    {
        error = "socket path '" + path + "' is empty or longer than " + std::to_string(sizeof address.sun_path - 1) +
                " bytes";
        return false;
    }
    std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
    return true;
}

std::string tooLongLine(size_t maxLineBytes)
{
    nlohmann::json j = {{"type", "error"},
                        {"code", "too_long"},
                        {"message", "line exceeds " + std::to_string(maxLineBytes) +
                                        " bytes (newline included); skipped to the next newline"}};
    return j.dump();
}

}  // namespace

struct ControlSocketServer::Connection
{
    int fd = -1;
    uint32_t uid = 0;
    bool dead = false;           ///< to be closed and reported at the next reap
    bool discarding = false;     ///< inside an over-long line: drop bytes up to the next newline
    uint32_t tooLongInARow = 0;
    std::string partial;         ///< bytes of the current line not yet ended by a newline
    std::deque<PendingLine> out;
    size_t queuedBytes = 0;
    size_t queuedFds = 0;        ///< descriptors in `out`, ours until sent
    bool admitted = false;       ///< said hello (ControlSocketServer::admit)
    int64_t connectedMs = 0;     ///< steady clock
    int64_t lastInputMs = 0;     ///< steady clock, last bytes received
};

bool ControlSocketServer::listen(const std::string& path, uint32_t mode, const ControlSocketLimits& limits,
                                 std::string& error)
{
    close();
    sockaddr_un address;
    if (!fillAddress(path, address, error))
        return false;
    struct stat st{};
    if (::lstat(path.c_str(), &st) == 0)
    {
        if (!S_ISSOCK(st.st_mode))
        {
            error = path + " exists and is not a socket";
            return false;
        }
        // A socket file is left behind by a service that crashed. If something answers, it is live.
        int probe = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (probe < 0)
        {
            error = sysError("socket for", path);
            return false;
        }
        int rc = ::connect(probe, reinterpret_cast<const sockaddr*>(&address), sizeof address);
        int connectErrno = errno;
        ::close(probe);
        if (rc == 0 || connectErrno == EAGAIN)  // EAGAIN: a live listener with a full backlog
        {
            error = "another service is listening at " + path;
            return false;
        }
        if (connectErrno != ECONNREFUSED && connectErrno != ENOENT)
        {
            errno = connectErrno;
            error = sysError("probing the existing socket", path);
            return false;
        }
        if (connectErrno == ECONNREFUSED && ::unlink(path.c_str()) != 0 && errno != ENOENT)
        {
            error = sysError("removing the stale socket", path);
            return false;
        }
    }
    listenFd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (listenFd_ < 0)
    {
        error = sysError("socket for", path);
        return false;
    }
    if (::bind(listenFd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
    {
        error = sysError("bind", path);
        ::close(listenFd_);
        listenFd_ = -1;
        return false;
    }
    path_ = path;  // ours from here: close() unlinks it
    // Before listen(): nobody can connect yet, so nobody gets in under the umask's wider mode.
    if (::chmod(path.c_str(), mode_t(mode & 07777)) != 0 || ::listen(listenFd_, kListenBacklog) != 0)
    {
        error = sysError("chmod/listen", path);
        close();
        return false;
    }
    wakeFd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (wakeFd_ < 0)
    {
        error = sysError("eventfd for", path);
        close();
        return false;
    }
    limits_ = limits;
    if (limits_.maxLineBytes < 2)
        limits_.maxLineBytes = 2;
    return true;
}

void ControlSocketServer::close()
{
    for (auto& [id, c] : clients_)
    {
        ::close(c->fd);
        for (PendingLine& p : c->out)
            closeAll(p.fds);
        delete c;
    }
    clients_.clear();
    if (listenFd_ >= 0)
        ::close(listenFd_);
    if (wakeFd_ >= 0)
        ::close(wakeFd_);
    listenFd_ = wakeFd_ = -1;
    if (!path_.empty())
        ::unlink(path_.c_str());
    path_.clear();
}

void ControlSocketServer::wake()
{
    if (wakeFd_ < 0)
        return;
    uint64_t one = 1;
    ssize_t n = ::write(wakeFd_, &one, sizeof one);
    (void)n;  // EAGAIN: the counter is already non-zero, poll() will return anyway
}

uint32_t ControlSocketServer::peerUid(ClientId client) const
{
    auto it = clients_.find(client);
    return it == clients_.end() ? UINT32_MAX : it->second->uid;
}

void ControlSocketServer::admit(ClientId client)
{
    auto it = clients_.find(client);
    if (it != clients_.end())
        it->second->admitted = true;
}

int ControlSocketServer::expireUnadmitted()
{
    const int64_t now = steadyMs();
    int64_t next = -1;
    std::vector<std::pair<ClientId, std::string>> expired;
    for (auto& [id, c] : clients_)
    {
        if (c->admitted || c->dead)
            continue;
        const int64_t helloDeadline = c->connectedMs + limits_.helloTimeoutMs;
        const int64_t idleDeadline = c->lastInputMs + limits_.idleWithoutHelloMs;
        if (now >= helloDeadline)
            expired.emplace_back(id, "no hello within " + std::to_string(limits_.helloTimeoutMs) + " ms of connecting");
        else if (now >= idleDeadline)
            expired.emplace_back(id, "idle for " + std::to_string(limits_.idleWithoutHelloMs) + " ms without hello");
        else
        {
            const int64_t in = std::min(helloDeadline, idleDeadline) - now;
            next = next < 0 ? in : std::min(next, in);
        }
    }
    for (const auto& [id, why] : expired)
    {
        nlohmann::json j = {{"type", "error"}, {"code", "failed"}, {"message", "timeout: " + why + "; closing"}};
        send(id, j.dump());
        disconnect(id);
    }
    return int(next);
}

void ControlSocketServer::disconnect(ClientId client)
{
    auto it = clients_.find(client);
    if (it == clients_.end() || it->second->dead)
        return;
    it->second->dead = true;
    ::shutdown(it->second->fd, SHUT_RDWR);
}

// Writes what the socket takes now. False when the peer is gone (the connection is marked dead).
static bool flushConnection(int fd, std::deque<PendingLine>& out, size_t& queuedBytes, size_t& queuedFds)
{
    while (!out.empty())
    {
        PendingLine& p = out.front();
        const char* data = p.data.data() + p.sent;
        const size_t left = p.data.size() - p.sent;
        ssize_t n = sendWithFds(fd, data, left, p.fds.data(), p.fds.size());
        if (n < 0)
            return errno == EAGAIN || errno == EWOULDBLOCK;
        queuedFds -= p.fds.size();
        closeAll(p.fds);  // they went with the first byte sent
        p.sent += size_t(n);
        queuedBytes -= size_t(n);
        if (p.sent < p.data.size())
            return true;  // the socket buffer is full: POLLOUT will tell when to go on
        out.pop_front();
    }
    return true;
}

bool ControlSocketServer::send(ClientId client, std::string_view line, const std::vector<int>& fds)
{
    auto it = clients_.find(client);
    if (it == clients_.end() || it->second->dead)
        return false;
    Connection& c = *it->second;
    if (line.find('\n') != std::string_view::npos || fds.size() > kMaxFdsPerMessage)
        return false;  // would break the framing: a caller bug, never sent
    // It is not reading its replies: we will not buffer without bound, in bytes, in entries or in
    // descriptors (each queued Vulkan reply holds three; a client must not run the daemon out of them).
    if (c.queuedBytes + line.size() + 1 > limits_.maxQueuedReplyBytes || c.out.size() >= limits_.maxQueuedReplies ||
        c.queuedFds + fds.size() > limits_.maxQueuedFds)
    {
        disconnect(client);
        return false;
    }
    PendingLine p;
    p.data.reserve(line.size() + 1);
    p.data.append(line);
    p.data.push_back('\n');
    for (int fd : fds)
    {
        int copy = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);
        if (copy < 0)
        {
            closeAll(p.fds);
            return false;
        }
        p.fds.push_back(copy);
    }
    c.queuedBytes += p.data.size();
    c.queuedFds += p.fds.size();
    c.out.push_back(std::move(p));
    if (!flushConnection(c.fd, c.out, c.queuedBytes, c.queuedFds))
    {
        disconnect(client);
        return false;
    }
    return true;
}

void ControlSocketServer::poll(int timeoutMs, const Handlers& handlers)
{
    auto reap = [&] {
        for (auto it = clients_.begin(); it != clients_.end();)
        {
            if (!it->second->dead)
            {
                ++it;
                continue;
            }
            ClientId id = it->first;
            Connection* c = it->second;
            ::close(c->fd);
            for (PendingLine& p : c->out)
                closeAll(p.fds);
            delete c;
            it = clients_.erase(it);
            if (handlers.disconnected)
                handlers.disconnected(id);
        }
    };
    reap();
    if (listenFd_ < 0)
        return;
    // One client's bytes, split into lines (bounded); handlers may send to or disconnect anyone.
    auto readClient = [&](ClientId id) {
        char buffer[65536];
        size_t budget = kReadBudgetBytes;
        const size_t maxContent = limits_.maxLineBytes - 1;  // the limit counts the newline
        while (budget > 0)
        {
            auto it = clients_.find(id);
            if (it == clients_.end() || it->second->dead)
                return;
            std::vector<int> strayFds;  // clients have no business sending fds: closed at once
            ssize_t n = receiveWithFds(it->second->fd, buffer, std::min(sizeof buffer, budget), strayFds);
            closeAll(strayFds);
            if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK))
            {
                disconnect(id);
                return;
            }
            if (n < 0)
                return;
            budget -= size_t(n);
            it->second->lastInputMs = steadyMs();
            std::string_view data(buffer, size_t(n));
            while (!data.empty())
            {
                it = clients_.find(id);  // a handler may have disconnected it
                if (it == clients_.end() || it->second->dead)
                    return;
                Connection& c = *it->second;
                const size_t newline = data.find('\n');
                if (c.discarding)
                {
                    if (newline == std::string_view::npos)
                        break;
                    c.discarding = false;
                    data.remove_prefix(newline + 1);
                    continue;
                }
                const size_t take = newline == std::string_view::npos ? data.size() : newline;
                if (c.partial.size() + take > maxContent)
                {
                    // Answer as soon as the limit is passed, not when the newline finally comes.
                    c.partial.clear();
                    c.discarding = true;
                    ++c.tooLongInARow;
                    send(id, tooLongLine(limits_.maxLineBytes));
                    if (c.tooLongInARow >= limits_.maxConsecutiveTooLong)
                    {
                        disconnect(id);
                        return;
                    }
                    continue;  // the discarding branch skips to the newline
                }
                c.partial.append(data.substr(0, take));
                if (newline == std::string_view::npos)
                    break;
                data.remove_prefix(newline + 1);
                std::string line;
                line.swap(c.partial);
                c.tooLongInARow = 0;
                if (handlers.line)
                    handlers.line(id, line);
            }
        }
    };

    // After EMFILE the pending connection keeps the listening socket readable: polling it would spin.
    // It is left out of the poll set until the back-off ends (descriptors may be free again by then).
    // Slots held by silent connections come back: a client has helloTimeoutMs to say hello.
    const int nextDeadlineMs = expireUnadmitted();
    reap();
    if (nextDeadlineMs >= 0)
        timeoutMs = timeoutMs < 0 ? nextDeadlineMs : std::min(timeoutMs, nextDeadlineMs);
    const int64_t now = steadyMs();
    const bool accepting = now >= acceptPausedUntilMs_;
    if (!accepting)
        timeoutMs = int(std::min<int64_t>(timeoutMs < 0 ? INT32_MAX : timeoutMs, acceptPausedUntilMs_ - now));
    std::vector<pollfd> fds;
    std::vector<ClientId> ids;
    fds.push_back({accepting ? listenFd_ : -1, POLLIN, 0});
    fds.push_back({wakeFd_, POLLIN, 0});
    for (auto& [id, c] : clients_)
    {
        fds.push_back({c->fd, short(POLLIN | (c->out.empty() ? 0 : POLLOUT)), 0});
        ids.push_back(id);
    }
    int ready = ::poll(fds.data(), fds.size(), timeoutMs);
    if (ready <= 0)
        return;  // timeout or EINTR (a signal: the caller checks its flags)

    if (fds[1].revents & POLLIN)
    {
        uint64_t count;
        ssize_t n = ::read(wakeFd_, &count, sizeof count);
        (void)n;
    }
    for (size_t i = 0; i < ids.size(); ++i)
    {
        const short revents = fds[i + 2].revents;
        auto it = clients_.find(ids[i]);
        if (revents == 0 || it == clients_.end() || it->second->dead)
            continue;
        Connection& c = *it->second;
        if (revents & POLLOUT)
            if (!flushConnection(c.fd, c.out, c.queuedBytes, c.queuedFds))
            {
                disconnect(ids[i]);
                continue;
            }
        if (revents & (POLLIN | POLLHUP | POLLERR))
            readClient(ids[i]);
    }
    if (fds[0].revents & POLLIN)
        acceptClients(handlers);
    reap();
}

// New connections: over the limit they are told so and closed.
void ControlSocketServer::acceptClients(const Handlers& handlers)
{
    for (;;)
    {
        int fd = ::accept4(listenFd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd < 0)
        {
            if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM)
                acceptPausedUntilMs_ = steadyMs() + limits_.acceptBackoffMs;
            return;  // EAGAIN: all taken; out of resources: back off, then try again
        }
        ucred cred{};
        socklen_t len = sizeof cred;
        const uint32_t uid =
            ::getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) == 0 ? uint32_t(cred.uid) : UINT32_MAX;
        const auto sameUid = size_t(std::count_if(clients_.begin(), clients_.end(),
                                                  [uid](const auto& kv) { return kv.second->uid == uid; }));
        std::string busy;
        if (clients_.size() >= limits_.maxClients)
            busy = "busy: the service serves at most " + std::to_string(limits_.maxClients) + " clients";
        else if (limits_.maxClientsPerUid > 0 && sameUid >= limits_.maxClientsPerUid)
            busy = "busy: uid " + std::to_string(uid) + " already holds its share of " +
                   std::to_string(limits_.maxClientsPerUid) + " connections";
        if (!busy.empty())
        {
            std::string line = nlohmann::json({{"type", "error"}, {"code", "failed"}, {"message", busy}}).dump() + "\n";
            ssize_t n = ::send(fd, line.data(), line.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
            (void)n;
            ::close(fd);
            continue;
        }
        auto* c = new Connection;
        c->fd = fd;
        c->uid = uid;
        c->connectedMs = c->lastInputMs = steadyMs();
        ClientId id = nextId_++;
        clients_[id] = c;
        if (handlers.connected)
            handlers.connected(id);
    }
}

}  // namespace sky
