// SPDX-License-Identifier: MIT
// A bound on how often one log line is written. A line that a peer can make the daemon write (a CIGI
// datagram, a control request, a connection) must not let that peer fill the disk: the first `burst`
// occurrences in a window are logged in full, the rest are counted and reported as one summary line per
// window ("cigi: host changed 12345 times in the last 5 s ..."), so a flood costs a few lines every few
// seconds however fast it comes. Not thread-safe: each limiter belongs to one thread or one mutex.
#pragma once

#include <chrono>
#include <cstdint>

namespace sky
{

class LogLimiter
{
  public:
    using Clock = std::chrono::steady_clock;

    /// `windowS`: the window's length (seconds, > 0); `burst`: lines logged in full per window (>= 1).
    explicit LogLimiter(double windowS = 5.0, uint32_t burst = 1);

    /// One occurrence at `now`: true when it is to be logged in full, false when it is only counted.
    bool admit(Clock::time_point now);

    /// The occurrences counted (not logged) since the last summary, once the window they fell in has
    /// ended; 0 otherwise. A non-zero answer is the caller's cue to log one summary line: the count is
    /// reset and a new window begins in which further occurrences are counted again. `spanS` (optional)
    /// gets the time the count covers (seconds, at least windowS()).
    uint64_t heldBack(Clock::time_point now, double* spanS = nullptr);

    /// The window's length (seconds), for the summary line.
    double windowS() const { return windowS_; }

  private:
    double windowS_;
    Clock::duration window_;
    uint32_t burst_;
    Clock::time_point windowStart_{};
    bool started_ = false;
    uint32_t logged_ = 0; ///< lines logged in full in the current window
    uint64_t held_ = 0;   ///< occurrences counted since the last summary
};

} // namespace sky
