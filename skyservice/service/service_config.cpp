// SPDX-License-Identifier: MIT
#include "skyservice/service/service_config.h"

#include "skyservice/app/commands.h"
#include "skyservice/app/toml_file.h"
#include "skyservice/render/view_validation.h"
#include "skyservice/service/files_root.h"
#include "skyservice/sky/ephemeris.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <sys/stat.h>
#include <unistd.h>

namespace sky
{
namespace
{

/// One [service] key: reads a TOML value into the config, or says what is wrong with it.
using FieldReader = std::function<bool(const toml::node&, ServiceConfig&, std::string& why)>;

FieldReader realField(double ServiceConfig::*field, double lo, double hi)
{
    return [=](const toml::node& n, ServiceConfig& c, std::string& why) {
        std::optional<double> v = n.is_integer() ? std::optional<double>(double(*n.value<int64_t>())) : n.value<double>();
        if (!v || !n.is_number())
        {
            why = "must be a number";
            return false;
        }
        if (!(*v >= lo && *v <= hi))
        {
            why = "= " + std::to_string(*v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
            return false;
        }
        c.*field = *v;
        return true;
    };
}

bool readInteger(const toml::node& n, int64_t lo, int64_t hi, int64_t& out, std::string& why)
{
    if (!n.is_integer())
    {
        why = "must be an integer";
        return false;
    }
    int64_t v = *n.value<int64_t>();
    if (v < lo || v > hi)
    {
        why = "= " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        return false;
    }
    out = v;
    return true;
}

FieldReader u32Field(uint32_t ServiceConfig::*field, int64_t lo, int64_t hi)
{
    return [=](const toml::node& n, ServiceConfig& c, std::string& why) {
        int64_t v = 0;
        if (!readInteger(n, lo, hi, v, why))
            return false;
        c.*field = uint32_t(v);
        return true;
    };
}

/// A string, optionally one of `allowed`.
FieldReader stringField(std::string ServiceConfig::*field, std::vector<std::string> allowed = {})
{
    return [=](const toml::node& n, ServiceConfig& c, std::string& why) {
        if (!n.is_string())
        {
            why = "must be a string";
            return false;
        }
        std::string v = *n.value<std::string>();
        if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), v) == allowed.end())
        {
            why = "= \"" + v + "\" is not one of";
            for (const std::string& a : allowed)
                why += " " + a;
            return false;
        }
        c.*field = v;
        return true;
    };
}

std::map<std::string, FieldReader> serviceFields()
{
    std::map<std::string, FieldReader> f;
    f["socket_path"] = stringField(&ServiceConfig::socketPath);
    f["socket_mode"] = [](const toml::node& n, ServiceConfig& c, std::string& why) {
        // An integer (TOML octal literal 0o600) or a string of octal digits ("0600").
        int64_t v = -1;
        if (n.is_string())
        {
            std::string s = *n.value<std::string>();
            char* end = nullptr;
            long parsed = std::strtol(s.c_str(), &end, 8);
            v = (!s.empty() && end && *end == '\0') ? parsed : -1;
        }
        else if (n.is_integer())
            v = *n.value<int64_t>();
        if (v < 0 || v > 0777 || (v & 0600) != 0600)
        {
            why = "must be permission bits (0o600 .. 0o777, owner read and write included)";
            return false;
        }
        c.socketMode = uint32_t(v);
        return true;
    };
    f["shm_name"] = [](const toml::node& n, ServiceConfig& c, std::string& why) {
        std::optional<std::string> v = n.value<std::string>();
        if (!n.is_string() || !v || (!v->empty() && ((*v)[0] != '/' || v->find('/', 1) != std::string::npos ||
                                                      v->size() > 200)))
        {
            why = "must be \"\" or a name with one leading slash and no other, e.g. \"/skyservice-test\"";
            return false;
        }
        c.shmName = *v;
        return true;
    };
    f["weather_dir"] = stringField(&ServiceConfig::weatherDir);
    f["weather"] = stringField(&ServiceConfig::weather);
    f["render_rate_hz"] = realField(&ServiceConfig::renderRateHz, 0, 1000);
    f["max_width"] = u32Field(&ServiceConfig::maxWidth, 8, 8192);
    f["max_height"] = u32Field(&ServiceConfig::maxHeight, 8, 8192);
    f["shm_slots"] = u32Field(&ServiceConfig::shmSlots, 2, 4);  // SKY_MAX_EXPORTED_SLOTS is 4
    f["shadow_map_size"] = u32Field(&ServiceConfig::shadowMapSize, 0, 8192);
    f["shadow_map_extent_m"] = realField(&ServiceConfig::shadowMapExtentM, 100, 1600000);
    f["files_every"] = u32Field(&ServiceConfig::filesEvery, 0, 1000000);
    f["files_dir"] = stringField(&ServiceConfig::filesDir);
    f["files_root"] = stringField(&ServiceConfig::filesRoot);
    f["files_format"] = stringField(&ServiceConfig::filesFormat, {"png", "exr", "both"});
    f["log_level"] = [](const toml::node& n, ServiceConfig& c, std::string& why) {
        std::optional<std::string> v = n.value<std::string>();
        if (!n.is_string() || !v || !parseLogLevel(*v, c.logLevel))
        {
            why = "must be one of error, warn, info, debug";
            return false;
        }
        return true;
    };
    f["device"] = stringField(&ServiceConfig::device);
    f["validate"] = [](const toml::node& n, ServiceConfig& c, std::string& why) {
        if (!n.is_boolean())
        {
            why = "must be true or false";
            return false;
        }
        c.validate = *n.value<bool>();
        return true;
    };
    f["time"] = [](const toml::node& n, ServiceConfig& c, std::string& why) {
        std::optional<std::string> v = n.value<std::string>();
        if (!n.is_string() || !v)
        {
            why = "must be an ISO 8601 UTC string such as \"2026-06-21T12:00:00Z\"";
            return false;
        }
        return parseIso8601Utc(*v, c.timeUnixS, why);
    };
    f["rate"] = realField(&ServiceConfig::rate, -86400, 86400);
    f["quality"] = stringField(&ServiceConfig::quality, {"high", "medium", "test"});
    return f;
}

