// SPDX-License-Identifier: MIT
#include "tests/service/cigi_test_host.h"

#include "skyservice/cigi/cigi_fields.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>

namespace skytest
{

using namespace sky::cigi;

bool parseIgReply(const std::vector<uint8_t>& bytes, IgReply& out, std::string& error)
{
    if (bytes.size() < kSizeStartOfFrame || bytes[0] != kOpStartOfFrame || bytes[1] != kSizeStartOfFrame)
    {
        error = "an IG datagram of " + std::to_string(bytes.size()) + " bytes does not start with Start of Frame";
        return false;
    }
    constexpr uint8_t kMagicAt = PacketLayout<StartOfFrame>::magicOffset;
    if (bytes[kMagicAt] == 0x80 && bytes[kMagicAt + 1] == 0x00)
        out.order = ByteOrder::Big;
    else if (bytes[kMagicAt] == 0x00 && bytes[kMagicAt + 1] == 0x80)
        out.order = ByteOrder::Little;
    else
    {
        error = "Start of Frame's byte-swap magic is neither 0x8000 nor 0x0080";
        return false;
    }
    out.sof = decodeStartOfFrame(bytes.data(), out.order);
    out.weather.clear();
    out.aerosol.clear();
    for (size_t at = kSizeStartOfFrame; at < bytes.size();)
    {
        const uint8_t op = bytes[at], size = at + 1 < bytes.size() ? bytes[at + 1] : 0;
        if (size < 2 || at + size > bytes.size())
        {
            error = "a packet at byte " + std::to_string(at) + " has a bad size";
            return false;
        }
        if (op == kOpWeatherConditionsResponse && size == kSizeWeatherConditionsResponse)
            out.weather.push_back(decodeWeatherConditionsResponse(bytes.data() + at, out.order));
        else if (op == kOpAerosolConcentrationResponse && size == kSizeAerosolConcentrationResponse)
            out.aerosol.push_back(decodeAerosolConcentrationResponse(bytes.data() + at, out.order));
        else
        {
            error = "unexpected packet " + std::to_string(op) + " of " + std::to_string(size) + " bytes";
            return false;
        }
        at += size;
    }
    return true;
}

uint16_t freeUdpPort()
{
    int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof a;
    uint16_t port = 0;
    if (fd >= 0 && bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
        getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
        port = ntohs(a.sin_port);
    if (fd >= 0)
        close(fd);
    return port;
}

CigiTestHost::~CigiTestHost()
{
    if (fd_ >= 0)
        close(fd_);
}

bool CigiTestHost::open(std::string& error, uint32_t loopbackAddress)
{
    fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(loopbackAddress);
    socklen_t len = sizeof a;
    if (fd_ < 0 || bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
        getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len) != 0)
    {
        error = "test host: cannot bind a UDP socket on 127.0.0." + std::to_string(loopbackAddress & 0xff);
        return false;
    }
    port_ = ntohs(a.sin_port);
    return true;
}

bool CigiTestHost::send(const std::vector<uint8_t>& bytes, uint16_t igPort)
{
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to.sin_port = htons(igPort);
    return sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to) ==
           ssize_t(bytes.size());
}

std::optional<IgReply> CigiTestHost::receive(int timeoutMs, std::string* error)
{
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, timeoutMs) <= 0)
        return std::nullopt;
    std::vector<uint8_t> bytes(65536);
    const ssize_t n = recv(fd_, bytes.data(), bytes.size(), 0);
    if (n < 0)
        return std::nullopt;
    bytes.resize(size_t(n));
    IgReply reply;
    std::string why;
    if (!parseIgReply(bytes, reply, why))
    {
        if (error)
            *error = why;
        return std::nullopt;
    }
    return reply;
}

std::optional<IgReply> CigiTestHost::receiveForHostFrame(uint32_t hostFrame, int timeoutMs, size_t* skipped)
{
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeoutMs);
    for (;;)
    {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0)
            return std::nullopt;
        std::optional<IgReply> r = receive(int(left.count()));
        if (!r)
            return std::nullopt;
        if (r->sof.lastHostFrameNumber == hostFrame)
            return r;
        if (skipped)
            ++*skipped;
    }
}

} // namespace skytest
