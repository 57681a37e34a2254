// SPDX-License-Identifier: MIT
// The view a published frame was rendered for, as the shared-memory ring and libskyclient carry it.
#pragma once

#include "skyservice/ipc/shm_layout.h"
#include "skyservice/render/render_types.h"

namespace sky
{

/// `request` as SkyShmView: longitude in [-180, 180), and either fov_deg or, for an asymmetric frustum,
/// the four half-angles with asymmetric = 1 and fov_deg = up + down (the vertical angle it covers).
SkyShmView shmViewOf(const ViewRequest& request);

}  // namespace sky