/// [service.view]: the same names and ranges as the socket API's set_view (PROTOCOL.md).
bool readView(const toml::table& t, ViewRequest& v, std::string& key, std::string& why)
{
    std::map<std::string, std::pair<double*, std::pair<double, double>>> reals = {
        {"lat", {&v.pose.latDeg, {-90, 90}}},        {"lon", {&v.pose.lonDeg, {-540, 540}}},
        {"alt", {&v.pose.altitudeM, {-500, 100000}}}, {"heading", {&v.pose.headingDeg, {-360, 720}}},
        {"pitch", {&v.pose.pitchDeg, {-90, 90}}},    {"roll", {&v.pose.rollDeg, {-180, 180}}},
        {"fov", {&v.fovYDeg, {kMinFovYDeg, kMaxFovYDeg}}}};
    for (auto&& [k, node] : t)
    {
        key = "service.view." + std::string(k.str());
        if (k.str() == "width" || k.str() == "height")
        {
            int64_t n = 0;
            if (!readInteger(node, 8, 8192, n, why))
                return false;
            (k.str() == "width" ? v.width : v.height) = uint32_t(n);
            continue;
        }
        auto it = reals.find(std::string(k.str()));
        if (it == reals.end())
        {
            why = "unknown key (config/service.toml lists every key)";
            return false;
        }
        std::optional<double> d = node.is_integer() ? std::optional<double>(double(*node.value<int64_t>()))
                                                    : node.value<double>();
        if (!node.is_number() || !d)
        {
            why = "must be a number";
            return false;
        }
        auto [lo, hi] = it->second.second;
        if (!(*d >= lo && *d <= hi))
        {
            why = "= " + std::to_string(*d) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
            return false;
        }
        *it->second.first = *d;
    }
    return true;
}

/// [cigi]: port numbers and 16-bit CIGI ids.
bool readCigi(const toml::table& t, CigiConfig& c, std::string& key, std::string& why)
{
    const std::map<std::string, std::pair<uint32_t*, std::pair<int64_t, int64_t>>> fields = {
        {"port", {&c.port, {1, 65534}}},   // 65534: the default host port is port + 1
        {"host_port", {&c.hostPort, {1, 65535}}},
        {"view_id", {&c.viewId, {0, 65535}}},
        {"ownship", {&c.ownship, {0, 65535}}}};
    for (auto&& [k, node] : t)
    {
        key = "cigi." + std::string(k.str());
        auto it = fields.find(std::string(k.str()));
        if (it == fields.end())
        {
            why = "unknown key (config/service.toml lists every key)";
            return false;
        }
        int64_t v = 0;
        if (!readInteger(node, it->second.second.first, it->second.second.second, v, why))
            return false;
        *it->second.first = uint32_t(v);
    }
    return true;
}

}  // namespace

std::string defaultSocketPath()
{
    const char* runtime = std::getenv("XDG_RUNTIME_DIR");
    if (runtime && *runtime)
        return std::string(runtime) + "/skyservice.sock";
    return "/tmp/skyservice-" + std::to_string(getuid()) + ".sock";
}

std::string defaultShmName(const std::string& socketPath)
{
    // FNV-1a of the socket path: stable across restarts (a restarted daemon finds, and replaces, the
    // ring a killed one left), distinct for two daemons of one user on different sockets.
    uint64_t hash = 14695981039346656037ull;
    for (const char c : socketPath)
        hash = (hash ^ uint8_t(c)) * 1099511628211ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)hash);
    return "/skyservice-" + std::to_string(getuid()) + "-" + hex;
}

