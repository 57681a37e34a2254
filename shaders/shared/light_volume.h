// SPDX-License-Identifier: MIT
// The light volume: optical depth toward the key light, precomputed each frame around the eye,
// so that a lit view sample near the eye reads one texel instead of marching the far part of its light
// cone. Shared by the C++ renderer and the shaders.
//
// Texel (i, j, k) of a LIGHT_VOLUME_SIZE^2 x LIGHT_VOLUME_LEVELS RG16F volume holds, for the point at
//   window-plane position cornerM + (i + 0.5, j + 0.5) * texelM (frame.lightVolume.nearCascade; metres, the
//   unwarped plane of the weather window: fixed to the ground while the window is, so the texels do not
//   slide with the eye), altitude shell.lowestBaseM + (k + 0.5) / LEVELS * (shell.highestTopM - shell.lowestBaseM),
// the transmittance exp(-tau) (x) and the diffusion factor 1 / (1 + k tau) (y, shaders/clouds/light_cone.glsl),
// tau = look.extinctionPerM x relative density x metres of the cone samples from frame.march.fullConeSamples on and of the
// long sample, all with the cheap (base-shape) density: the tail of the light cone (LightCone,
// shaders/clouds/cloud_lighting.glsl). Each of the light's two attenuations is interpolated as itself:
// the transmittance of texels deep in a cumulus, interpolated, is the least deep one's, which lit the
// diffuse term up to 2x too brightly there. Transmittance, not optical depth, because the
// march interpolates between texels: across a cloud's edge, where the tail goes from clear to opaque, the
// mean of two optical depths made the lit side far too dark (Jensen: exp of a mean is below the mean of
// exps; tests/gpu/test_light_volume.cpp's cumulus from below shows it). The first cone samples stay live and detailed,
// because they make the sunlit skin of a cloud (a mean free path is ~20 m); the tail starts 210 m away
// and spreads over a cone hundreds of metres wide, so 160 m texels lose little.
#ifndef SKY_SHARED_LIGHT_VOLUME_H
#define SKY_SHARED_LIGHT_VOLUME_H

#define LIGHT_VOLUME_SIZE 96     // texels per side on the window plane (96 x 160 m: 7.7 km around the eye)
#define LIGHT_VOLUME_LEVELS 24   // altitude levels over the cloud shell

// The far cascade: a second volume of the same size whose texels are this many times wider (320 m: 15.4
// km around the eye), placed in frame.lightVolume.farCascade, read where a lit sample lies outside the first.
// Beyond 7.7 km those samples marched the whole cone (7 lookups). At 4 (640 m, 30.7 km) the cascade
// flattened the shading of clouds 8-30 km away: the sunlit/shadow side ratio of a cumulus 12 km off fell
// from 1.39 to 1.23 (tests/gpu/test_render.cpp SunSide...); at 2 it is 1.35 (BENCHMARKS.md).
#define LIGHT_VOLUME_FAR_SCALE 2

#endif
