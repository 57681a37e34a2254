// SPDX-License-Identifier: MIT
#include "client_demo/headless_run.h"

#include "client_demo/compositor.h"
#include "client_demo/overlay.h"
#include "client_demo/utc_time.h"

#include "skyservice/output/image_files.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace demo
{
namespace
{

nlohmann::json viewJson(const SkyShmView& v)
{
    return {{"lat", v.lat_deg},     {"lon", v.lon_deg},     {"alt", v.alt_m},  {"heading", v.heading_deg},
            {"pitch", v.pitch_deg}, {"roll", v.roll_deg},   {"fov", v.fov_deg}, {"width", v.width},
            {"height", v.height}};
}

const char* compositeName(CompositeMode mode) { return mode == CompositeMode::Layers ? "layers" : "display"; }

nlohmann::json sidecarOf(const LatestFrame& frame, const Aircraft& aircraft, const std::string& transport,
                         const CompositeStats& stats)
{
    nlohmann::json j;
    j["frame_id"] = frame.frameId;
    j["time"] = formatUtc(frame.simTimeUnixS);
    j["sim_time_unix_s"] = frame.simTimeUnixS;
    j["view"] = viewJson(frame.view);
    j["aircraft"] = {{"lat", aircraft.latDeg},         {"lon", aircraft.lonDeg},     {"alt", aircraft.altitudeM},
                     {"heading", aircraft.headingDeg}, {"pitch", aircraft.pitchDeg}, {"speed", aircraft.speedMps}};
    j["transport"] = transport;
    j["exposure"] = frame.exposure;
    j["composite"] = compositeName(stats.mode);
    if (stats.mode == CompositeMode::Layers)
        j["terrain"] = {{"pixels", stats.terrainPixels},
                        {"in_front_of_cloud_pixels", stats.terrainInFrontPixels},
                        {"behind_cloud_pixels", stats.terrainBehindCloudPixels}};
    if (frame.shadowSize > 0)
        j["shadow_map"] = {{"size", frame.shadowSize},
                           {"extent_m", frame.shadow.extent_m},
                           {"centre_lat", frame.shadow.centre_lat_deg},
                           {"centre_lon", frame.shadow.centre_lon_deg},
                           {"sun_azimuth_deg", frame.shadow.sun_azimuth_deg},
                           {"sun_elevation_deg", frame.shadow.sun_elevation_deg},
                           {"light_is_moon", frame.shadow.light_is_moon != 0}};
    else
        j["shadow_map"] = nullptr;
    return j;
}

}  // namespace

int runHeadless(const DemoOptions& o)
{
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    if (ec)
    {
        std::fprintf(stderr, "client_demo: cannot create %s: %s\n", o.outDir.c_str(), ec.message().c_str());
        return 1;
    }
    // A Vulkan instance only when the zero-copy transport may be taken; shm needs none.
    VulkanDevice vk;
    std::string error;
    VulkanDevice* vkOrNull = nullptr;
    if (o.transport != Transport::Shm)
    {
        if (createVulkanInstance(vk, {}, error))
            vkOrNull = &vk;
        else if (o.transport == Transport::Vulkan)
        {
            std::fprintf(stderr, "client_demo: %s\n", error.c_str());
            return 1;
        }
    }
    int code = 0;
    {
        std::unique_ptr<SkyClientSource> source = SkyClientSource::open(o.socketPath, o.transport, vkOrNull, {},
                                                                        o.composite == CompositeMode::Layers, error);
        if (!source)
        {
            std::fprintf(stderr, "client_demo: %s\n", error.c_str());
            destroyVulkanDevice(vk);
            return 1;
        }
        double unixTimeS = 0.0;
        if (!o.timeIso.empty() && parseUtc(o.timeIso, unixTimeS) && !source->setTime(unixTimeS, o.rate))
        {
            std::fprintf(stderr, "client_demo: %s\n", source->lastError().c_str());
            code = 1;
        }
        Aircraft aircraft = o.aircraft;
        const CompositeOptions composite = compositeOptionsOf(o);
        uint64_t lastId = 0;
        for (unsigned i = 0; code == 0 && i < o.frames; ++i)
        {
            uint64_t wantId = lastId + 1;
            if (!source->setView(viewOf(aircraft, o.angles, o.width, o.height)) || !source->requestFrame(wantId))
            {
                std::fprintf(stderr, "client_demo: %s\n", source->lastError().c_str());
                code = 1;
                break;
            }
            LatestFrame frame;
            FetchStatus status = FetchStatus::NoFrame;
            // Frames rendered before the request (a service rendering at its own rate) are skipped.
            do
                status = source->fetch(wantId > 0 ? wantId - 1 : 0, o.frameTimeoutMs, frame);
            while (status == FetchStatus::NewFrame && frame.frameId < wantId);
            if (status != FetchStatus::NewFrame)
            {
                std::fprintf(stderr, "client_demo: no frame %llu within %d ms%s%s\n", (unsigned long long)wantId,
                             o.frameTimeoutMs, status == FetchStatus::Failed ? ": " : "",
                             status == FetchStatus::Failed ? source->lastError().c_str() : "");
                code = 1;
                break;
            }
            lastId = frame.frameId;
            sky::ImageRgba8 image;
            CompositeStats stats;
            compositeFrame(frame, composite, image, &stats);
            OverlayInfo info;
            info.aircraft = aircraft;
            info.simTimeUnixS = frame.simTimeUnixS;
            info.frameId = frame.frameId;
            info.transport = source->transportName();
            drawOverlay(image, info);
            char name[32];
            std::snprintf(name, sizeof name, "frame-%04u", i);
            const std::string prefix = (std::filesystem::path(o.outDir) / name).string();
            if (!sky::writePng(prefix + ".png", image, error) ||
                !sky::writeJsonAtomic(prefix + ".json", sidecarOf(frame, aircraft, source->transportName(), stats),
                                      error))
            {
                std::fprintf(stderr, "client_demo: %s\n", error.c_str());
                code = 1;
                break;
            }
            std::printf("client_demo: %s.png (frame %llu, %s, %ux%u, shadow map %u, composite %s, terrain %llu px)\n",
                        prefix.c_str(), (unsigned long long)frame.frameId, source->transportName().c_str(), frame.width,
                        frame.height, frame.shadowSize, compositeName(stats.mode),
                        (unsigned long long)stats.terrainPixels);
            advanceAircraft(aircraft, scriptedInput(i), o.stepS);
        }
    }
    destroyVulkanDevice(vk);
    return code;
}

}  // namespace demo
