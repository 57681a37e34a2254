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

/// Creates the LUT images and the atmosphere uniform buffer.
SkyStatus createAtmosphereResources(Renderer& r);

/// CPU estimate of the lighting for this frame (double precision, a few hundred atmosphere samples).
LightingEstimate estimateLighting(Renderer& r, const CameraFrame& camera, const SunMoon& sunMoon,
                                  const WindowSummary& summary);

/// Records the transmittance and multiple-scattering LUTs (when the earth radius changed) and the
/// sky-view LUT for this frame.
void recordAtmosphere(Renderer& r, VkCommandBuffer cmd, const CameraFrame& camera, const SunMoon& sunMoon,
                      const FrameInputs& in);

/// Records the composite pass (sky + clouds + aerial perspective -> linear and display images).
/// `cloud`, `depth`: the march's images (block resolution in reprojected frames); `history`: the packed
/// history of the pixels not marched (a 1x1 stand-in in full-resolution frames); `linear`: the linear
/// frame, or a 1x1 stand-in the shader does not write (FRAME_FLAG_NO_LINEAR_OUTPUT).
void recordComposite(Renderer& r, VkCommandBuffer cmd, const ViewRequest& request, const Image& cloud,
                     const Image& depth, const Image& history, const Image& linear);

}  // namespace sky
