// SPDX-License-Identifier: MIT
// Where a view ray's march start offset comes from (docs/model.md "March").
//
// The offset is read from the blue-noise tile at a texel chosen by the ray's direction in earth-fixed
// axes, not by its screen pixel: the same world direction gets the same offset whatever the camera's
// heading, roll or screen position, so the noise stays on the clouds when the view turns (history
// reprojected from the last frame carries the noise the new frame would march), and two display
// channels that see the same direction march it the same way.
//
// The sphere of directions is cut into the six faces of a cube, each face into cells of equal angle
// (an equi-angular cube map: atan of the face coordinates), `texelAngleRad` on a side at the face
// centre; the caller makes that the angle of one screen pixel so that neighbouring pixels read
// neighbouring texels of the tile and keep its blue-noise spectrum.
#ifndef SKY_LIB_WORLD_JITTER_GLSL
#define SKY_LIB_WORLD_JITTER_GLSL

// Blue-noise texel (0..BLUE_NOISE_SIZE-1 on both axes) for the unit direction `dirEcef`.
ivec2 worldJitterTexel(vec3 dirEcef, float texelAngleRad)
{
    SKY_ASSERT(texelAngleRad > 0.0f);
    vec3 a = abs(dirEcef);
    float u;
    float v;
    int face;
    if (a.x >= a.y && a.x >= a.z)
    {
        face = dirEcef.x > 0.0f ? 0 : 1;
        u = dirEcef.y / a.x;
        v = dirEcef.z / a.x;
    }
    else if (a.y >= a.z)
    {
        face = dirEcef.y > 0.0f ? 2 : 3;
        u = dirEcef.x / a.y;
        v = dirEcef.z / a.y;
    }
    else
    {
        face = dirEcef.z > 0.0f ? 4 : 5;
        u = dirEcef.x / a.z;
        v = dirEcef.y / a.z;
    }
    ivec2 cell = ivec2(int(floor(atan(u) / texelAngleRad)), int(floor(atan(v) / texelAngleRad)));
    // Each face starts at another place in the tile (odd offsets, our choice), so that opposite faces
    // do not repeat each other's pattern.
    cell = cell + ivec2(face * 23, face * 41);
    // The tile size is a power of two: the bit mask is a modulo that is also right for negative cells
    // (GLSL leaves % of negative integers undefined).
    return ivec2(cell.x & (BLUE_NOISE_SIZE - 1), cell.y & (BLUE_NOISE_SIZE - 1));
}

#endif
