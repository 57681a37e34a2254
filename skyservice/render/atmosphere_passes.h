// SPDX-License-Identifier: MIT
// Host side of the atmosphere: the LUT images and passes, the composite pass, and the CPU estimate of
// the light that reaches the clouds (ambient sky, ground irradiance, exposure).
#pragma once

#include "skyservice/render/frame_setup.h"
#include "skyservice/render/renderer.h"

namespace sky
{

struct LightingEstimate
{
    glm::dvec3 sunIrradiance{1.0};        ///< top-of-atmosphere solar irradiance (renderer units)
    glm::dvec3 ambientSkyRadiance{0.0};   ///< mean sky radiance over the upper hemisphere at cloud level
    glm::dvec3 groundIrradiance{0.0};     ///< sun + sky irradiance on the ground
    double groundAlbedo = 0.3;
    double exposure = 1.0;                ///< multiplier before tone mapping
};

/// Creates the LUT images.
SkyStatus createAtmosphereResources(Renderer& r);

/// CPU estimate of the lighting for this frame (double precision, a few hundred atmosphere samples).
LightingEstimate estimateLighting(Renderer& r, const CameraFrame& camera, const SunMoon& sunMoon,
                                  const WindowSummary& summary);

/// Records the transmittance and multiple-scattering LUTs (when the earth radius changed) and the
/// sky-view LUT for this frame.
void recordAtmosphere(Renderer& r, VkCommandBuffer cmd, const CameraFrame& camera, const SunMoon& sunMoon,
                      const FrameInputs& in);

/// The images the composite reads and writes. Each optional output is the frame's image while a reader
/// asks for it (its FRAME_FLAG_* set), else a 1x1 stand-in the shader does not write.
struct CompositeImages
{
    const Image* cloud = nullptr;    ///< the march's cloud image (block resolution in reprojected frames)
    const Image* depth = nullptr;    ///< ... and its depth
    const Image* history = nullptr;  ///< the packed history of the pixels not marched (stand-in: full frames)
    const Image* linear = nullptr;   ///< linear frame (FRAME_FLAG_NO_LINEAR_OUTPUT clear)
    const Image* sky = nullptr;      ///< FRAME_FLAG_SKY_LAYER
    const Image* cloudLayer = nullptr;  ///< FRAME_FLAG_CLOUD_LAYER
    const Image* cloudOut = nullptr;    ///< FRAME_FLAG_WRITE_CLOUD: the full-resolution cloud image...
    const Image* depthOut = nullptr;    ///< ... and depth of a reprojected frame
};

/// Records the composite pass (sky + clouds + aerial perspective -> display image and the outputs asked for).
void recordComposite(Renderer& r, VkCommandBuffer cmd, const ViewRequest& request, const CompositeImages& images);

}  // namespace sky
