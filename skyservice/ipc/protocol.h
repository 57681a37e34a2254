// SPDX-License-Identifier: MIT
// The control protocol's messages (skyservice/ipc/PROTOCOL.md) as typed C++: parsing and validating a
// request line, and writing reply lines. Pure functions, no sockets, no service state.
#pragma once

#include "skyservice/ipc/shm_layout.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sky
{

constexpr int kProtocolVersion = 1;

enum class RequestType
{
    Hello,
    SetView,
    SetTime,
    LoadWeather,
    Subscribe,
    Render,
    Status,
    WriteFiles,
};

/// A view change: only the fields the client sent are set (skyservice/ipc/PROTOCOL.md names). An asymmetric frustum's
/// half-angles (left, right, up, down) come all four together and never with fov.
struct ViewUpdate
{
    std::optional<double> lat, lon, alt, heading, pitch, roll, fov;
    std::optional<double> left, right, up, down;
    std::optional<uint32_t> width, height;
};

enum class Transport
{
    Shm,
    Vulkan,
    Files,
};

struct Request
{
    RequestType type = RequestType::Status;
    nlohmann::json id;  ///< null when the client sent none; echoed in the reply
    // hello
    int protocol = 0;
    std::string clientName;
    // set_view
    ViewUpdate view;
    // set_time
    std::optional<std::string> timeIso;  ///< "time" as sent; the service parses it (parseIso8601Utc in
                                         ///< skyservice/sky/ephemeris.h) and answers out_of_range itself
    std::optional<double> rate;
    // load_weather (path), write_files (prefix), subscribe files (dir)
    std::string path;
    // subscribe
    Transport transport = Transport::Shm;
    uint32_t layers = 1u << SKY_LAYER_DISPLAY;  ///< shm, vulkan: the layers asked for, bit k = SKY_LAYER_k
    uint32_t every = 1;
    std::string fileFormat = "png";  ///< png | exr | both
};

/// The bit of a layer's name ("display", "sky", "clouds", "depth": 1 << SKY_LAYER_*), 0 for another name.
uint32_t layerBit(const std::string& name);

/// What was wrong with a request (PROTOCOL.md "Errors").
struct ProtocolError
{
    std::string code;     ///< bad_json, too_long, not_hello, bad_version, unknown_type, missing_field, bad_type, out_of_range, failed
    std::string message;  ///< one line
    std::string field;    ///< "view.lat" etc., empty when not one field
    nlohmann::json id;    ///< the request's id when it could be read
};

/// Limits that depend on the service's configuration.
struct ProtocolLimits
{
    uint32_t maxWidth = 1920;
    uint32_t maxHeight = 1080;
};

/// Parses and validates one line. False + `error` (with the request's id when it had one).
bool parseRequest(std::string_view line, const ProtocolLimits& limits, Request& out, ProtocolError& error);

/// Reply lines (no trailing newline).
std::string errorReply(const ProtocolError& error);
/// {"type":"ok","request":NAME,"id":ID} plus the members of `extra` (an object or null).
std::string okReply(const Request& request, const nlohmann::json& extra = nullptr);
/// `body` with "id" set from the request (for hello, status, subscribed replies).
std::string replyWithId(const Request& request, nlohmann::json body);
const char* requestName(RequestType type);

}  // namespace sky
