// SPDX-License-Identifier: MIT
#include "progress_bar.h"

#include <algorithm>
#include <cstdio>

#include <unistd.h>

namespace sky
{

ProgressBar::ProgressBar(bool enabled) : active_(enabled && isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() { clear(); }

void ProgressBar::update(double fraction, const std::string& stage)
{
    if (!active_)
        return;
    const auto now = std::chrono::steady_clock::now();
    if (fraction < 1.0 && drawn_ && now - last_ < std::chrono::milliseconds(50))
        return;
    last_ = now;
    constexpr int kWidth = 30;
    const double f = std::clamp(fraction, 0.0, 1.0);
    const int filled = static_cast<int>(f * kWidth);
    std::string bar(size_t(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r[%s] %3d%% %-40.40s", bar.c_str(), static_cast<int>(f * 100.0), stage.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::clear()
{
    if (!drawn_)
        return;
    std::fprintf(stderr, "\r%*s\r", 80, "");
    std::fflush(stderr);
    drawn_ = false;
}

}  // namespace sky
