// SPDX-License-Identifier: MIT
// UTC times as the demo reads and shows them (ISO 8601, "2026-06-21T12:00:00Z").
#pragma once

#include <string>

namespace demo
{

/**
 * @param[in] text "YYYY-MM-DDTHH:MM:SS" with an optional fraction of a second and a trailing "Z".
 * @param[out] unixTimeS seconds since 1970-01-01T00:00:00Z.
 * @return false when the text is not such a time.
 **********************************************************************/
bool parseUtc(const std::string& text, double& unixTimeS);

/// "2026-06-21T12:00:00Z" (whole seconds, rounded down).
std::string formatUtc(double unixTimeS);

}  // namespace demo
