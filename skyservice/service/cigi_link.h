// SPDX-License-Identifier: MIT
// The daemon's CIGI 3.3 IG interface ([cigi] port): a UDP socket and its receiver thread. Each host
// datagram is decoded (skyservice/cigi/) into the IG-side CigiState under the link's mutex and applied to
// the next frame (cigi_apply.h). After every frame the render loop calls frameEnded: the link sends Start
// of Frame, followed by the answers to the Environmental Conditions Requests that came since, to the
// address the last host datagram came from, at the host port. Nothing here waits on the render thread or
// the network: a bad datagram is counted (status "cigi"), each kind of error is logged once, a line a host
// can repeat at will (a change of host, a send error) at most once per few seconds (log_limiter.h), and a
// host that stops sending leaves the last state in place.
#pragma once

#include "skyservice/cigi/cigi_decoder.h"
#include "skyservice/cigi/cigi_encoder.h"
#include "skyservice/cigi/cigi_state.h"
#include "skyservice/cigi/geoid_undulation.h"
#include "skyservice/service/cigi_apply.h"
#include "skyservice/service/log_limiter.h"
#include "skyservice/service/service_config.h"
#include "skyservice/service/service_state.h"

#include <nlohmann/json.hpp>

#include <netinet/in.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace sky
{

class CigiLink
{
  public:
    CigiLink() = default;
    CigiLink(const CigiLink&) = delete;
    CigiLink& operator=(const CigiLink&) = delete;
    ~CigiLink() { stop(); }

    /// Binds UDP `config.port` on every interface and starts the receiver. False + error (naming the port)
    /// when the socket cannot be had. `service` must outlive the link.
    bool start(const CigiConfig& config, ServiceState* service, std::string& error);
    void stop();
    bool running() const { return fd_ >= 0; }

    /// Render thread, after each frame (ok or failed: Start of Frame says which in IG Status).
    void frameEnded(uint64_t frameId, bool ok);

    /// The status reply's "cigi" object: the config, the decoder's counters, what was applied and sent.
    nlohmann::json statusJson() const;

  private:
    void run();
    void receive();
    /// The summaries of the lines the limiters held back (each at most once per window).
    void logHeldBack();

    CigiConfig config_;
    ServiceState* service_ = nullptr;
    int fd_ = -1;
    std::thread thread_;
    std::atomic<bool> stop_{false};
    SteadyClock::time_point startedAt_ = SteadyClock::now();
    cigi::GeoidGrid geoid_;
    std::string geoidError_;
    std::unique_ptr<CigiApplier> applier_; ///< receiver thread; status reads it under applierMutex_
    mutable std::mutex applierMutex_;

    mutable std::mutex mutex_; ///< guards everything below
    cigi::Decoder decoder_;
    cigi::CigiState state_;
    cigi::IgEncoder encoder_;
    sockaddr_in host_{}; ///< where the last accepted host datagram came from
    bool haveHost_ = false;
    uint64_t startOfFramesSent_ = 0, responsesSent_ = 0, sendErrors_ = 0;
    uint64_t hostChanges_ = 0; ///< datagrams from another address than the one before
    std::string lastSendError_;
    LogLimiter hostLog_, receiveLog_, sendLog_;
};

} // namespace sky
