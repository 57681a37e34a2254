// SPDX-License-Identifier: MIT
// The columns a reprojected frame marches in full (skyservice/render/reprojection.h NewColumns: in a
// turn, those the previous frame did not see): frame.previousForward.w is the first, frame.previousEye.w
// how many (0: none). Their pixels are stored in the fresh images beside the blocks: block row r holds,
// from texel column ceil(width / B) on, the count x B pixels of rows rB .. rB + B - 1, row by row.
// Included after the FrameBlock.
#ifndef SKY_LIB_NEW_COLUMNS_GLSL
#define SKY_LIB_NEW_COLUMNS_GLSL

uint newColumnCount()
{
    return uint(frame.previousEye.w);
}

// The first texel column after the blocks.
int newColumnsTexelX0(int B)
{
    return (int(frame.image.x) + B - 1) / B;
}

// The pixel that the fresh texel `texel` (x at or after newColumnsTexelX0) holds; x -1 when none.
ivec2 newColumnPixel(ivec2 texel, int B)
{
    int count = int(newColumnCount());
    int k = texel.x - newColumnsTexelX0(B);
    if (count == 0 || k < 0 || k >= count * B)
        return ivec2(-1);
    return ivec2(int(frame.previousForward.w) + k % count, texel.y * B + k / count);
}

// Whether `pixel` lies in the new columns; its fresh texel in `texel`.
bool newColumnTexel(ivec2 pixel, int B, out ivec2 texel)
{
    int count = int(newColumnCount());
    int k = pixel.x - int(frame.previousForward.w);
    texel = ivec2(newColumnsTexelX0(B) + k + (pixel.y % B) * count, pixel.y / B);
    return B > 1 && k >= 0 && k < count;
}

#endif
