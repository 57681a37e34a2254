// SPDX-License-Identifier: MIT
// Parsing and validating control requests (PROTOCOL.md). Every rejection names the field and the
// rule; nothing here has side effects, so "a malformed request changes nothing" holds by construction.
#include "skyservice/ipc/protocol.h"

#include "skyservice/render/view_limits.h"

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

namespace sky
{

namespace
{

using json = nlohmann::json;

constexpr size_t kMaxClientNameChars = 64;
constexpr double kMaxRate = 86400.0;        // sim seconds per real second: one day per second
constexpr uint32_t kMinImageSize = 8;
constexpr int64_t kMaxEvery = 1000000;      // frames between file writes

/// A number for messages: integers without ".0", others with enough digits to see what was sent.
std::string numberText(double v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.10g", v);
    return buffer;
}

/// nlohmann's message without its "[json.exception.x.n] " prefix, bounded to one short line.
std::string exceptionText(const std::exception& e)
{
    std::string s = e.what();
    size_t bracket = s.find("] ");
    if (s.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
        s.erase(0, bracket + 2);
    return s.size() > 160 ? s.substr(0, 157) + "..." : s;
}

/// The value as sent, shortened to stay one readable line.
std::string shownValue(const json& v)
{
    std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
    return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

}  // namespace

uint32_t layerBit(const std::string& name)
{
    const char* names[SKY_LAYER_COUNT] = {"display", "sky", "clouds", "depth"};
    for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
        if (name == names[k])
            return 1u << k;
    return 0;
}

namespace
{

struct Checker
{
    ProtocolError& error;

    bool fail(const char* code, const std::string& field, const std::string& message)
    {
        error.code = code;
        error.field = field;
        error.message = message;
        return false;
    }

    /// A finite number in [lo, hi].
    bool number(const json& v, const std::string& field, double lo, double hi, double& out)
    {
        if (!v.is_number())
            return fail("bad_type", field, field + " must be a number, got " + shownValue(v));
        out = v.get<double>();
        if (!std::isfinite(out))
            return fail("out_of_range", field, field + " must be finite");
        if (out < lo || out > hi)
            return fail("out_of_range", field,
                        field + " = " + numberText(out) + " is outside [" + numberText(lo) + ", " + numberText(hi) + "]");
        return true;
    }

    /// An integer in [lo, hi] (a JSON number without fraction or exponent).
    bool integer(const json& v, const std::string& field, int64_t lo, int64_t hi, int64_t& out)
    {
        if (v.is_number_unsigned())
        {
            uint64_t u = v.get<uint64_t>();
            out = u > uint64_t(INT64_MAX) ? INT64_MAX : int64_t(u);
        }
        else if (v.is_number_integer())
            out = v.get<int64_t>();
        else
            return fail("bad_type", field, field + " must be an integer, got " + shownValue(v));
        if (out < lo || out > hi)
            return fail("out_of_range", field,
                        field + " = " + std::to_string(out) + " is outside [" + std::to_string(lo) + ", " +
                            std::to_string(hi) + "]");
        return true;
    }

    bool string(const json& v, const std::string& field, std::string& out)
    {
        if (!v.is_string())
            return fail("bad_type", field, field + " must be a string, got " + shownValue(v));
        out = v.get<std::string>();
        // C APIs (open, the log) would silently cut the string at an embedded NUL.
        if (out.find('\0') != std::string::npos)
            return fail("out_of_range", field, field + " contains a NUL character");
        return true;
    }

    bool required(const json& object, const char* name)
    {
        if (object.contains(name))
            return true;
        return fail("missing_field", name, std::string("missing field \"") + name + "\"");
    }
};

bool parseView(const json& v, const ProtocolLimits& limits, ViewUpdate& out, Checker& check)
{
    if (!v.is_object())
        return check.fail("bad_type", "view", "view must be an object, got " + shownValue(v));
    struct Angle
    {
        const char* name;
        double lo, hi;
        std::optional<double>* target;
        bool open = false; ///< lo and hi themselves are outside
    };
    // Ranges of PROTOCOL.md: longitude and heading allow one wrap either way, so a client may send its
    // unwrapped value; altitude from the Dead Sea shore to the edge of the modelled atmosphere.
    const Angle fields[] = {
        {"lat", -90, 90, &out.lat},       {"lon", -540, 540, &out.lon},         {"alt", -500, 100000, &out.alt},
        {"heading", -360, 720, &out.heading}, {"pitch", -90, 90, &out.pitch}, {"roll", -180, 180, &out.roll},
        // The renderer's ranges (skyservice/render/view_limits.h): a view the parser takes is one it draws.
        {"fov", kMinFovYDeg, kMaxFovYDeg, &out.fov},
        // An asymmetric frustum; the service also checks left + right and up + down (view_frustum.h).
        {"left", -kMaxFrustumHalfAngleDeg, kMaxFrustumHalfAngleDeg, &out.left, true},
        {"right", -kMaxFrustumHalfAngleDeg, kMaxFrustumHalfAngleDeg, &out.right, true},
        {"up", -kMaxFrustumHalfAngleDeg, kMaxFrustumHalfAngleDeg, &out.up, true},
        {"down", -kMaxFrustumHalfAngleDeg, kMaxFrustumHalfAngleDeg, &out.down, true},
    };
    bool any = false;
    for (const Angle& f : fields)
    {
        if (!v.contains(f.name))
            continue;
        double value;
        const std::string field = std::string("view.") + f.name;
        if (!check.number(v[f.name], field, f.lo, f.hi, value))
            return false;
        if (f.open && (value == f.lo || value == f.hi))
            return check.fail("out_of_range", field,
                              field + " = " + numberText(value) + " is outside (" + numberText(f.lo) + ", " +
                                  numberText(f.hi) + ")");
        *f.target = value;
        any = true;
    }
    const struct
    {
        const char* name;
        uint32_t max;
        std::optional<uint32_t>* target;
    } sizes[] = {{"width", limits.maxWidth, &out.width}, {"height", limits.maxHeight, &out.height}};
    for (const auto& s : sizes)
    {
        if (!v.contains(s.name))
            continue;
        int64_t value;
        if (!check.integer(v[s.name], std::string("view.") + s.name, kMinImageSize, s.max, value))
            return false;
        *s.target = uint32_t(value);
        any = true;
    }
    if (!any)
        return check.fail("missing_field", "view",
                          "view has none of lat, lon, alt, heading, pitch, roll, fov, left, right, up, down, width, "
                          "height");
    const bool anyAngle = out.left || out.right || out.up || out.down;
    if (anyAngle && out.fov)
        return check.fail("out_of_range", "view.fov",
                          "view.fov given with left/right/up/down: a frustum is either symmetric (fov) or "
                          "asymmetric (the four half-angles)");
    if (anyAngle)
        for (const auto& [name, angle] : {std::pair{"left", &out.left}, std::pair{"right", &out.right},
                                          std::pair{"up", &out.up}, std::pair{"down", &out.down}})
            if (!*angle)
                return check.fail("missing_field", std::string("view.") + name,
                                  std::string("missing field \"view.") + name +
                                      "\": an asymmetric frustum's left, right, up and down come together");
    return true;
}

bool parseFields(const json& j, const ProtocolLimits& limits, Request& out, Checker& check)
{
    switch (out.type)
    {
    case RequestType::Hello:
    {
        int64_t protocol;
        if (!check.required(j, "protocol") || !check.integer(j["protocol"], "protocol", INT32_MIN, INT32_MAX, protocol))
            return false;
        out.protocol = int(protocol);
        if (protocol != kProtocolVersion)
            return check.fail("bad_version", "protocol",
                              "protocol " + std::to_string(protocol) + " is not supported; this service speaks " +
                                  std::to_string(kProtocolVersion));
        if (j.contains("client"))
        {
            if (!check.string(j["client"], "client", out.clientName))
                return false;
            if (out.clientName.size() > kMaxClientNameChars)
                return check.fail("out_of_range", "client",
                                  "client name is longer than " + std::to_string(kMaxClientNameChars) + " bytes");
        }
        return true;
    }
    case RequestType::SetView:
        return check.required(j, "view") && parseView(j["view"], limits, out.view, check);
    case RequestType::SetTime:
        if (!j.contains("time") && !j.contains("rate"))
            return check.fail("missing_field", "time", "set_time needs \"time\" and/or \"rate\"");
        if (j.contains("time"))
        {
            std::string time;
            if (!check.string(j["time"], "time", time))
                return false;
            out.timeIso = time;
        }
        if (j.contains("rate"))
        {
            double rate;
            if (!check.number(j["rate"], "rate", -kMaxRate, kMaxRate, rate))
                return false;
            out.rate = rate;
        }
        return true;
    case RequestType::LoadWeather:
        if (!check.required(j, "path") || !check.string(j["path"], "path", out.path))
            return false;
        if (out.path.empty() || out.path[0] != '/')
            return check.fail("out_of_range", "path", "path '" + out.path + "' must be absolute");
        return true;
    case RequestType::Subscribe:
    {
        std::string transport;
        if (!check.required(j, "transport") || !check.string(j["transport"], "transport", transport))
            return false;
        if (transport == "shm")
            out.transport = Transport::Shm;
        else if (transport == "vulkan")
            out.transport = Transport::Vulkan;
        else if (transport == "files")
            out.transport = Transport::Files;
        else
            return check.fail("out_of_range", "transport",
                              "transport '" + transport + "' is not one of shm, vulkan, files");
        if (out.transport != Transport::Files && j.contains("layers"))
        {
            if (!j["layers"].is_array() || j["layers"].empty() || j["layers"].size() > SKY_LAYER_COUNT)
                return check.fail("bad_type", "layers", "layers must be an array of 1 to 4 of display, sky, clouds, depth");
            out.layers = 0;
            for (const json& layer : j["layers"])
            {
                std::string name;
                if (!check.string(layer, "layers", name))
                    return false;
                const uint32_t bit = layerBit(name);
                if (bit == 0)
                    return check.fail("out_of_range", "layers",
                                      "layer '" + name + "' is not one of display, sky, clouds, depth");
                out.layers |= bit;
            }
        }
        if (out.transport != Transport::Files)
            return true;
        if (!check.required(j, "dir") || !check.string(j["dir"], "dir", out.path))
            return false;
        if (out.path.empty())
            return check.fail("out_of_range", "dir", "dir must not be empty");
        if (j.contains("every"))
        {
            int64_t every;
            if (!check.integer(j["every"], "every", 1, kMaxEvery, every))
                return false;
            out.every = uint32_t(every);
        }
        if (j.contains("format"))
        {
            if (!check.string(j["format"], "format", out.fileFormat))
                return false;
            if (out.fileFormat != "png" && out.fileFormat != "exr" && out.fileFormat != "both")
                return check.fail("out_of_range", "format",
                                  "format '" + out.fileFormat + "' is not one of png, exr, both");
        }
        return true;
    }
    case RequestType::WriteFiles:
        if (!check.required(j, "prefix") || !check.string(j["prefix"], "prefix", out.path))
            return false;
        if (out.path.empty())
            return check.fail("out_of_range", "prefix", "prefix must not be empty");
        return true;
    case RequestType::Render:
    case RequestType::Status:
        return true;
    }
    return true;
}

}  // namespace

const char* requestName(RequestType type)
{
    switch (type)
    {
    case RequestType::Hello: return "hello";
    case RequestType::SetView: return "set_view";
    case RequestType::SetTime: return "set_time";
    case RequestType::LoadWeather: return "load_weather";
    case RequestType::Subscribe: return "subscribe";
    case RequestType::Render: return "render";
    case RequestType::Status: return "status";
    case RequestType::WriteFiles: return "write_files";
    }
    return "unknown";
}

bool parseRequest(std::string_view line, const ProtocolLimits& limits, Request& out, ProtocolError& error)
{
    out = Request{};
    error = ProtocolError{};
    Checker check{error};
    // Parse errors are caught here: a hostile line must never throw through the service's poll loop.
    json j;
    try
    {
        j = json::parse(line.begin(), line.end());
    }
    catch (const json::out_of_range& e)
    {
        // JSON text has no NaN or infinity; a number too large for a double (1e999) is the only way to
        // send a non-finite one, and nlohmann reports it as out_of_range (id 406, "number overflow").
        return check.fail("out_of_range", "", std::string("a number is not finite: ") + exceptionText(e));
    }
    catch (const json::exception& e)
    {
        return check.fail("bad_json", "", std::string("the line is not valid JSON: ") + exceptionText(e));
    }
    if (!j.is_object())
        return check.fail("bad_json", "", std::string("the line is a JSON ") + j.type_name() + ", not an object");
    if (j.contains("id"))
    {
        const json& id = j["id"];
        if (!id.is_string() && !id.is_number())
            return check.fail("bad_type", "id", "id must be a number or a string, got " + shownValue(id));
        if (id.is_number_float() && !std::isfinite(id.get<double>()))
            return check.fail("out_of_range", "id", "id must be finite");
        out.id = id;
        error.id = id;
    }
    if (!j.contains("type"))
        return check.fail("unknown_type", "type", "missing \"type\"");
    if (!j["type"].is_string())
        return check.fail("unknown_type", "type", "type must be a string, got " + shownValue(j["type"]));
    const std::string type = j["type"].get<std::string>();
    static const RequestType kAll[] = {RequestType::Hello,     RequestType::SetView, RequestType::SetTime,
                                       RequestType::LoadWeather, RequestType::Subscribe, RequestType::Render,
                                       RequestType::Status,    RequestType::WriteFiles};
    bool known = false;
    for (RequestType t : kAll)
        if (type == requestName(t))
        {
            out.type = t;
            known = true;
        }
    if (!known)
        return check.fail("unknown_type", "type",
                          "unknown type " + shownValue(j["type"]) +
                              " (one of hello, set_view, set_time, load_weather, subscribe, render, status, write_files)");
    if (!parseFields(j, limits, out, check))
    {
        out.view = ViewUpdate{};  // nothing half-parsed escapes
        return false;
    }
    return true;
}

namespace
{

std::string dumpLine(const json& j)
{
    // Replies may echo strings a client sent; invalid UTF-8 is replaced rather than thrown on.
    return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

}  // namespace

std::string errorReply(const ProtocolError& error)
{
    json j = {{"type", "error"}};
    if (!error.id.is_null())
        j["id"] = error.id;
    j["code"] = error.code;
    std::string message = error.message;
    for (char& c : message)
        if (c == '\n' || c == '\r')
            c = ' ';
    j["message"] = message;
    if (!error.field.empty())
        j["field"] = error.field;
    return dumpLine(j);
}

std::string okReply(const Request& request, const nlohmann::json& extra)
{
    json j = {{"type", "ok"}, {"request", requestName(request.type)}};
    if (!request.id.is_null())
        j["id"] = request.id;
    if (extra.is_object())
        for (auto it = extra.begin(); it != extra.end(); ++it)
            j[it.key()] = it.value();
    return dumpLine(j);
}

std::string replyWithId(const Request& request, nlohmann::json body)
{
    if (!request.id.is_null())
        body["id"] = request.id;
    return dumpLine(body);
}

}  // namespace sky
