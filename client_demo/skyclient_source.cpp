// SPDX-License-Identifier: MIT
#include "client_demo/skyclient_source.h"

#include "skyservice/client/skyclient.h"

#ifdef DEMO_HAVE_VULKAN_IMPORT
#include "client_demo/vulkan_import.h"
#endif

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

namespace demo
{

#ifndef DEMO_HAVE_VULKAN_IMPORT
// Without skyclient_vulkan the zero-copy transport is never taken; this keeps unique_ptr's deleter whole.
class VulkanFrameImport
{
};
#endif

namespace
{

SkyClient* connectClient(const std::string& socketPath, std::string& error)
{
    SkyClient* client = nullptr;
    if (sky_client_connect(socketPath.c_str(), "client_demo", &client) != SKY_OK)
    {
        error = "cannot connect to the sky service at " + socketPath + ": " +
                (client ? sky_client_last_error(client) : "no service there");
        sky_client_close(client);
        return nullptr;
    }
    return client;
}

// Copies one layer of `channels` values per pixel into out (half floats widened to float, float copied);
// clears out when the frame does not carry the layer in the expected format.
void copyLayer(const SkyFrameLayer& layer, uint32_t format, uint32_t width, uint32_t height, uint32_t channels,
               std::vector<float>& out)
{
    const bool half = format != SKY_FORMAT_RG32F_METRES;
    const size_t valueBytes = half ? 2 : 4;
    if (layer.format != format || layer.pixels == nullptr || layer.row_bytes < width * channels * valueBytes)
    {
        out.clear();
        return;
    }
    out.resize(size_t(width) * height * channels);
    for (uint32_t y = 0; y < height; ++y)
    {
        const uint8_t* row = layer.pixels + size_t(y) * layer.row_bytes;
        float* dst = out.data() + size_t(y) * width * channels;
        if (!half)
        {
            std::memcpy(dst, row, size_t(width) * channels * 4);
            continue;
        }
        for (size_t k = 0; k < size_t(width) * channels; ++k)
        {
            uint16_t bits = 0;
            std::memcpy(&bits, row + 2 * k, 2);
            dst[k] = glm::unpackHalf1x16(bits);
        }
    }
}

}  // namespace

std::unique_ptr<SkyClientSource> SkyClientSource::open(const std::string& socketPath, Transport transport,
                                                       VulkanDevice* vk, const DeviceRequest& request,
                                                       bool wantLayers, std::string& error)
{
    std::unique_ptr<SkyClientSource> source(new SkyClientSource());
    source->client_ = connectClient(socketPath, error);
    if (!source->client_)
        return nullptr;

    const uint32_t compositing = (1u << SKY_LAYER_SKY) | (1u << SKY_LAYER_CLOUDS) | (1u << SKY_LAYER_DEPTH);
#ifdef DEMO_HAVE_VULKAN_IMPORT
    if (vk != nullptr && (transport == Transport::Vulkan || transport == Transport::Auto))
    {
        SkyExportedFrames exported{};
        std::string why;
        if (sky_client_subscribe_vulkan_layers(source->client_, wantLayers ? compositing : 0u, &exported) != SKY_OK)
            why = std::string("the service exports no frames: ") + sky_client_last_error(source->client_);
        else
        {
            DeviceRequest zeroCopy = request;
            zeroCopy.preferred = VulkanFrameImport::findServiceDevice(vk->instance, exported);
            for (const char* e : VulkanFrameImport::requiredExtensions())
                zeroCopy.extensions.push_back(e);
            if (zeroCopy.preferred == VK_NULL_HANDLE)
                why = "the service renders on a GPU this process cannot see (different device or driver UUID)";
            else if (request.surface != VK_NULL_HANDLE && !canPresent(zeroCopy.preferred, request.surface))
                why = "the service's GPU cannot present to this window";
            else if (!createVulkanDevice(*vk, zeroCopy, why))
                why = "device for zero-copy import: " + why;
            else
            {
                source->import_ = VulkanFrameImport::create(*vk, exported, why);
                if (source->import_)
                    return source;
                destroyVulkanDeviceOnly(*vk);  // the shm fallback below makes its own
            }
            closeExportedFds(exported);
        }
        if (transport == Transport::Vulkan)
        {
            error = "zero-copy transport unavailable: " + why;
            return nullptr;
        }
        std::fprintf(stderr, "client_demo: zero-copy transport unavailable (%s); using shared memory\n", why.c_str());
        // A fresh connection: the service's zero-copy subscription ends with the old one.
        sky_client_close(source->client_);
        source->client_ = connectClient(socketPath, error);
        if (!source->client_)
            return nullptr;
    }
#else
    if (transport == Transport::Vulkan)
    {
        error = "this client_demo was built without skyclient_vulkan: no zero-copy transport";
        return nullptr;
    }
#endif
    const uint32_t layers = (1u << SKY_LAYER_DISPLAY) | (wantLayers ? compositing : 0u);
    if (sky_client_subscribe_shm_layers(source->client_, layers) != SKY_OK)
    {
        error = std::string("subscribing to the shared-memory ring: ") + sky_client_last_error(source->client_);
        return nullptr;
    }
    if (vk != nullptr && vk->device == VK_NULL_HANDLE && !createVulkanDevice(*vk, request, error))
        return nullptr;
    return source;
}

SkyClientSource::~SkyClientSource()
{
    import_.reset();
    sky_client_close(client_);
}

bool SkyClientSource::setView(const SkyShmView& view)
{
    if (sky_client_set_view(client_, &view) == SKY_OK)
        return true;
    error_ = std::string("set_view: ") + sky_client_last_error(client_);
    return false;
}

bool SkyClientSource::setTime(double unixTimeS, double rate)
{
    if (sky_client_set_time(client_, unixTimeS, rate) == SKY_OK)
        return true;
    error_ = std::string("set_time: ") + sky_client_last_error(client_);
    return false;
}

bool SkyClientSource::requestFrame(uint64_t& frameId)
{
    if (sky_client_request_frame(client_, &frameId) == SKY_OK)
        return true;
    error_ = std::string("render: ") + sky_client_last_error(client_);
    return false;
}

std::string SkyClientSource::transportName() const { return import_ ? "vulkan" : "shm"; }

bool SkyClientSource::copyShm(const SkyFrame& frame, LatestFrame& out)
{
    if (frame.format != SKY_FORMAT_RGBA8_SRGB || frame.pixels == nullptr || frame.row_bytes < frame.width * 4)
    {
        error_ = "the service's frames are not RGBA8 (format " + std::to_string(frame.format) + ")";
        return false;
    }
    out.width = frame.width;
    out.height = frame.height;
    out.rgba.resize(size_t(frame.width) * frame.height * 4);
    for (uint32_t y = 0; y < frame.height; ++y)
        std::memcpy(out.rgba.data() + size_t(y) * frame.width * 4, frame.pixels + size_t(y) * frame.row_bytes,
                    size_t(frame.width) * 4);
    out.shadowSize = frame.shadow_transmittance ? frame.shadow_size : 0;
    out.shadowTransmittance.assign(frame.shadow_transmittance,
                                   frame.shadow_transmittance + size_t(out.shadowSize) * out.shadowSize);
    copyLayer(frame.layers[SKY_LAYER_SKY], SKY_FORMAT_RGBA16F_LINEAR, frame.width, frame.height, 4, out.skyRgba);
    copyLayer(frame.layers[SKY_LAYER_CLOUDS], SKY_FORMAT_RGBA16F_PREMULTIPLIED, frame.width, frame.height, 4,
              out.cloudsRgba);
    copyLayer(frame.layers[SKY_LAYER_DEPTH], SKY_FORMAT_RG32F_METRES, frame.width, frame.height, 2, out.depthM);
    return true;
}

FetchStatus SkyClientSource::fetch(uint64_t afterFrameId, int timeoutMs, LatestFrame& out)
{
    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
    for (;;)
    {
        const auto leftMs = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        SkyResult r = sky_client_wait_frame(client_, afterFrameId, int(std::max<int64_t>(leftMs, 0)));
        if (r == SKY_ERR_TIMEOUT)
            return FetchStatus::NoFrame;
        SkyFrame frame{};
        if (r == SKY_OK)
            r = sky_client_acquire_frame(client_, &frame);
        if (r == SKY_ERR_NO_FRAME)
            return FetchStatus::NoFrame;
        if (r != SKY_OK)
        {
            error_ = sky_client_last_error(client_);
            return FetchStatus::Failed;
        }
        bool copied = false;
#ifdef DEMO_HAVE_VULKAN_IMPORT
        if (import_)
        {
            copied = import_->copySlot(frame.slot, frame.frame_id, frame.width, frame.height, frame.shadow_size, out,
                                       error_);
        }
        else
#endif
            copied = copyShm(frame, out);
        const SkyResult intact = sky_client_release_frame(client_, &frame);
        if (!copied)
            return FetchStatus::Failed;
        if (intact == SKY_ERR_TORN)
            continue;  // the service rewrote the slot while it was copied: take the next one
        if (intact != SKY_OK)
        {
            error_ = sky_client_last_error(client_);
            return FetchStatus::Failed;
        }
        out.frameId = frame.frame_id;
        out.simTimeUnixS = frame.sim_time_unix_s;
        out.exposure = frame.exposure;
        out.view = frame.view;
        out.shadow = frame.shadow;
        if (out.shadowSize == 0)
            out.shadow.size_texels = 0;
        return FetchStatus::NewFrame;
    }
}

}  // namespace demo
