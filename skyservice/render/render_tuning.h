// SPDX-License-Identifier: MIT
// The renderer's experiment knobs: distances and switches that trade a little of the picture for speed,
// kept settable so that sky-bench and the tests can measure both sides of each trade (BENCHMARKS.md).
// The product does not expose them: QualitySettings and the TOML config hold what a user or a quality
// preset sets; these stay at the defaults below unless a benchmark or a test changes Renderer::tuning.
#pragma once

#include <cstdint>

namespace sky
{

struct RenderTuning
{
    /// Beyond this distance (m) the light cone takes 3 cheap samples over the same length (0: never).
    double lightLodDistanceM = 0.0;
    /// Where no light volume reaches, a lit sample within this distance (m) of the last cone that marched
    /// its far (cheap) samples takes those instead of marching its own; its near, detailed samples stay
    /// its own (0: every cone marched in full). The next lit sample in a cloud is tens of metres away, the
    /// far samples 300 m-4.4 km, so a neighbour's tail is nearly the sample's own. Speed and picture cost
    /// of each setting: BENCHMARKS.md, tests/gpu/test_cone_tail.cpp.
    double coneTailReuseM = 400.0;
    /// ...and only lit samples farther than this from the eye (m) do: nearer, the reused tails of points
    /// nearer the cloud's surface brighten the cloud (a sunset deck 1.6/255 on average at 200 m, light
    /// volume off). 15 km is about where the light volume's far cascade ends on the ground (15.4 km); along
    /// a view ray from high up it reaches further (from 10 km up, ~18 km), and a render without the volume
    /// takes tails there that the cascade holds. With the diffuse octave remainder (1 / (1 + k tau) keeps
    /// light where a taken tail is too short) they brighten a deck seen from high up slightly, less than
    /// the cascade's texels holding those tails would (tests/gpu/test_light_volume.cpp, far cascade).
    double coneTailReuseBeyondM = 15000.0;
    /// Deep lit samples (behind a view transmittance below detailMinTransmittance) within
    /// this distance (m) of the last cone marched take its light and march none (0: each marches its own).
    /// What they add reaches the eye through less than a tenth, so an error in their light hardly shows
    /// (speed and picture cost: BENCHMARKS.md).
    double deepLightReuseM = 400.0;
    /// Beyond this distance (m) a light cone's detailed near samples (QualitySettings::fullConeSamples) are
    /// taken as one sample over their length (0: never): there the detail erosion has faded out
    /// (detailFadeEndM) and a pixel spans tens of metres. One density lookup fewer per far lit sample, and
    /// the frame's costliest rays are far ones (the sunset and FL350 scenes gain most: BENCHMARKS.md). The
    /// single sample sees less of a cloud's thin sunlit skin, so the clouds it lights come out brighter;
    /// a nearer limit changes more of the picture (figures: BENCHMARKS.md, tests/gpu/test_cone_tail.cpp).
    double coneNearMergeBeyondM = 40000.0;
    /// View samples behind a view transmittance below this take the base shape without detail erosion
    /// (0: never): little of such a sample reaches the eye. 0.2, not 0.1, because the current cloud
    /// shapes make each eroded sample dear (speed and picture cost: BENCHMARKS.md;
    /// tests/gpu/test_render.cpp checks the picture against the render that erodes every sample).
    double detailMinTransmittance = 0.2;
    /// Those deep view samples also step this many times further (1: the same step): fewer lookups per
    /// frame for a picture the bench scenes' contact sheet cannot tell apart (BENCHMARKS.md).
    double deepStepFactor = 2.0;
    /// A step inside a cloud covers at most this optical depth at the sample's extinction (the sample at
    /// a surface: at full density; while the view transmittance is above 0.5: at least half of it), so
    /// that the sunlit skin, a mean free path deep, gets its samples where the distance-grown step is
    /// longer (0: no limit). With no limit the sunlit side of a cumulus comes out too dark
    /// (tests/gpu/test_render.cpp SunSideOfACumulusIsBrighterThanItsShadowSide,
    /// CloudStepsConvergeOnFinerSteps), though frames are cheaper (BENCHMARKS.md).
    double maxStepOpticalDepth = 1.0;
    /// Reprojected frames march one pixel of every NxN block with the eye inside an overcast cloud layer
    /// (between its base and top, coverage >= 0.8 around it: fog; reprojection.h kOvercastCoverage): 2 (a
    /// quarter of the pixels, 4x those of the usual 4x4 block), or 1 (every pixel: the frame equals a full
    /// render). In a broken or scattered layer it is always 1. In fog a pixel's radiance comes from the
    /// first ~100 m of cloud, which moves little per frame, so block 2 stays close to the full render
    /// while turning fast inside an overcast deck (tests/gpu/test_flight_path.cpp) at a fraction of block
    /// 1's cost (BENCHMARKS.md).
    uint32_t insideCloudBlockPx = 2;
    double detailFadeStartM = 8000.0;  ///< detail erosion fades out from here...
    double detailFadeEndM = 25000.0;   ///< ...to here (beyond, its noise is finer than a pixel)
    /// With the light volume, also its far cascade of 2x wider texels (15.4 km around the eye): lit
    /// samples beyond the volume read it instead of marching the whole cone (shaders/shared/light_volume.h).
    bool lightVolumeFarCascade = true;
    /// The march's search jumps over stretches that the weather's column bounds show empty
    /// (shaders/shared/column_bounds.h); false samples every search step (tests, A/B).
    bool emptySpaceSkipping = true;
    /// The march launches its workgroup rows costliest first, by the lookups the previous frame of the
    /// same shape counted (shaders/shared/march_order.h); false: always the interleaved order (A/B). It
    /// changes no pixel; the frame ends sooner (BENCHMARKS.md).
    bool costOrderedMarch = true;
    /// The march's row counts (RenderResult::marchRowLookups) sum every ray's density lookups instead of
    /// taking the slowest ray of each workgroup: the work of a frame per pixel, for sky-bench's
    /// --lookup-totals and the tests that count it (the launch order then follows the totals).
    bool marchLookupTotals = false;

    bool operator==(const RenderTuning&) const = default;
};

}  // namespace sky
