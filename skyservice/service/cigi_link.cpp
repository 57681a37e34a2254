// SPDX-License-Identifier: MIT
#include "skyservice/service/cigi_link.h"

#include "skyservice/service/cigi_conditions.h"
#include "skyservice/service/log.h"

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace sky
{
namespace
{

// A reply datagram stays under this size (UDP's limit is 65507 bytes); requests beyond it wait a frame.
constexpr size_t kMaxReplyBytes = 60000;
constexpr int kPollMs = 200;                                // how soon stop() is noticed
constexpr int kFadePollMs = int(kCigiFadeStepS * 1000 / 2); // while a fade is under way: its steps' pace
constexpr int kMaxBatch = 256;                              // datagrams read between two polls

std::string addressText(const sockaddr_in& a)
{
    char text[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
    return text;
}

} // namespace

bool CigiLink::start(const CigiConfig& config, ServiceState* service, std::string& error)
{
    config_ = config;
    service_ = service;
    const std::string where = "cigi.port " + std::to_string(config.port);
    int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (fd < 0)
    {
        error = where + ": socket: " + std::strerror(errno);
        return false;
    }
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_ANY);
    addr.sin_port = htons(uint16_t(config.port));
    if (bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    {
        error = where + ": bind: " + std::strerror(errno);
        ::close(fd);
        return false;
    }
    fd_ = fd;
    if (!geoid_.load(cigi::defaultEgm96GridPath(), geoidError_))
        SKY_LOG_WARN("cigi: %s: altitudes above mean sea level are taken as ellipsoid heights", geoidError_.c_str());
    applier_ = std::make_unique<CigiApplier>(uint16_t(config.viewId), geoid_);
    stop_ = false;
    thread_ = std::thread([this] { run(); });
    SKY_LOG_INFO("cigi: IG on UDP port %u (replies to the host's port %u), view %u, ownship entity %u", config.port,
                 config.replyPort(), config.viewId, config.ownship);
    return true;
}

void CigiLink::stop()
{
    stop_ = true;
    if (thread_.joinable())
        thread_.join();
    if (fd_ >= 0)
        ::close(fd_);
    fd_ = -1;
}

void CigiLink::run()
{
    while (!stop_.load())
    {
        bool fading = false;
        {
            std::lock_guard<std::mutex> lock(applierMutex_);
            fading = applier_->fading();
        }
        pollfd p{fd_, POLLIN, 0};
        if (poll(&p, 1, fading ? kFadePollMs : kPollMs) > 0)
            receive();
        logHeldBack(); // also when the host has gone quiet: the last count of a flood is not lost
        if (fading) // the next step of the fade, also when the host has gone quiet
        {
            cigi::CigiState snapshot;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                snapshot = state_;
            }
            std::lock_guard<std::mutex> lock(applierMutex_);
            applier_->tick(snapshot, *service_);
        }
    }
}

void CigiLink::receive()
{
    std::vector<uint8_t> buffer(65536);
    // The datagrams waiting, then back to poll; at most kMaxBatch, so that a host that never stops
    // sending still lets stop() and the log's summaries through.
    for (int k = 0; k < kMaxBatch; ++k)
    {
        sockaddr_in from{};
        socklen_t fromLen = sizeof from;
        const ssize_t n = recvfrom(fd_, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &fromLen);
        if (n < 0)
        {
            if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
            {
                std::lock_guard<std::mutex> lock(mutex_);
                if (receiveLog_.admit(SteadyClock::now()))
                    SKY_LOG_WARN("cigi: recvfrom: %s", std::strerror(errno));
            }
            return;
        }
        cigi::DecodeResult datagram;
        cigi::CigiState snapshot;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            datagram = decoder_.decode(buffer.data(), size_t(n));
            for (const cigi::DecodeError& e : datagram.errors)
                if (e.firstOfKind)
                    SKY_LOG_WARN("cigi: %s from %s: %s (this kind is logged once; status cigi.errors counts it)",
                                 cigi::decodeErrorName(e.kind), addressText(from).c_str(), e.message.c_str());
            if (!datagram.accepted)
                continue;
            cigi::applyDatagram(state_, datagram, uint16_t(config_.ownship));
            // A destroyed region is forgotten here; the applier's fade keeps what it drew until it faded out.
            cigi::pruneDestroyedRegions(state_, state_.lastHostFrame);
            if (!haveHost_ || host_.sin_addr.s_addr != from.sin_addr.s_addr)
            {
                // Two hosts taking turns (a second host on the network, a spoofer) change it with every
                // datagram: the change is counted, and logged at most once per window of hostLog_.
                hostChanges_ += haveHost_ ? 1 : 0;
                if (hostLog_.admit(SteadyClock::now()))
                    SKY_LOG_INFO("cigi: host %s (%s-endian); replies go to its port %u", addressText(from).c_str(),
                                 datagram.order == cigi::ByteOrder::Big ? "big" : "little", config_.replyPort());
            }
            host_ = from;
            host_.sin_port = htons(uint16_t(config_.replyPort()));
            haveHost_ = true;
            encoder_.setByteOrder(datagram.order); // answer in the host's own order
            snapshot = state_;
        }
        std::lock_guard<std::mutex> lock(applierMutex_);
        applier_->apply(snapshot, datagram, *service_);
    }
}

