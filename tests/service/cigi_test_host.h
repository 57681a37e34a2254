// SPDX-License-Identifier: MIT
// A CIGI test host for the daemon's end-to-end tests: a UDP socket on 127.0.0.1 that sends host datagrams
// (tests/cigi/cigi_host_datagram.h) to an IG port and reads the IG's replies (Start of Frame, then the
// responses), whatever byte order the IG answers in.
#pragma once

#include "skyservice/cigi/cigi_packets.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace skytest
{

/// One IG datagram, decoded.
struct IgReply
{
    sky::cigi::ByteOrder order = sky::cigi::ByteOrder::Big;
    sky::cigi::StartOfFrame sof;
    std::vector<sky::cigi::WeatherConditionsResponse> weather;
    std::vector<sky::cigi::AerosolConcentrationResponse> aerosol;
};

/// Decodes an IG datagram: Start of Frame first, its magic giving the order. False + error otherwise.
bool parseIgReply(const std::vector<uint8_t>& bytes, IgReply& out, std::string& error);

/// A UDP port that was free a moment ago (bound to port 0 and closed).
uint16_t freeUdpPort();

class CigiTestHost
{
  public:
    CigiTestHost() = default;
    CigiTestHost(const CigiTestHost&) = delete;
    CigiTestHost& operator=(const CigiTestHost&) = delete;
    ~CigiTestHost();

    /// Binds `loopbackAddress` (host order; default 127.0.0.1, any of 127/8 on Linux: a second host's
    /// own address) on a free port (port()).
    bool open(std::string& error, uint32_t loopbackAddress = 0x7f000001);
    uint16_t port() const { return port_; }
    bool send(const std::vector<uint8_t>& bytes, uint16_t igPort);
    /// The next IG datagram, decoded; nothing after timeoutMs. A datagram that does not parse fails the
    /// call with `error` set.
    std::optional<IgReply> receive(int timeoutMs, std::string* error = nullptr);
    /// Replies until one whose Start of Frame echoes host frame `hostFrame` (nothing after timeoutMs);
    /// `skipped` counts the others.
    std::optional<IgReply> receiveForHostFrame(uint32_t hostFrame, int timeoutMs, size_t* skipped = nullptr);

  private:
    int fd_ = -1;
    uint16_t port_ = 0;
};

} // namespace skytest
