// SPDX-License-Identifier: MIT
// The progress callback of long ingest operations.
#pragma once

#include <functional>
#include <string>

namespace sky
{

/// Called now and then with the fraction done in [0, 1] and what is being done ("decoding message 12").
/// May be empty.
using ProgressFn = std::function<void(double fraction, const std::string& stage)>;

}  // namespace sky
