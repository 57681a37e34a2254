// SPDX-License-Identifier: MIT
// Where the demo's frames come from: "the latest frame" of the sky service (pixels, shadow map,
// geo-reference, view), behind an interface so that the window, the compositing and the headless
// capture do not care which transport (shared memory or imported Vulkan memory) delivered it.
#pragma once

#include "skyservice/ipc/shm_layout.h"

#include <cstdint>
#include <string>
#include <vector>

namespace demo
{

/// One frame of the service, copied out of the transport (so it can be held as long as the demo likes).
struct LatestFrame
{
    uint64_t frameId = 0;            ///< the service's frame id (1, 2, ...); 0 = none yet
    double simTimeUnixS = 0.0;       ///< UTC of the rendered scene (s since 1970)
    SkyShmView view{};               ///< the view it was rendered for (its width/height are the image's)
    uint32_t width = 0;              ///< pixels
    uint32_t height = 0;             ///< pixels
    std::vector<uint8_t> rgba;       ///< width*height*4 bytes, sRGB-encoded RGBA8, top row first
    uint32_t shadowSize = 0;         ///< shadow map texels per side; 0 = no shadow map in this frame
    std::vector<float> shadowTransmittance;  ///< shadowSize^2 key-light transmittance (0 opaque, 1 clear),
                                             ///< north row first, west column first
    SkyShmShadowGeoRef shadow{};     ///< where the shadow map lies on the earth, and the key light
    // Compositing layers (shm_layout.h SKY_LAYER_*), decoded to float; empty when the frame has none (the
    // Vulkan transport, or a service not asked for them). Linear values are pre-exposed (`exposure`).
    double exposure = 1.0;           ///< linear values / exposure = W m^-2 sr^-1 nm^-1
    std::vector<float> skyRgba;      ///< width*height*4: the sky without clouds, linear
    std::vector<float> cloudsRgba;   ///< width*height*4: the clouds, premultiplied linear radiance + alpha
    /// width*height*2: per pixel the cloud's front, then its transmittance-weighted distance (m), 0 = none.
    std::vector<float> depthM;

    /// True when the sky, clouds and depth layers are all present for this frame's size.
    bool hasLayers() const
    {
        const size_t n = size_t(width) * height;
        return n > 0 && skyRgba.size() == 4 * n && cloudsRgba.size() == 4 * n && depthM.size() == 2 * n;
    }
};

/// Result of FrameSource::fetch.
enum class FetchStatus
{
    NewFrame,  ///< `out` holds a frame newer than the one asked after
    NoFrame,   ///< nothing newer within the timeout (not an error)
    Failed,    ///< the connection is gone or the transport broke: lastError() says why
};

/// The service as the demo sees it. Implementations: SkyClientSource (skyclient_source.h).
class FrameSource
{
public:
    virtual ~FrameSource() = default;

    /// Sends the view the service should render next; false (lastError) when the service refused it.
    virtual bool setView(const SkyShmView& view) = 0;
    /**
     * @param[in] unixTimeS simulated UTC (s since 1970).
     * @param[in] rate simulated seconds per real second (0 = frozen).
     * @return false (lastError) when the service refused it.
     **********************************************************************/
    virtual bool setTime(double unixTimeS, double rate) = 0;
    /// Asks for one frame now (a service with render_rate_hz = 0 renders only on request).
    virtual bool requestFrame(uint64_t& frameId) = 0;
    /**
     * Copies the newest frame with an id greater than afterFrameId into out, waiting at most timeoutMs.
     * A frame torn while it was copied is discarded and the next one taken (within the same timeout).
     **********************************************************************/
    virtual FetchStatus fetch(uint64_t afterFrameId, int timeoutMs, LatestFrame& out) = 0;
    /// "shm" or "vulkan" (zero-copy import).
    virtual std::string transportName() const = 0;
    /// One line: why the last call failed.
    virtual std::string lastError() const = 0;
};

}  // namespace demo
