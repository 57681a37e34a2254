// SPDX-License-Identifier: MIT
// Empty-space skipping for the march's search (shaders/shared/column_bounds.h): whether a stretch of a
// view ray certainly holds no cloud. Included after cloud_density.glsl; reads the columnBounds binding.

// Column-bounds level-0 texel coordinates (texel units) of the point at map position `mapPosM`.
vec2 columnBoundsTexelPosition(vec2 mapPosM)
{
    vec2 uv = windowWarp(windowPlanePosition(mapPosM), frame.window.halfExtentM, frame.window.warpRadiusM) / (2.0f * frame.window.halfExtentM) + 0.5f;
    return uv * float(WEATHER_WINDOW_SIZE);
}

// The 2x2 texels (atlas coordinates i0, i1 of shaders/shared/column_bounds.h) of the coarsest pyramid level
// needed whose block covers every map position of a stretch of ray from map position m0 to m1.
void columnBoundsCover(vec2 m0, vec2 m1, out ivec2 i0, out ivec2 i1)
{
    // A view ray's map positions lie on a straight line from the eye (the projection is azimuthal
    // equidistant about it); the window's radial warp bends that line a little, and a ray from elsewhere
    // (the reference path tracer's) bends more over a short stretch, so: the texel box of both ends and
    // the middle, grown by an eighth of its size and a texel.
    vec2 a = columnBoundsTexelPosition(m0);
    vec2 b = columnBoundsTexelPosition(m1);
    vec2 c = columnBoundsTexelPosition(0.5f * (m0 + m1));
    vec2 lo = min(min(a, b), c);
    vec2 hi = max(max(a, b), c);
    vec2 grow = 0.125f * (hi - lo) + 1.0f;
    lo -= grow;
    hi += grow;
    // The pyramid level whose texels are wider than the box: the 2x2 texels from the one holding the box's
    // low corner cover it. Beyond the window everything is empty, so clamped texels are conservative.
    float extent = max(hi.x - lo.x, hi.y - lo.y);
    int level = extent < 1.0f ? 0 : min(int(floor(log2(extent))) + 1, COLUMN_BOUNDS_LEVELS - 1);
    int side = WEATHER_WINDOW_SIZE >> level;
    ivec2 first = ivec2(floor(lo / float(1 << level)));
    ivec2 origin = columnBoundsLevelOrigin(level, WEATHER_WINDOW_SIZE);
    i0 = origin + clamp(first, ivec2(0), ivec2(side - 1));
    i1 = origin + clamp(first + 1, ivec2(0), ivec2(side - 1));
}

// True when the ray from `rayOrigin` (eye ENU, m) along the unit `dir` holds no cloud between t0 and t1 (m
// along it): its altitudes there lie above the highest top or below the lowest base of every column the
// stretch crosses. False when unsure.
bool noCloudOnSegment(vec3 rayOrigin, vec3 dir, float t0, float t1)
{
    float h0;
    float h1;
    vec2 m0 = weatherMapPosition(rayOrigin + dir * t0, h0);
    vec2 m1 = weatherMapPosition(rayOrigin + dir * t1, h1);
    // The altitude along a straight line is convex in t: highest at an end, lowest at an end or at the
    // point nearest the earth's centre.
    float hHigh = max(h0, h1);
    float hLow = min(h0, h1);
    float tNearest = -dot(rayOrigin + vec3(0.0f, 0.0f, frame.earth.centreToEyeM), dir);
    if (tNearest > t0 && tNearest < t1)
    {
        float hNearest;
        weatherMapPosition(rayOrigin + dir * tNearest, hNearest);
        hLow = min(hLow, hNearest);
    }
    ivec2 i0;
    ivec2 i1;
    columnBoundsCover(m0, m1, i0, i1);
    uvec2 b00 = texelFetch(columnBounds, i0, 0).xy;
    uvec2 b10 = texelFetch(columnBounds, ivec2(i1.x, i0.y), 0).xy;
    uvec2 b01 = texelFetch(columnBounds, ivec2(i0.x, i1.y), 0).xy;
    uvec2 b11 = texelFetch(columnBounds, i1, 0).xy;
    float baseM = columnBoundsBaseM(min(min(b00.x, b10.x), min(b01.x, b11.x)));
    float topM = columnBoundsTopM(max(max(b00.y, b10.y), max(b01.y, b11.y)));
    return hLow > topM || hHigh < baseM;
}

// The same for the view ray `dir` from the eye, between t0 and t1 (m from the eye).
bool noCloudBetween(vec3 dir, float t0, float t1)
{
    return noCloudOnSegment(vec3(0.0f), dir, t0, t1);
}
