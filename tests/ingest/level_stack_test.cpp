// SPDX-License-Identifier: MIT
// Fields on pressure levels (pressure_altitude.h): levels that view the decoded fields instead of copying
// them, and the samplers for one pressure over every cell, which must give exactly LevelStack::at() and
// pressureToAltitudeM() whatever levels are missing.
#include "weather_ingest/pressure_altitude.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace sky
{
namespace
{

bool sameFloat(float a, float b)
{
    return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(LevelStack, ViewedLevelsAreNotCopied)
{
    std::vector<float> at850(4, 1500.0f), at500(4, 5600.0f);
    LevelStack s;
    s.addLevelView(50000, at500.data(), at500.size());
    s.addLevelView(85000, at850.data(), at850.size());
    s.addLevel(70000, std::vector<float>(4, 3000.0f));
    ASSERT_EQ(s.levelCount(), 3u);
    EXPECT_EQ(s.pressurePa(0), 85000); // sorted surface first
    EXPECT_EQ(s.level(0), at850.data());
    at850[2] = 1400.0f; // the stack sees the field it views
    EXPECT_EQ(s.at(2, 85000, true), 1400.0f);
    const std::vector<float> all = s.concatenated();
    ASSERT_EQ(all.size(), 12u);
    EXPECT_EQ(all[2], 1400.0f);
    EXPECT_EQ(all[4], 3000.0f);
    EXPECT_EQ(all[11], 5600.0f);
    std::vector<float> again(4, 1450.0f);
    s.addLevelView(85000, again.data(), again.size()); // a repeated pressure replaces the level
    EXPECT_EQ(s.levelCount(), 3u);
    EXPECT_EQ(s.at(0, 85000, true), 1450.0f);
}

TEST(LevelStack, SamplersGiveExactlyWhatAtGives)
{
    constexpr size_t kCells = 400;
    const double levelsPa[] = {100000, 92500, 85000, 70000, 50000, 30000};
    std::mt19937 random(23);
    std::uniform_real_distribution<float> height(-100.0f, 12000.0f);
    std::bernoulli_distribution missing(0.3);
    std::vector<std::vector<float>> fields;
    for (size_t k = 0; k < std::size(levelsPa); ++k)
    {
        std::vector<float> f(kCells);
        for (size_t c = 0; c < kCells; ++c)
            f[c] = c < 20 || missing(random) ? NAN : height(random); // the first 20 cells: no level at all
        fields.push_back(std::move(f));
    }
    LevelStack s;
    for (size_t k : {3, 0, 5, 1, 4, 2}) // any order
        s.addLevelView(levelsPa[k], fields[k].data(), kCells);

    size_t compared = 0, interpolated = 0;
    for (const double p : {110000.0, 100000.0, 96000.0, 85000.0, 60000.0, 30000.0, 20000.0, 1000.0})
        for (const bool extrapolate : {false, true})
        {
            const LevelSampler sample(s, p, extrapolate);
            const AltitudeAtPressure altitude(s, p);
            for (size_t c = 0; c < kCells; ++c)
            {
                const float expected = s.at(c, p, extrapolate);
                EXPECT_TRUE(sameFloat(sample(c), expected))
                    << p << " Pa, cell " << c << ": " << sample(c) << " vs " << expected;
                EXPECT_TRUE(sameFloat(altitude(c), pressureToAltitudeM(s, c, p))) << p << " Pa, cell " << c;
                ++compared;
                interpolated += std::isfinite(expected) ? 1u : 0u;
            }
        }
    EXPECT_GT(interpolated, compared / 2);
    // No geopotential at all: the standard atmosphere, as pressureToAltitudeM gives it.
    const LevelStack none;
    EXPECT_EQ(AltitudeAtPressure(none, 85000)(0), pressureToAltitudeM(none, 0, 85000));
    EXPECT_TRUE(std::isnan(LevelSampler(none, 85000, true)(0)));
}

} // namespace
} // namespace sky
