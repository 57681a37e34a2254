// SPDX-License-Identifier: MIT
// The civil calendar and UTC times (weather_ingest/civil_time.h): days from a date and back against
// known dates and over 1600-2400, the days of each month, and the ISO 8601 parser and formatter.
#include "weather_ingest/civil_time.h"

#include <gtest/gtest.h>

#include <utility>

namespace
{

using namespace sky;

TEST(CivilTime, DaysFromCivilAtKnownDates)
{
    EXPECT_EQ(daysFromCivil(1970, 1, 1), 0);
    EXPECT_EQ(daysFromCivil(1969, 12, 31), -1);
    EXPECT_EQ(daysFromCivil(2000, 3, 1), 11017);   // the day after a 400-year leap day
    EXPECT_EQ(daysFromCivil(2026, 6, 21), 20625);  // 1782043200 s / 86400
    EXPECT_EQ(daysFromCivil(1600, 1, 1), -135140);
    EXPECT_EQ(unixTimeFromCivil(2026, 6, 21, 12, 0, 0), 1782043200);
    EXPECT_EQ(unixTimeFromCivil(2003, 10, 17, 19, 30, 30), 1066419030);
}

TEST(CivilTime, CivilFromDaysInvertsDaysFromCivil)
{
    for (int64_t days = daysFromCivil(1600, 1, 1); days <= daysFromCivil(2400, 12, 31); ++days)
    {
        const CivilDate d = civilFromDays(days);
        ASSERT_TRUE(isCivilDate(d.year, d.month, d.day)) << days;
        ASSERT_EQ(daysFromCivil(d.year, d.month, d.day), days) << d.year << "-" << d.month << "-" << d.day;
    }
    EXPECT_EQ(civilFromDays(0), (CivilDate{1970, 1, 1}));
    EXPECT_EQ(civilFromDays(11016), (CivilDate{2000, 2, 29}));
}

TEST(CivilTime, DaysInEachMonthAndLeapYears)
{
    const unsigned common[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    for (unsigned m = 1; m <= 12; ++m)
        EXPECT_EQ(daysInMonth(2026, m), common[m - 1]) << m;
    EXPECT_EQ(daysInMonth(2024, 2), 29u);
    EXPECT_EQ(daysInMonth(2000, 2), 29u);  // divisible by 400
    EXPECT_EQ(daysInMonth(2100, 2), 28u);  // divisible by 100 only
    EXPECT_TRUE(isCivilDate(2024, 2, 29));
    EXPECT_FALSE(isCivilDate(2026, 2, 29));
    EXPECT_FALSE(isCivilDate(2026, 4, 31));
    EXPECT_FALSE(isCivilDate(2026, 13, 1));
    EXPECT_FALSE(isCivilDate(2026, 1, 0));
}

TEST(CivilTime, ParsesValidIsoTimes)
{
    const std::pair<const char*, int64_t> cases[] = {
        {"2026-06-21T12:00:00Z", 1782043200},
        {"2026-06-21T12:00:00.750Z", 1782043200},  // fractional seconds are truncated
        {"2026-06-21T12:00:00,5Z", 1782043200},
        {"2026-06-21T12:00:00+00:00", 1782043200},
        {"2026-06-21t12:00:00z", 1782043200},
        {"2026-06-21T14:30:00+02:30", 1782043200},
        {"2003-10-17T12:30:30-07:00", 1066419030},
        {"1970-01-01T00:00:00Z", 0},
        {"2024-02-29T00:00:00Z", 1709164800},
        {"1969-12-31T23:59:59Z", -1},
    };
    for (const auto& [text, expected] : cases)
    {
        int64_t t = 12345;
        std::string error;
        EXPECT_TRUE(parseIso8601Utc(text, t, error)) << text << ": " << error;
        EXPECT_EQ(t, expected) << text;
    }
}

TEST(CivilTime, RejectsAmbiguousOrInvalidTimes)
{
    const std::pair<const char*, const char*> cases[] = {
        {"2026-06-21T12:00:00", "no time zone"},
        {"2026-06-21 12:00:00Z", "expected"},
        {"20260621T120000Z", "expected"},
        {"2026-06-21T12:00Z", "expected"},
        {"2026-02-30T00:00:00Z", "does not exist"},
        {"2100-02-29T00:00:00Z", "does not exist"},
        {"2026-13-01T00:00:00Z", "month 13"},
        {"2026-06-21T24:00:00Z", "hour 24"},
        {"2026-06-21T12:61:00Z", "minute 61"},
        {"2026-06-21T12:00:60Z", "leap second"},
        {"1850-01-01T00:00:00Z", "year 1850"},
        {"2026-06-21T12:00:00Zjunk", "expected"},
        {"2026-06-21T12:00:00.Z", "decimal"},
        {"2026-06-21T12:00:00+0200", "offset"},
        {"2026-06-21T12:00:00+15:00", "offset"},
        {"", "expected"},
    };
    for (const auto& [text, message] : cases)
    {
        int64_t t = 777;
        std::string error;
        EXPECT_FALSE(parseIso8601Utc(text, t, error)) << text;
        EXPECT_EQ(t, 777) << text;
        EXPECT_NE(error.find(message), std::string::npos) << text << " -> " << error;
    }
}

TEST(CivilTime, FormatsAndRoundTrips)
{
    EXPECT_EQ(formatIso8601Utc(0), "1970-01-01T00:00:00Z");
    EXPECT_EQ(formatIso8601Utc(-1), "1969-12-31T23:59:59Z");
    EXPECT_EQ(formatIso8601Utc(1782043200), "2026-06-21T12:00:00Z");
    for (int64_t t = -2000000000; t < 4000000000; t += 123456789)
    {
        int64_t back = 0;
        std::string error;
        ASSERT_TRUE(parseIso8601Utc(formatIso8601Utc(t), back, error)) << error;
        EXPECT_EQ(back, t);
    }
}

}  // namespace
