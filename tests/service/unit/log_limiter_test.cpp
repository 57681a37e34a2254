// SPDX-License-Identifier: MIT
// skyservice/service/log_limiter.h on a made-up clock: a line that comes now and then is always logged,
// a flood costs `burst` full lines and one count per window, and no occurrence is lost from the counts.
#include "skyservice/service/log_limiter.h"

#include <gtest/gtest.h>

using sky::LogLimiter;
using namespace std::chrono_literals;

namespace
{

const LogLimiter::Clock::time_point kT0{};

} // namespace

TEST(LogLimiter, OccasionalLinesAreAllLogged)
{
    LogLimiter limiter(5.0, 1);
    for (int k = 0; k < 10; ++k)
    {
        const auto t = kT0 + k * 6s; // one every 6 s: more than a window apart
        EXPECT_TRUE(limiter.admit(t)) << k;
        EXPECT_EQ(limiter.heldBack(t + 5s), 0u) << k;
    }
}

TEST(LogLimiter, AFloodIsOneLineThenOneCountPerWindow)
{
    LogLimiter limiter(5.0, 1);
    uint64_t logged = 0, counted = 0, summaries = 0;
    // 100000 occurrences over 20 s (one every 200 us), summaries asked for after each one.
    for (int k = 0; k < 100000; ++k)
    {
        const auto t = kT0 + k * 200us;
        logged += limiter.admit(t) ? 1 : 0;
        double spanS = 0;
        if (const uint64_t n = limiter.heldBack(t, &spanS))
        {
            counted += n;
            ++summaries;
            EXPECT_GE(spanS, 5.0);
            EXPECT_LT(spanS, 5.001);
        }
    }
    // The last window (15..20 s) ends with the flood: its count comes once, then nothing is left.
    const auto end = kT0 + 100000 * 200us;
    const uint64_t last = limiter.heldBack(end);
    EXPECT_GT(last, 0u);
    counted += last;
    EXPECT_EQ(limiter.heldBack(end + 5s), 0u);
    EXPECT_EQ(logged, 1u);
    EXPECT_EQ(logged + counted, 100000u) << "every occurrence is logged or counted";
    EXPECT_EQ(summaries, 3u); // at 5, 10 and 15 s, while the flood went on
}

TEST(LogLimiter, BurstLinesPerWindowAreLoggedInFull)
{
    LogLimiter limiter(5.0, 3);
    int logged = 0;
    for (int k = 0; k < 10; ++k)
        logged += limiter.admit(kT0 + k * 1ms) ? 1 : 0;
    EXPECT_EQ(logged, 3);
    EXPECT_EQ(limiter.heldBack(kT0 + 4s), 0u) << "the window has not ended";
    EXPECT_EQ(limiter.heldBack(kT0 + 5s), 7u);
    // The flood goes on in the next window: counted, not logged.
    EXPECT_FALSE(limiter.admit(kT0 + 6s));
    EXPECT_EQ(limiter.heldBack(kT0 + 10s), 1u);
    // A quiet window later, a line is logged in full again.
    EXPECT_TRUE(limiter.admit(kT0 + 16s));
}
