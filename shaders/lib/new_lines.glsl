// SPDX-License-Identifier: MIT
// The lines a reprojected frame marches in full (skyservice/render/reprojection.h NewLines): in a turn,
// the columns the previous frame did not see, in a pitch change the rows (both in a banked turn);
// frame.reprojection.newLines says which. Their pixels are
// stored in the fresh images beside and below the blocks:
// - columns: block row r holds, from texel column ceil(width / B) on, the count x B pixels of rows
//   rB .. rB + B - 1, row by row;
// - rows: block column c holds, from texel row ceil(height / B) on, the count x B pixels of columns
//   cB .. cB + B - 1, column by column.
// A pixel in both (a corner) is marched twice and taken from its column.
// Included after the FrameBlock.
#ifndef SKY_LIB_NEW_LINES_GLSL
#define SKY_LIB_NEW_LINES_GLSL

uint newColumnCount()
{
    return frame.reprojection.newLines.columnCount;
}

uint newRowCount()
{
    return frame.reprojection.newLines.rowCount;
}

// The first texel column after the blocks.
int newColumnsTexelX0(int B)
{
    return (int(frame.image.widthPx) + B - 1) / B;
}

// The first texel row after the blocks.
int newRowsTexelY0(int B)
{
    return (int(frame.image.heightPx) + B - 1) / B;
}

// The pixel that the fresh texel `texel` (beyond the blocks: x at or after newColumnsTexelX0, or y at or
// after newRowsTexelY0) holds; x -1 when none.
ivec2 newLinePixel(ivec2 texel, int B)
{
    int x0 = newColumnsTexelX0(B), y0 = newRowsTexelY0(B);
    if (texel.x >= x0)
    {
        int count = int(newColumnCount());
        int k = texel.x - x0;
        if (count == 0 || texel.y >= y0 || k >= count * B)
            return ivec2(-1);
        return ivec2(int(frame.reprojection.newLines.firstColumn) + k % count, texel.y * B + k / count);
    }
    int count = int(newRowCount());
    int k = texel.y - y0;
    if (count == 0 || k < 0 || k >= count * B)
        return ivec2(-1);
    return ivec2(texel.x * B + k / count, int(frame.reprojection.newLines.firstRow) + k % count);
}

// Whether `pixel` lies in the new columns or rows; its fresh texel in `texel`.
bool newLineTexel(ivec2 pixel, int B, out ivec2 texel)
{
    texel = ivec2(0);
    if (B <= 1)
        return false;
    int columns = int(newColumnCount());
    int k = pixel.x - int(frame.reprojection.newLines.firstColumn);
    if (k >= 0 && k < columns)
    {
        texel = ivec2(newColumnsTexelX0(B) + k + (pixel.y % B) * columns, pixel.y / B);
        return true;
    }
    int rows = int(newRowCount());
    k = pixel.y - int(frame.reprojection.newLines.firstRow);
    if (k >= 0 && k < rows)
    {
        texel = ivec2(pixel.x / B, newRowsTexelY0(B) + k + (pixel.x % B) * rows);
        return true;
    }
    return false;
}

#endif
