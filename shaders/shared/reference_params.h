// SPDX-License-Identifier: MIT
// Push constants and path state of the reference path tracer (shaders/reference/reference_path.comp.glsl,
// skyservice/render/reference_renderer.h). Each dispatch carries every pixel's path on by a bounded amount
// of work (control.z loop iterations), keeping the path in ReferencePathState between dispatches, adds the
// samples it finished to the running sums and writes the average so far into the cloud image and depth
// the composite reads. The host dispatches until every pixel has its control.y samples.
#ifndef SKY_SHARED_REFERENCE_PARAMS_H
#define SKY_SHARED_REFERENCE_PARAMS_H
#include "shaders/shared/prelude.h"

// Phase functions the reference can scatter with (ReferencePush::phase.x).
#define REFERENCE_PHASE_MODEL 0      // the model's two-lobe Henyey-Greenstein (frame.look phaseForwardG, phaseBackG, phaseForwardWeight)
#define REFERENCE_PHASE_HG_DRAINE 1  // Jendersie & d'Eon 2023 HG + Draine blend for droplets of phase.y um
#define REFERENCE_PHASE_ISOTROPIC 2  // 1 / (4 pi): the tables of plane-parallel transfer (tests)

// Flags (ReferencePush::control.w).
// Density override: a homogeneous spherical shell (a plane-parallel slab at the scale of the test)
// between slab.x and slab.y metres of altitude, extinction slab.z per metre, single-scattering albedo
// slab.w; the weather window, noise and rain are not read.
#define REFERENCE_FLAG_SLAB 1u
// One light of irradiance 1 from testLight.xyz, in vacuum (no atmospheric transmittance), no moon, no sky
// light, a black ground: the radiance is then the plane-parallel problem's, per unit incident flux.
#define REFERENCE_FLAG_UNIT_LIGHT 2u
// The camera rays are cosine-distributed over the upper (or, with the next flag, lower) hemisphere of the
// eye instead of the view's pixels: the mean radiance times pi is then the flux through a horizontal plane.
#define REFERENCE_FLAG_HEMISPHERE 4u
#define REFERENCE_FLAG_HEMISPHERE_DOWN 8u

// What a pixel's path is doing (ReferencePathState::control.z).
#define REFERENCE_MODE_START 0u         // begin the next sample at the eye
#define REFERENCE_MODE_TRACK 1u         // delta tracking along the path to its next collision
#define REFERENCE_MODE_SHADOW 2u        // ratio tracking toward the light from a collision in a cloud
#define REFERENCE_MODE_GROUND_SHADOW 3u // ratio tracking toward the light from the ground
#define REFERENCE_MODE_IDLE 4u          // all of the pixel's samples are done

// The layer-bounds atlas (reference_renderer.cpp buildLayerBounds), RGBA32F in the layout of the column
// bounds (shaders/shared/column_bounds.h, same levels and texels): channel k of a level-0 texel is an upper
// bound of layer k's relative density times (1 + rain absorption) at any point whose weather lookups read
// that texel (0 where the layer has no coverage in its 3x3 neighbourhood); a coarser texel holds the
// maxima of its 2x2. Times frame.look.extinctionPerM, summed over the layers a stretch of ray can reach, it is the
// majorant of the tracking there.
struct ReferencePush
{
    // x: index of this dispatch (0: the paths start); y: samples per pixel; z: loop iterations per
    // invocation and dispatch at most (llvmpipe ends every loop of an invocation once they total 65535,
    // its guard against endless loops: reference_renderer.cpp); w: flags (REFERENCE_FLAG_*)
    uvec4 control;
    // x: phase function (REFERENCE_PHASE_*); y: droplet diameter (um, REFERENCE_PHASE_HG_DRAINE);
    // z: random seed; w: relative extinction bound of the anvil slab (the weather window's fifth layer)
    vec4 phase;
    // x: scattering events per path at most (the path ends there: the bias of a truncated series); yzw unused
    uvec4 limits;
    // REFERENCE_FLAG_SLAB: x base (m), y top (m), z extinction (1/m), w single-scattering albedo
    vec4 slab;
    // REFERENCE_FLAG_UNIT_LIGHT: xyz unit direction to the light (eye ENU); w unused
    vec4 testLight;
};

// One pixel's path between dispatches (std430; one per pixel in a storage buffer).
struct ReferencePathState
{
    vec4 origin;     // xyz: start of the ray being tracked (eye ENU, m); w: path weight
    vec4 direction;  // xyz: the path's unit direction; w: distance of the eye ray's first collision (m; < 0: none)
    vec4 light;      // xyz: unit direction of the shadow ray being tracked; w: its transmittance so far
    vec4 pending;    // rgb: what the shadow ray adds if it gets through; w: unused
    vec4 radiance;   // rgb: the sample's radiance so far; w: unused
    vec4 tracker;    // x: distance along the ray (m); y: end of its stretch; z: the stretch's majorant (1/m; 0:
                     // find the next stretch); w: end of the shell stretch (< x: find the next one)
    vec4 stretch;    // x: length of the next stretch tried (m); yzw unused
    uvec4 control;   // x: random state; y: scattering events; z: mode (REFERENCE_MODE_*); w: samples done
};

// The path tracer's counters (one storage buffer, host-visible; reference_renderer.h ReferenceStats says what
// each means). The wide ones are 64-bit sums kept in two words: an invocation adds its work once per dispatch
// and carries into the high word when the low one wraps (no 64-bit atomics needed).
struct ReferenceCounters
{
    uint majorantExceeded;   // densities above their majorant
    uint pathsTruncated;     // paths cut at limits.x scattering events
    uint pixelsUnfinished;   // pixels whose samples are not all done after this dispatch (reset by the host)
    uint samplesUnfinished;  // their samples not done (reset by the host): what a cut at the dispatch bound drops
    uint stepsLow;           // loop iterations of the paths (one step of either tracking, a stretch, a start)
    uint stepsHigh;
    uint skippedLow;         // stretches of ray passed over as empty (column bounds or a zero majorant)
    uint skippedHigh;
};

#endif
