// SPDX-License-Identifier: MIT
#include "client_demo/utc_time.h"

#include <cmath>
#include <cstdio>
#include <ctime>

namespace demo
{

bool parseUtc(const std::string& text, double& unixTimeS)
{
    int year = 0, month = 0, day = 0, hour = 0, minute = 0;
    double second = 0.0;
    int consumed = 0;
    if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%n", &year, &month, &day, &hour, &minute, &second,
                    &consumed) != 6)
        return false;
    const std::string rest = text.substr(size_t(consumed));
    if (!(rest.empty() || rest == "Z") || month < 1 || month > 12 || day < 1 || day > 31 || hour > 23 ||
        minute > 59 || second < 0.0 || second >= 61.0)
        return false;
    std::tm tm{};
    tm.tm_year = year - 1900;
    tm.tm_mon = month - 1;
    tm.tm_mday = day;
    tm.tm_hour = hour;
    tm.tm_min = minute;
    tm.tm_sec = 0;
    unixTimeS = double(timegm(&tm)) + second;
    return true;
}

std::string formatUtc(double unixTimeS)
{
    const auto t = time_t(std::floor(unixTimeS));
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

}  // namespace demo
