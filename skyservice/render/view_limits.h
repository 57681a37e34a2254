// SPDX-License-Identifier: MIT
// The projections the renderer draws, defined once: every place a view enters (the socket protocol's
// set_view in skyservice/ipc/protocol.cpp, the CIGI View Definition in skyservice/service/cigi_view.cpp,
// the config's [service.view], the render command's options) checks against these numbers, and
// validateView (view_validation.h) holds the renderer to the same ones, so no view that entered is
// refused when a frame draws it. Plain constants with no includes: the CPU-only ipc layer reads them
// without linking the renderer. skyservice/ipc/PROTOCOL.md states the same ranges.
#pragma once

namespace sky
{

/// A symmetric view's vertical field of view (degrees), the closed range [kMinFovYDeg, kMaxFovYDeg]. Both
/// ends render: tan(fovY/2) is finite and well conditioned up to 170 degrees (tan 85 = 11.4).
constexpr double kMinFovYDeg = 1.0;
constexpr double kMaxFovYDeg = 170.0;

/// An off-centre frustum's angle from the view axis to one image edge (degrees), the open range
/// (-kMaxFrustumHalfAngleDeg, kMaxFrustumHalfAngleDeg); the view spans more than kMinFrustumSpanDeg each way.
constexpr double kMaxFrustumHalfAngleDeg = 85.0;
constexpr double kMinFrustumSpanDeg = 1.0;

/// True when `fovYDeg` is a vertical field of view the renderer draws (NaN is not).
constexpr bool fovYInRange(double fovYDeg) { return fovYDeg >= kMinFovYDeg && fovYDeg <= kMaxFovYDeg; }

/// True when `deg` is a frustum half-angle the renderer draws (NaN is not).
constexpr bool frustumHalfAngleInRange(double deg)
{
    return deg > -kMaxFrustumHalfAngleDeg && deg < kMaxFrustumHalfAngleDeg;
}

} // namespace sky