ServiceConfig defaultServiceConfig()
{
    ServiceConfig c;
    c.view.pose.latDeg = 44.3;  // the render command's default view: the Alps' southern edge
    c.view.pose.lonDeg = 7.5;
    c.view.pose.altitudeM = 1500;
    std::string ignored;
    parseIso8601Utc("2026-06-21T12:00:00Z", c.timeUnixS, ignored);
    CommonRenderOptions o;
    o.quality = c.quality;
    qualityFromOptions(o, c.qualitySettings, ignored);
    return c;
}

bool loadServiceConfig(const std::string& path, ServiceConfig& out, std::string& error)
{
    // An empty file, a folder or a FIFO would read as "no settings": every field silently back to its
    // default on SIGHUP. They are refused like any other bad config.
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0)
    {
        error = path + ": " + std::strerror(errno);
        return false;
    }
    if (!S_ISREG(st.st_mode) || st.st_size == 0)
    {
        error = path + (S_ISREG(st.st_mode) ? ": empty file" : ": not a regular file") +
                " (refused, not taken as defaults)";
        return false;
    }
    toml::table table;
    if (!parseTomlFile(path, table, error))
        return false;
    if (table.empty())
    {
        error = path + ": no settings, only blanks and comments (refused, not taken as defaults)";
        return false;
    }
    ServiceConfig c = out;
    c.path = path;
    if (const toml::node* node = table.get("service"))
    {
        const toml::table* service = node->as_table();
        if (!service)
        {
            error = path + ": 'service' must be a section [service]";
            return false;
        }
        const std::map<std::string, FieldReader> fields = serviceFields();
        for (auto&& [key, value] : *service)
        {
            std::string name(key.str());
            std::string why;
            if (name == "view")
            {
                std::string field;
                if (!value.is_table())
                    why = "must be a section [service.view]", field = "service.view";
                else if (!readView(*value.as_table(), c.view, field, why))
                    ;  // `field` and `why` name the key at fault
                else if (!validateView(c.view, why))  // the view as a whole: the renderer takes it unchecked
                    field = "service.view";
                else
                    continue;
                error = path + ": '" + field + "' " + why;
                return false;
            }
            auto it = fields.find(name);
            if (it == fields.end())
                why = "unknown key (config/service.toml lists every key)";
            else if (it->second(value, c, why))
                continue;
            error = path + ": 'service." + name + "' " + why;
            return false;
        }
    }
    if (const toml::node* node = table.get("cigi"))
    {
        std::string field = "cigi", why;
        if (!node->is_table())
            why = "must be a section [cigi]";
        else if (readCigi(*node->as_table(), c.cigi, field, why))
            why.clear();
        if (!why.empty())
        {
            error = path + ": '" + field + "' " + why;
            return false;
        }
    }
    // The renderer's sections of the same file, on top of the preset (applyConfigFile skips [service] and
    // [cigi]).
    CommonRenderOptions o;
    o.quality = c.quality;
    o.config = path;
    if (!qualityFromOptions(o, c.qualitySettings, error))
        return false;
    out = c;
    return true;
}

bool checkServiceConfig(const ServiceConfig& c, const std::string& where, std::string& error)
{
    auto fail = [&](const std::string& field, const std::string& why) {
        error = where + ": '" + field + "' " + why;
        return false;
    };
    if (c.view.width > c.maxWidth)
        return fail("service.view.width", "= " + std::to_string(c.view.width) + " exceeds service.max_width");
    if (c.view.height > c.maxHeight)
        return fail("service.view.height", "= " + std::to_string(c.view.height) + " exceeds service.max_height");
    if (c.filesEvery > 0 && c.filesDir.empty())
        return fail("service.files_dir", "is required when service.files_every > 0");
    std::string why;
    if (c.filesEvery > 0 && !FilesRoot::checkName(c.filesDir, "is relative to service.files_root:", why))
        return fail("service.files_dir", why);
    if (!c.filesRoot.empty() && c.filesRoot[0] != '/')
        return fail("service.files_root", "must be an absolute path");
    if (c.socketPath.empty())
        return fail("service.socket_path", "is empty");
    if (c.shadowMapSize > 0 && c.shadowMapSize < 8)
        return fail("service.shadow_map_size", "must be 0 (none) or at least 8");
    if (c.cigi.port > 65534)
        return fail("cigi.port", "= " + std::to_string(c.cigi.port) + " is outside [1, 65534]");
    if (c.cigi.hostPort > 65535)
        return fail("cigi.host_port", "= " + std::to_string(c.cigi.hostPort) + " is outside [1, 65535]");
    if (c.cigi.viewId > 65535 || c.cigi.ownship > 65535)
        return fail(c.cigi.viewId > 65535 ? "cigi.view_id" : "cigi.ownship", "is outside [0, 65535]");
    return true;
}

}  // namespace sky
