// SPDX-License-Identifier: MIT
#include "weather_ingest/civil_time.h"

namespace sky
{

namespace
{

// Reads n decimal digits at text[pos]; false if any is not a digit.
bool readDigits(const std::string& text, size_t pos, size_t n, int& value)
{
    if (pos + n > text.size())
        return false;
    value = 0;
    for (size_t i = pos; i < pos + n; ++i)
    {
        char c = text[i];
        if (c < '0' || c > '9')
            return false;
        value = value * 10 + (c - '0');
    }
    return true;
}

bool fail(std::string& error, const std::string& text, const std::string& why)
{
    error = "invalid UTC time '" + text + "': " + why;
    return false;
}

}  // namespace

bool parseIso8601Utc(const std::string& text, int64_t& unixTimeS, std::string& error)
{
    const char* shape = "expected YYYY-MM-DDThh:mm:ss[.fff](Z|+hh:mm|-hh:mm), e.g. 2026-06-21T12:00:00Z";
    int year, month, day, hour, minute, second;
    if (!readDigits(text, 0, 4, year) || text.size() < 19 || text[4] != '-' || !readDigits(text, 5, 2, month) ||
        text[7] != '-' || !readDigits(text, 8, 2, day) || (text[10] != 'T' && text[10] != 't') ||
        !readDigits(text, 11, 2, hour) || text[13] != ':' || !readDigits(text, 14, 2, minute) || text[16] != ':' ||
        !readDigits(text, 17, 2, second))
        return fail(error, text, shape);
    size_t pos = 19;
    if (pos < text.size() && (text[pos] == '.' || text[pos] == ','))
    {
        size_t start = ++pos;
        while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9')
            ++pos;
        if (pos == start)
            return fail(error, text, "no digits after the decimal mark");
    }
    int offsetMin = 0;
    if (pos == text.size())
        return fail(error, text, "no time zone (local time is ambiguous): append 'Z' for UTC");
    if ((text[pos] == 'Z' || text[pos] == 'z') && pos + 1 == text.size())
    {
        offsetMin = 0;
    }
    else if (text[pos] == '+' || text[pos] == '-')
    {
        int offH, offM;
        if (text.size() != pos + 6 || !readDigits(text, pos + 1, 2, offH) || text[pos + 3] != ':' ||
            !readDigits(text, pos + 4, 2, offM))
            return fail(error, text, "time zone offset must be +hh:mm or -hh:mm");
        if (offH > 14 || offM > 59)
            return fail(error, text, "time zone offset out of range (at most 14:00)");
        offsetMin = (offH * 60 + offM) * (text[pos] == '-' ? -1 : 1);
    }
    else
    {
        return fail(error, text, shape);
    }
    if (year < 1900 || year > 2100)
        return fail(error, text, "year " + std::to_string(year) + " outside the supported range [1900, 2100]");
    if (month < 1 || month > 12)
        return fail(error, text, "month " + std::to_string(month) + " outside [1, 12]");
    if (!isCivilDate(year, unsigned(month), unsigned(day)))
        return fail(error, text, "day " + std::to_string(day) + " does not exist in that month");
    if (hour > 23)
        return fail(error, text, "hour " + std::to_string(hour) + " outside [0, 23]");
    if (minute > 59)
        return fail(error, text, "minute " + std::to_string(minute) + " outside [0, 59]");
    if (second == 60)
        return fail(error, text, "leap second :60 cannot be represented in Unix time");
    if (second > 59)
        return fail(error, text, "second " + std::to_string(second) + " outside [0, 59]");
    unixTimeS = unixTimeFromCivil(year, month, day, hour, minute, second) - int64_t(offsetMin) * 60;
    error.clear();
    return true;
}

}  // namespace sky
