// SPDX-License-Identifier: MIT
// Front-to-back compositing of stretches of a pixel's ray, shared by the real-time march
// (cloud_march.comp.glsl) and the reference path tracer (reference/reference_path.comp.glsl).
#ifndef CLOUD_PATH_GLSL
#define CLOUD_PATH_GLSL

// What a stretch of a pixel's ray leaves: radiance toward the eye (premultiplied), transmittance, and the
// sums of the transmittance-weighted depth.
struct CloudPath
{
    vec3 radiance;
    float transmittance;
    float depthWeighted;
    float depthWeight;
};

// `front` seen through, then `back`.
CloudPath inFrontOf(CloudPath front, CloudPath back)
{
    return CloudPath(front.radiance + front.transmittance * back.radiance, front.transmittance * back.transmittance,
                     front.depthWeighted + front.transmittance * back.depthWeighted,
                     front.depthWeight + front.transmittance * back.depthWeight);
}

#endif
