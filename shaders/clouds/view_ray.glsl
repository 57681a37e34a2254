// SPDX-License-Identifier: MIT
// Pixel -> view ray, and the workgroup-row permutation (included by pass shaders after FrameBlock).

// lavapipe hands each CPU thread a contiguous range of workgroups; with sky on top and ground below one
// thread would get all the work. Interleaving rows of workgroups (0, n-1, 1, n-2, ...) balances it and
// costs nothing on a GPU (shared/GPU.md, "Pitfalls").
// `rows` is the height of the dispatched grid.
uvec2 permutedId(uvec2 globalId, uint rows)
{
    uint groupsY = (rows + gl_WorkGroupSize.y - 1u) / gl_WorkGroupSize.y;
    uint gy = gl_WorkGroupID.y;
    uint py = (gy % 2u == 0u) ? gy / 2u : groupsY - 1u - gy / 2u;
    return uvec2(globalId.x, py * gl_WorkGroupSize.y + gl_LocalInvocationID.y);
}

uvec2 permutedPixel(uvec2 globalId) { return permutedId(globalId, frame.image.heightPx); }

// Unit view direction (ENU) through the centre of `pixelCentre` (pixels, y down). An off-centre frustum
// (a display wall's channel) needs nothing more: camera.centreRayEnu is the ray through the image centre,
// shifted from the view axis on the CPU (frame_params.h).
vec3 viewRayDirection(vec2 pixelCentre)
{
    vec2 ndc = (pixelCentre + frame.sequence.rayJitterPx) / vec2(uvec2(frame.image.widthPx, frame.image.heightPx)) * 2.0f - 1.0f;
    vec3 d = frame.camera.centreRayEnu + ndc.x * frame.camera.halfWidthTan * frame.camera.rightEnu -
             ndc.y * frame.camera.halfHeightTan * frame.camera.upEnu;
    return normalize(d);
}
