// SPDX-License-Identifier: MIT
// Front-to-back compositing of stretches of a pixel's ray, shared by the real-time march
// (cloud_march.comp.glsl) and the reference path tracer (reference/reference_path.comp.glsl).
#ifndef CLOUD_PATH_GLSL
#define CLOUD_PATH_GLSL

// The cloud's front along a ray (the depth layer's R): where the opacity accumulated from the eye first
// reaches this. Our choice: 2 % hides a scene point behind it by less than one 8-bit display step of most
// pictures, and is far enough above the march's noise that a wisp in front of a cloud does not count.
const float kCloudFrontOpacity = 0.02f;

// What a stretch of a pixel's ray leaves: radiance toward the eye (premultiplied), transmittance, the
// sums of the transmittance-weighted depth, and the stretch's front (m: where its own opacity first
// reaches kCloudFrontOpacity; 0 when it never does).
struct CloudPath
{
    vec3 radiance;
    float transmittance;
    float depthWeighted;
    float depthWeight;
    float frontM;
};

// `front` seen through, then `back`. The front is the front stretch's own when it has one, else the back
// one's: measured without the front stretch's little opacity, it lies a little behind the exact one.
CloudPath inFrontOf(CloudPath front, CloudPath back)
{
    return CloudPath(front.radiance + front.transmittance * back.radiance, front.transmittance * back.transmittance,
                     front.depthWeighted + front.transmittance * back.depthWeighted,
                     front.depthWeight + front.transmittance * back.depthWeight,
                     front.frontM > 0.0f ? front.frontM : back.frontM);
}

// The depth layer of a finished ray: (front, weighted distance), both 0 without cloud. A ray whose opacity
// never reaches kCloudFrontOpacity takes the weighted distance as its front, and the front is never
// beyond the weighted distance (a thin stretch before a dense one can put its weighted mean nearer).
vec2 cloudDepthLayer(CloudPath c)
{
    float depth = c.depthWeight > 1e-4f ? c.depthWeighted / c.depthWeight : 0.0f;
    return vec2(c.frontM > 0.0f ? min(c.frontM, depth) : depth, depth);
}

#endif
