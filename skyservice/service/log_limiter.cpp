// SPDX-License-Identifier: MIT
#include "skyservice/service/log_limiter.h"

#include <algorithm>

namespace sky
{

LogLimiter::LogLimiter(double windowS, uint32_t burst)
    : windowS_(windowS > 0 ? windowS : 1.0),
      window_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(windowS_))),
      burst_(std::max(burst, 1u))
{
}

bool LogLimiter::admit(Clock::time_point now)
{
    // A quiet window (nothing held back) lets the next occurrence through in full: a line that comes
    // now and then is always logged as it is.
    if (!started_ || (held_ == 0 && now - windowStart_ >= window_))
    {
        started_ = true;
        windowStart_ = now;
        logged_ = 0;
    }
    if (logged_ < burst_)
    {
        ++logged_;
        return true;
    }
    ++held_;
    return false;
}

uint64_t LogLimiter::heldBack(Clock::time_point now, double* spanS)
{
    if (held_ == 0 || now - windowStart_ < window_)
        return 0;
    const uint64_t n = held_;
    if (spanS)
        *spanS = std::chrono::duration<double>(now - windowStart_).count();
    held_ = 0;
    // The flood may go on: the new window starts spent, so what comes in it is counted, not logged.
    windowStart_ = now;
    logged_ = burst_;
    return n;
}

} // namespace sky
