// SPDX-License-Identifier: MIT
// A view's image plane: a symmetric frustum (vertical field of view and the image's aspect) or an
// off-centre one (Frustum: four half-angles, as the channels of a display wall have), both reduced to
// the same four numbers that the frame's uniforms carry (shaders/shared/frame_params.h).
#pragma once

#include "skyservice/render/render_types.h"

#include <string>

namespace sky
{

/// The image plane at unit distance along the view axis, in tangent units. The ray of normalised
/// device coordinates (ndcX, ndcY), each in [-1, 1] with y down, is
///   forward + (centreX + ndcX * halfWidth) * right + (centreY - ndcY * halfHeight) * up.
/// A symmetric frustum has centre (0, 0); its half extents are tan(fovY/2) * width/height and tan(fovY/2).
struct ViewTangents
{
    double halfWidth = 0, halfHeight = 0;
    double centreX = 0, centreY = 0;
};

ViewTangents viewTangents(const ViewRequest& view);

/// True when the frustum's angles are in range (Frustum: each in (-85, 85) degrees, left + right and
/// up + down > 1 degree); otherwise false and `error` names the angle at fault.
bool validateFrustum(const Frustum& frustum, std::string& error);

/// True when the two views project the same directions onto the same pixels (size and frustum equal).
bool sameProjection(const ViewRequest& a, const ViewRequest& b);

/// The vertical angle the view covers (degrees): fovYDeg, or up + down of an asymmetric frustum.
double verticalExtentDeg(const ViewRequest& view);

}  // namespace sky
