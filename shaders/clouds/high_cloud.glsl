// SPDX-License-Identifier: MIT
// The high-altitude 2D texture layer: cirrus (streaks along the upper wind), cirrostratus (a smooth
// veil) and cirrocumulus (small cells), on a sphere at the high layer's altitude.

#include "shaders/clouds/high_cloud_alpha.glsl"

struct HighCloudSample
{
    vec3 radiance;   // premultiplied
    float alpha;
    float distanceM;
};

HighCloudSample sampleHighCloud(vec3 dir, float mu, float hc, float R)
{
    HighCloudSample s;
    s.radiance = vec3(0.0f);
    s.alpha = 0.0f;
    s.distanceM = 0.0f;
    float hHigh = frame.shell.highCloudAltitudeM;
    if ((frame.image.flags & FRAME_FLAG_NO_HIGH_CLOUD) != 0u || hHigh <= 0.0f)
        return s;
    float tNear;
    float tFar;
    if (!raySphereRoots(R + hc, mu, hc, hHigh, R, tNear, tFar))
        return s;
    float t = hc < hHigh ? tFar : tNear;
    if (t <= 0.0f || t > frame.shell.maxMarchDistanceM)
        return s;
    if (hc < hHigh)
    {
        float tGround = rayGroundDistance(R + hc, mu, hc, R);
        if (tGround >= 0.0f && tGround < t)
            return s;
    }
    vec3 p = dir * t;
    s.alpha = highCloudAlpha(p);
    if (s.alpha <= 0.0f)
        return s;
    vec3 lightDir = keyLightDirection();
    float cosTheta = dot(dir, lightDir);
    vec3 light = keyLightAt(p, lightDir);
    float phase = phaseTwoLobeHG(0.85f, -0.2f, 0.75f, cosTheta);
    s.radiance = s.alpha * (light * phase + frame.ambient.skyRadiance * frame.look.ambientStrength);
    s.distanceM = t;
    return s;
}
