// SPDX-License-Identifier: MIT
// FrameSource over libskyclient (skyservice/client/skyclient.h): the shared-memory ring, or the zero-copy
// transport (the service's exported Vulkan images imported into the demo's own device, vulkan_import.h)
// when the service renders on a GPU that the demo's Vulkan instance also sees.
#pragma once

#include "client_demo/frame_source.h"
#include "client_demo/vulkan_device.h"

#include "skyservice/client/skyclient.h"

#include <memory>
#include <string>

namespace demo
{

class VulkanFrameImport;

/// Which transport to use.
enum class Transport
{
    Auto,    ///< zero-copy when the service's GPU is one of ours (same deviceUUID and driverUUID), else shm
    Shm,     ///< shared-memory ring only
    Vulkan,  ///< zero-copy only (fails when the GPUs differ)
};

class SkyClientSource final : public FrameSource
{
public:
    /**
     * Connects to the service and subscribes.
     *
     * @param[in] socketPath the service's control socket.
     * @param[in] transport which transport.
     * @param[in,out] vk null: shared memory only, no Vulkan at all. Otherwise an instance must exist and the
     *   device must not: open() creates the device, on the service's GPU when the zero-copy transport is
     *   taken (with the import extensions added to `request`), else as `request` says.
     * @param[in] request what else the device must do (present to a surface).
     * @param[in] wantLayers shared memory: subscribe to the sky, clouds and depth layers as well (the zero-copy
     *   transport exports the display image only; Transport::Auto then takes shared memory).
     * @param[out] error why it failed (connection refused, no device, import failed).
     * @return the source, or null.
     **********************************************************************/
    static std::unique_ptr<SkyClientSource> open(const std::string& socketPath, Transport transport, VulkanDevice* vk,
                                                 const DeviceRequest& request, bool wantLayers, std::string& error);
    ~SkyClientSource() override;
    SkyClientSource(const SkyClientSource&) = delete;
    SkyClientSource& operator=(const SkyClientSource&) = delete;

    bool setView(const SkyShmView& view) override;
    bool setTime(double unixTimeS, double rate) override;
    bool requestFrame(uint64_t& frameId) override;
    FetchStatus fetch(uint64_t afterFrameId, int timeoutMs, LatestFrame& out) override;
    std::string transportName() const override;
    std::string lastError() const override { return error_; }

private:
    SkyClientSource() = default;
    bool copyShm(const SkyFrame& frame, LatestFrame& out);

    SkyClient* client_ = nullptr;
    std::unique_ptr<VulkanFrameImport> import_;  ///< null on the shared-memory transport
    std::string error_;
};

}  // namespace demo
