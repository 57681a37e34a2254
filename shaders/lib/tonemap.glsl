// SPDX-License-Identifier: MIT
// Display transform: ACES filmic curve (Narkowicz 2015 fit) and the sRGB transfer function (IEC 61966-2-1).

vec3 tonemapAces(vec3 x)
{
    const float a = 2.51f;
    const float b = 0.03f;
    const float c = 2.43f;
    const float d = 0.59f;
    const float e = 0.14f;
    vec3 y = (x * (a * x + b)) / (x * (c * x + d) + e);
    return clamp(y, vec3(0.0f), vec3(1.0f));
}

float encodeSrgbChannel(float c)
{
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

vec3 encodeSrgb(vec3 c)
{
    return vec3(encodeSrgbChannel(c.x), encodeSrgbChannel(c.y), encodeSrgbChannel(c.z));
}
