// SPDX-License-Identifier: MIT
// The reference renderer: a path tracer of the same clouds as the real-time march (its density function,
// noise textures, weather window, sun, moon and sky), with every order of scattering, to measure the
// real-time lighting against (shaders/reference/reference_path.comp.glsl says how a path goes).
//
// Usage:
//   ReferenceRenderer ref;  createReferenceRenderer(renderer, ref)
//   renderReference(renderer, ref, request, quality, settings, result)  -> the same RenderResult as renderView
//   destroyReferenceRenderer(renderer, ref)
// It borrows the Renderer's noise textures, atmosphere LUTs, weather window and composite: renderReference
// first renders the view in real time (which prepares all of those for it, and leaves the frame uniforms in
// the frame context it used), then replaces the march's cloud image and depth with the converged path-traced
// ones and composites again. Its own objects (pipeline, running sums, counters) live here.
#pragma once

#include "skyservice/render/renderer.h"

namespace sky
{

enum class ReferencePhase : uint32_t
{
    Model = 0,      ///< the model's two-lobe Henyey-Greenstein (QualitySettings::phase*)
    HgDraine = 1,   ///< Jendersie & d'Eon 2023, HG + Draine for droplets of dropletDiameterUm
    Isotropic = 2,  ///< 1 / (4 pi) (the plane-parallel tables)
};

/// A homogeneous layer replacing the clouds (tests): between baseM and topM of altitude, everywhere.
struct ReferenceSlab
{
    bool enabled = false;
    double baseM = 2000.0, topM = 3000.0;
    double extinctionPerM = 0.01;
    double albedo = 1.0;  ///< single-scattering albedo
};

struct ReferenceSettings
{
    uint32_t samplesPerPixel = 64;
    /// Loop iterations per invocation and dispatch at most (ReferencePush::control.z): a dispatch carries each
    /// pixel's path on by this much work and the host dispatches again until every sample is done. llvmpipe
    /// ends every loop of an invocation once they total 65535 iterations (gallivm's guard against endless
    /// loops), so the budget stays below; it also keeps a GPU's dispatches short.
    uint32_t iterationsPerDispatch = 60000;
    /// Scattering events per path at most; a path cut there is counted (ReferenceStats::pathsTruncated).
    /// Light leaving a cloud of optical depth 100 has scattered ~1e3 times.
    uint32_t maxEvents = 20000;
    /// Dispatches at most: the bound that makes every render finish. A render that reaches it ends with the
    /// samples done so far (each pixel the average of its own; a pixel with none is left without cloud), and
    /// counts the samples it dropped (ReferenceStats::pathsCut). 0: 256 + 16 per sample per pixel, several times
    /// what the slowest views took (reference_renderer.cpp).
    uint32_t maxDispatches = 0;
    ReferencePhase phase = ReferencePhase::Model;
    double dropletDiameterUm = 20.0;  ///< ReferencePhase::HgDraine: cumulus droplets are 10-20 um
    uint32_t seed = 1;
    // Test modes (shaders/shared/reference_params.h REFERENCE_FLAG_*).
    ReferenceSlab slab;
    /// One light of irradiance 1 from unitLightDirectionEnu, in vacuum, no sky, a black ground.
    bool unitLight = false;
    glm::dvec3 unitLightDirectionEnu{0.0, 0.0, 1.0};
    /// Eye rays cosine-distributed over the upper (+1) or lower (-1) hemisphere instead of the pixels' (0):
    /// the mean radiance times pi is the flux through a horizontal plane at the eye.
    int hemisphere = 0;
};

/// What the last renderReference did (reference_path.comp.glsl). The first three should stay 0: a density above
/// its majorant biases the tracking, a path cut at maxEvents drops its higher orders, a sample cut at
/// maxDispatches is missing from its pixel.
struct ReferenceStats
{
    uint32_t majorantExceeded = 0;  ///< densities above the tracking's majorant (biased)
    uint32_t pathsTruncated = 0;    ///< paths cut at maxEvents
    uint64_t pathsCut = 0;          ///< samples not traced because the render reached maxDispatches
    uint64_t paths = 0;             ///< samples traced to their end (pixels x samples per pixel - pathsCut)
    uint64_t steps = 0;             ///< loop iterations of the paths (a tracking step, a stretch, a start)
    uint64_t stretchesSkipped = 0;  ///< stretches of ray passed over as empty (column bounds, zero majorant)
    uint32_t dispatches = 0;        ///< dispatches it took
    uint32_t maxDispatches = 0;     ///< the bound it ran under
    double seconds = 0;             ///< wall time of the path tracing
};

struct ReferenceRenderer
{
    Program pathProgram;
    Image radianceSum, depthSum;  ///< running sums, RGBA32F and R32F at the view's size
    Buffer paths;                 ///< a ReferencePathState per pixel (shaders/shared/reference_params.h)
    Image layerBounds;            ///< the window's layer bounds: the tracking's majorants (reference_params.h)
    Buffer stats;                 ///< the shader's ReferenceCounters (reference_params.h), host-visible
    ReferenceStats last;
};

SkyStatus createReferenceRenderer(Renderer& r, ReferenceRenderer& ref);
void destroyReferenceRenderer(Renderer& r, ReferenceRenderer& ref);

/// Renders `request` with the path tracer into `result` (the images and facts renderView gives; gpuMs
/// "reference" is the path tracing's wall time). `quality` is that of the real-time frame it borrows the
/// setup from: its model settings (extinction, phase, detail, high cloud) are the reference's too; it is
/// rendered at full resolution, without reprojection or accumulation.
SkyStatus renderReference(Renderer& r, ReferenceRenderer& ref, const ViewRequest& request,
                          const QualitySettings& quality, const ReferenceSettings& settings, RenderResult& result);

}  // namespace sky
