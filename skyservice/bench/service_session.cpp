// SPDX-License-Identifier: MIT
#include "skyservice/bench/service_session.h"

#include "skyservice/sky/ephemeris.h"
#include "weather_ingest/snapshot_file.h"

#include <chrono>
#include <thread>
#include <vector>

namespace sky
{
namespace
{

using Clock = std::chrono::steady_clock;

// The status reply is one line of at most 64 KiB (PROTOCOL.md).
constexpr size_t kStatusBytes = 65536;

// The loaded weather's version, and the one the last published frame drew (-1 before the first frame).
void weatherVersions(const nlohmann::json& status, int64_t& loaded, int64_t& drawn, std::string& lastError)
{
    loaded = drawn = -1;
    lastError.clear();
    if (!status.contains("weather") || !status["weather"].is_object())
        return;
    const nlohmann::json& w = status["weather"];
    if (w.contains("version") && w["version"].is_number_integer())
        loaded = w["version"].get<int64_t>();
    if (w.contains("frame") && w["frame"].is_object() && w["frame"].contains("version") &&
        w["frame"]["version"].is_number_integer())
        drawn = w["frame"]["version"].get<int64_t>();
    if (w.contains("last_error") && w["last_error"].is_string())
        lastError = w["last_error"].get<std::string>();
}

} // namespace

bool ServiceConnection::open(const std::string& socketPath, const char* clientName, std::string& error)
{
    if (sky_client_connect(socketPath.c_str(), clientName, &client_) == SKY_OK)
        return true;
    error = "cannot connect to the service at " + socketPath + ": " + sky_client_last_error(client_);
    sky_client_close(client_);
    client_ = nullptr;
    return false;
}

bool readServiceStatus(SkyClient* client, nlohmann::json& status, std::string& error)
{
    std::vector<char> buffer(kStatusBytes);
    if (sky_client_status(client, buffer.data(), buffer.size()) != SKY_OK)
    {
        error = std::string("status: ") + sky_client_last_error(client);
        return false;
    }
    status = nlohmann::json::parse(buffer.data(), nullptr, false);
    if (!status.is_object())
    {
        error = "status: the reply is not a JSON object";
        return false;
    }
    return true;
}

bool prepareSceneWeather(const std::string& socketPath, const BenchScene& scene, const std::string& dir, bool onRequest,
                         double timeoutS, std::string& error)
{
    ServiceConnection c;
    if (!c.open(socketPath, "sky-service-bench-setup", error))
        return false;
    int64_t unixTimeS = 0;
    if (!parseIso8601Utc(scene.timeIso, unixTimeS, error))
    {
        error = scene.name + ": time " + scene.timeIso + ": " + error;
        return false;
    }
    if (sky_client_set_time(c.get(), double(unixTimeS), 0.0) != SKY_OK)
    {
        error = c.why("set_time " + scene.timeIso);
        return false;
    }
    if (scene.builtinWeather)
        return true;

    const std::string path = dir + "/" + scene.name + ".skywx";
    if (!writeSnapshotFile(path, {makeBenchWeather(scene, unixTimeS)}, error))
    {
        error = "writing the weather of scene " + scene.name + ": " + error;
        return false;
    }
    nlohmann::json status;
    if (!readServiceStatus(c.get(), status, error))
        return false;
    int64_t before = 0, drawn = 0;
    std::string lastError;
    weatherVersions(status, before, drawn, lastError);
    if (sky_client_load_weather(c.get(), path.c_str()) != SKY_OK)
    {
        error = c.why("load_weather " + path);
        return false;
    }
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeoutS);
    while (Clock::now() < deadline)
    {
        uint64_t frameId = 0;
        if (onRequest && sky_client_request_frame(c.get(), &frameId) != SKY_OK)
        {
            error = c.why("render (while the weather loads)");
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(onRequest ? 5 : 20));
        if (!readServiceStatus(c.get(), status, error))
            return false;
        int64_t loaded = 0;
        std::string newError;
        weatherVersions(status, loaded, drawn, newError);
        if (!newError.empty() && newError != lastError)
        {
            error = "the service refused the weather snapshot " + path + ": " + newError;
            return false;
        }
        if (loaded > before && drawn == loaded)
            return true;
    }
    error = "the weather snapshot " + path + " was not drawn within " + std::to_string(int(timeoutS)) +
            " s (status: " + status.dump() + ")";
    return false;
}

} // namespace sky
