// SPDX-License-Identifier: MIT
// sky-service-bench's control-side steps through libskyclient: a connection that closes itself, the
// service's status as JSON, and a scene's time and weather set up before any frame is timed.
#pragma once

#include "skyservice/bench/bench_scenes.h"
#include "skyservice/client/skyclient.h"

#include <nlohmann/json.hpp>
#include <string>

namespace sky
{

/// A libskyclient connection, closed by the destructor.
class ServiceConnection
{
  public:
    ServiceConnection() = default;
    ServiceConnection(const ServiceConnection&) = delete;
    ServiceConnection& operator=(const ServiceConnection&) = delete;
    ~ServiceConnection() { sky_client_close(client_); }

    /// sky_client_connect; on failure `error` names the socket and the reason.
    bool open(const std::string& socketPath, const char* clientName, std::string& error);
    SkyClient* get() const { return client_; }
    /// "what: <libskyclient's last error>", for failure messages.
    std::string why(const std::string& what) const { return what + ": " + sky_client_last_error(client_); }

  private:
    SkyClient* client_ = nullptr;
};

/**
 * The service's status reply.
 *
 * @param[in] client a connected client.
 * @param[out] status the parsed JSON object (PROTOCOL.md `status`).
 * @param[out] error on failure, why.
 **********************************************************************/
bool readServiceStatus(SkyClient* client, nlohmann::json& status, std::string& error);

/**
 * Gives the service the scene's time (frozen) and weather. Built-in scenes draw the daemon's built-in
 * weather, which at a given second is the same as sky-bench's (makeBenchWeather); the synthetic ones are
 * written to DIR/<scene>.skywx, loaded with load_weather, and waited for until a published frame drew
 * them (status weather.frame.version), asking for frames meanwhile when the service renders on request.
 *
 * @param[in] socketPath the service's socket.
 * @param[in] scene the scene.
 * @param[in] dir a writable folder for the snapshot file.
 * @param[in] onRequest the service renders only on request (render_rate_hz 0).
 * @param[in] timeoutS how long the weather may take to be drawn (s).
 * @param[out] error on failure, which step failed and why.
 **********************************************************************/
bool prepareSceneWeather(const std::string& socketPath, const BenchScene& scene, const std::string& dir, bool onRequest,
                         double timeoutS, std::string& error);

} // namespace sky
