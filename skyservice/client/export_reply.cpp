// SPDX-License-Identifier: MIT
#include "skyservice/client/export_reply.h"

#include <cstdio>

namespace skyclientdetail
{
namespace
{

using json = nlohmann::json;

bool hexBytes(const json& j, const char* key, uint8_t out[16])
{
    if (!j.contains(key) || !j[key].is_string() || j[key].get<std::string>().size() != 32)
        return false;
    const std::string s = j[key].get<std::string>();
    for (size_t i = 0; i < 16; ++i)
    {
        unsigned value;
        if (std::sscanf(s.c_str() + 2 * i, "%2x", &value) != 1)
            return false;
        out[i] = uint8_t(value);
    }
    return true;
}

bool readImage(const json& j, SkyExportedImage& out)
{
    if (!j.is_object())
        return false;
    try
    {
        out.allocation_bytes = j.at("allocation_bytes").get<uint64_t>();
        out.memory_type_bits = j.at("memory_type_bits").get<uint32_t>();
        out.vk_format = j.at("vk_format").get<uint32_t>();
        out.width = j.at("width").get<uint32_t>();
        out.height = j.at("height").get<uint32_t>();
        out.linear_tiling = j.at("linear_tiling").get<bool>() ? 1u : 0u;
        out.row_pitch = j.at("row_pitch").get<uint64_t>();
    }
    catch (const json::exception&)
    {
        return false;
    }
    return true;
}

}  // namespace

// Reads the vulkan `subscribed` reply into f and hands it the fds in their SCM_RIGHTS order (PROTOCOL.md):
// frame images, shadow images (of the slots that have one), each layer's images (sky, clouds, depth; slots
// 0..n-1), the semaphore. An empty `why` on success; on failure the caller closes the fds.
std::string readExportReply(const json& reply, uint32_t asked, const std::vector<int>& fds, SkyExportedFrames& f)
{
    f.timeline_semaphore_fd = -1;
    for (uint32_t i = 0; i < SKY_MAX_EXPORTED_SLOTS; ++i)
    {
        f.frame[i].memory_fd = f.shadow[i].memory_fd = -1;
        for (uint32_t k = 0; k < SKY_LAYER_COUNT; ++k)
            f.layer[k][i].memory_fd = -1;
    }
    const json images = reply.value("images", json());
    const bool timeline = reply.value("timeline_semaphore", false);
    if (!images.is_array() || images.empty() || images.size() > SKY_MAX_EXPORTED_SLOTS)
        return "the subscribed reply needs 1 to " + std::to_string(SKY_MAX_EXPORTED_SLOTS) + " images";
    size_t expected = images.size() + (timeline ? 1 : 0);
    for (size_t i = 0; i < images.size(); ++i)
    {
        const json shadow = images[i].is_object() ? images[i].value("shadow", json()) : json();
        if (!readImage(images[i], f.frame[i]) || (!shadow.is_null() && !readImage(shadow, f.shadow[i])))
            return "image " + std::to_string(i) + " of the subscribed reply lacks a field";
        expected += shadow.is_null() ? 0 : 1;
        const json layers = images[i].value("layers", json::object());
        for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT; ++k)
        {
            const bool present = layers.is_object() && layers.contains(kLayerNames[k]);
            if (present != ((asked & (1u << k)) != 0) || (present && !readImage(layers[kLayerNames[k]], f.layer[k][i])))
                return "image " + std::to_string(i) + " of the subscribed reply: the " + kLayerNames[k] +
                       " layer is " + (present ? "not as asked for or lacks a field" : "missing");
            expected += present ? 1 : 0;
        }
    }
    if (!hexBytes(reply, "device_uuid", f.device_uuid) || !hexBytes(reply, "driver_uuid", f.driver_uuid))
        return "the subscribed reply lacks device_uuid/driver_uuid (32 hex digits)";
    if (fds.size() != expected)
        return "the subscribed reply came with " + std::to_string(fds.size()) + " fds, expected " +
               std::to_string(expected);
    size_t next = 0;
    f.slot_count = uint32_t(images.size());
    for (size_t i = 0; i < images.size(); ++i)
        f.frame[i].memory_fd = fds[next++];
    for (size_t i = 0; i < images.size(); ++i)
        if (!images[i].value("shadow", json()).is_null())
            f.shadow[i].memory_fd = fds[next++];
    f.layers = asked;
    for (uint32_t k = SKY_LAYER_SKY; k < SKY_LAYER_COUNT; ++k)
        for (size_t i = 0; (asked & (1u << k)) && i < images.size(); ++i)
            f.layer[k][i].memory_fd = fds[next++];
    if (timeline)
        f.timeline_semaphore_fd = fds[next++];
    return "";
}

}  // namespace skyclientdetail