void CigiLink::logHeldBack()
{
    const SteadyClock::time_point now = SteadyClock::now();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        double spanS = 0;
        if (const uint64_t n = hostLog_.heldBack(now, &spanS))
            SKY_LOG_INFO("cigi: host changed %llu more times in the last %.0f s (now %s; status cigi.host_changes "
                         "counts every change)",
                         (unsigned long long)n, spanS, addressText(host_).c_str());
        if (const uint64_t n = receiveLog_.heldBack(now, &spanS))
            SKY_LOG_WARN("cigi: recvfrom failed %llu more times in the last %.0f s", (unsigned long long)n, spanS);
        if (const uint64_t n = sendLog_.heldBack(now, &spanS))
            SKY_LOG_WARN("cigi: %llu more distinct sendto errors in the last %.0f s (status cigi.send_errors counts "
                         "every one)",
                         (unsigned long long)n, spanS);
    }
    std::lock_guard<std::mutex> lock(applierMutex_);
    applier_->logHeldBack(now);
}

void CigiLink::frameEnded(uint64_t /*frameId*/, bool ok)
{
    double extinctionPerM = 0;
    {
        std::lock_guard<std::mutex> lock(service_->mutex);
        extinctionPerM = service_->quality.extinctionPerM;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!haveHost_)
        return; // no host has spoken yet: nowhere to send
    cigi::StartOfFrame sof;
    sof.igMode = state_.igMode;
    sof.igStatus = ok ? 0 : 1; // IG-defined error code 1: the frame failed to render (the log says why)
    sof.databaseNumber = state_.databaseNumber;
    encoder_.beginFrame(state_.lastHostFrame, std::chrono::duration<double>(SteadyClock::now() - startedAt_).count(),
                        sof);
    size_t answered = 0;
    for (const cigi::EnvironmentalConditionsRequest& request : state_.pendingRequests)
    {
        if (encoder_.datagram().size() + cigi::kSizeWeatherConditionsResponse +
                3 * cigi::kSizeAerosolConcentrationResponse >
            kMaxReplyBytes)
            break;
        if (request.requestType & cigi::kRequestWeather)
        {
            encoder_.add(cigiWeatherConditions(state_, request, extinctionPerM));
            ++responsesSent_;
        }
        if (request.requestType & cigi::kRequestAerosol)
            for (const cigi::AerosolConcentrationResponse& a :
                 cigiAerosolConcentrations(state_, request, extinctionPerM))
            {
                encoder_.add(a);
                ++responsesSent_;
            }
        ++answered;
    }
    state_.pendingRequests.erase(state_.pendingRequests.begin(),
                                 state_.pendingRequests.begin() + std::ptrdiff_t(answered));
    const std::vector<uint8_t>& bytes = encoder_.datagram();
    if (sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&host_), sizeof host_) <
        0)
    {
        ++sendErrors_;
        std::string why = std::string("sendto ") + addressText(host_) + ":" + std::to_string(config_.replyPort()) +
                          ": " + std::strerror(errno);
        // Distinct errors alternate when hosts do (each names its address): a limiter bounds those too.
        if (why != lastSendError_ && sendLog_.admit(SteadyClock::now()))
            SKY_LOG_WARN("cigi: %s (logged once per distinct error)", why.c_str());
        lastSendError_ = why;
        return;
    }
    ++startOfFramesSent_;
}

nlohmann::json CigiLink::statusJson() const
{
    nlohmann::json applied;
    {
        std::lock_guard<std::mutex> lock(applierMutex_);
        if (applier_)
            applied = applier_->statusJson();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    const cigi::DecodeCounters& c = decoder_.counters();
    nlohmann::json errors = nlohmann::json::object();
    for (size_t k = 0; k < cigi::kDecodeErrorKindCount; ++k)
        errors[cigi::decodeErrorName(cigi::DecodeErrorKind(k))] = c.errors[k];
    const cigi::OwnshipPose& o = state_.ownship;
    return {{"port", config_.port},
            {"host_port", config_.replyPort()},
            {"view_id", config_.viewId},
            {"ownship_id", config_.ownship},
            {"geoid", geoidError_.empty() ? nlohmann::json(cigi::defaultEgm96GridPath()) : nlohmann::json()},
            {"host", haveHost_ ? nlohmann::json(addressText(host_)) : nlohmann::json()},
            {"host_changes", hostChanges_},
            {"host_byte_order", state_.hostByteOrder == cigi::ByteOrder::Big ? "big" : "little"},
            {"datagrams", c.datagrams},
            {"datagrams_dropped", c.datagramsDropped},
            {"packets_decoded", c.packetsDecoded},
            {"packets_ignored", c.packetsIgnored},
            {"errors", errors},
            {"errors_total", c.totalErrors()},
            {"last_host_frame", state_.lastHostFrame},
            {"ownship", {{"valid", o.valid}, {"lat", o.latDeg}, {"lon", o.lonDeg}, {"alt_msl", o.altitudeMslM}}},
            {"other_entity_packets", state_.otherEntityPackets},
            {"entity_weather_packets", state_.entityWeatherPackets},
            {"start_of_frames_sent", startOfFramesSent_},
            {"responses_sent", responsesSent_},
            {"requests_pending", state_.pendingRequests.size()},
            {"send_errors", sendErrors_},
            {"applied", applied}};
}

} // namespace sky
