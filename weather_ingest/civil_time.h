// SPDX-License-Identifier: MIT
// The proleptic Gregorian calendar and UTC times: days from a civil date and back, the days of a month,
// seconds since 1970-01-01T00:00:00Z, and their ISO 8601 form. The one place the project converts between
// dates and Unix time (weather valid times, CIGI's date, the service's clock, files, logs). The calendar
// functions are inline (the standard library's std::chrono calendar) so that libraries which link nothing,
// such as the CIGI layer, use them too; the ISO 8601 parser is in civil_time.cpp (sky_weather).
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace sky
{

/// A date of the proleptic Gregorian calendar.
struct CivilDate
{
    int year = 1970;
    unsigned month = 1;  ///< 1-12
    unsigned day = 1;    ///< 1-31

    bool operator==(const CivilDate&) const = default;
};

/// True when the date exists (month 1-12, day within the month).
constexpr bool isCivilDate(int year, unsigned month, unsigned day)
{
    return std::chrono::year_month_day{std::chrono::year{year}, std::chrono::month{month}, std::chrono::day{day}}
        .ok();
}

/// Days in a month (1-12) of a year: 28 to 31.
constexpr unsigned daysInMonth(int year, unsigned month)
{
    using namespace std::chrono;
    return unsigned(year_month_day_last{std::chrono::year{year}, month_day_last{std::chrono::month{month}}}.day());
}

/// Days from 1970-01-01 to a date (negative before it). The date should exist (isCivilDate); one that does
/// not counts on from the month's end (31 April is 1 May).
constexpr int64_t daysFromCivil(int year, unsigned month, unsigned day)
{
    using namespace std::chrono;
    const sys_days days{year_month_day{std::chrono::year{year}, std::chrono::month{month}, std::chrono::day{1}}};
    return int64_t(days.time_since_epoch().count()) + int64_t(day) - 1;
}

/// The date `days` days after 1970-01-01.
constexpr CivilDate civilFromDays(int64_t days)
{
    using namespace std::chrono;
    const year_month_day ymd{sys_days{std::chrono::days{days}}};
    return {int(ymd.year()), unsigned(ymd.month()), unsigned(ymd.day())};
}

/// Seconds since 1970-01-01T00:00:00Z of a UTC date and time of day.
constexpr int64_t unixTimeFromCivil(int year, int month, int day, int hour, int minute, int second)
{
    return daysFromCivil(year, unsigned(month), unsigned(day)) * 86400 + int64_t(hour) * 3600 +
           int64_t(minute) * 60 + second;
}

/// Formats a Unix time as "YYYY-MM-DDThh:mm:ssZ".
inline std::string formatIso8601Utc(int64_t unixTimeS)
{
    const int64_t days = unixTimeS >= 0 ? unixTimeS / 86400 : -((-unixTimeS + 86399) / 86400);  // floor
    const int64_t secondsOfDay = unixTimeS - days * 86400;
    const CivilDate date = civilFromDays(days);
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%04d-%02u-%02uT%02d:%02d:%02dZ", date.year, date.month, date.day,
                  int(secondsOfDay / 3600), int(secondsOfDay / 60 % 60), int(secondsOfDay % 60));
    return buffer;
}

/**
 * Parses an ISO 8601 UTC time: "2026-06-21T12:00:00Z", with optional fractional seconds
 * ("12:00:00.250Z", truncated to whole seconds) and a "Z" or numeric offset ("+00:00", "-07:00").
 *
 * @param[in] text the time.
 * @param[out] unixTimeS the time in Unix seconds (UTC), set only on success.
 * @param[out] error on failure, a message naming what is wrong.
 * @return false for anything else: no time zone (local time is ambiguous), basic format, a date that
 *   does not exist, a leap second (":60", Unix time cannot hold it), years outside 1900-2100.
 **********************************************************************/
bool parseIso8601Utc(const std::string& text, int64_t& unixTimeS, std::string& error);

}  // namespace sky
