// SPDX-License-Identifier: MIT
// libskyclient's reading of the vulkan `subscribed` reply (skyservice/ipc/PROTOCOL.md): the exported
// images' descriptions and the fds that came with it, in their SCM_RIGHTS order.
#pragma once

#include "skyservice/client/skyclient.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace skyclientdetail
{

/// The protocol's layer names, by SKY_LAYER_* index.
constexpr const char* kLayerNames[SKY_LAYER_COUNT] = {"display", "sky", "clouds", "depth"};

/**
 * Fills `f` from the reply and hands it the fds: frame images, shadow images (of the slots that have
 * one), each layer's images (sky, clouds, depth; slots 0..n-1), the semaphore.
 *
 * @param[in] asked the layers asked for (bit k = SKY_LAYER_k): each slot must describe exactly those.
 * @return "" on success, else why the reply is not understood (the caller closes the fds then).
 **********************************************************************/
std::string readExportReply(const nlohmann::json& reply, uint32_t asked, const std::vector<int>& fds,
                            SkyExportedFrames& f);

}  // namespace skyclientdetail
