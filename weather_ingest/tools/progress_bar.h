// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <chrono>
#include <string>

namespace sky
{

class ProgressBar
{
public:
    /// @param[in] enabled false (e.g. --quiet) draws nothing; so does a stderr that is not a terminal.
    explicit ProgressBar(bool enabled);
    ~ProgressBar();

    /// Redraws at most every 50 ms (and always at 100 %).
    void update(double fraction, const std::string& stage);

    /// Erases the bar (before printing anything else).
    void clear();

private:
    bool active_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point last_{};
};

}  // namespace sky
