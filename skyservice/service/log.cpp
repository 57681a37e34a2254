// SPDX-License-Identifier: MIT
#include "skyservice/service/log.h"

#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <ctime>
#include <mutex>
#include <string>

namespace sky
{
namespace
{

std::atomic<int> gLevel{int(LogLevel::Info)};
std::mutex gMutex;

}  // namespace

bool parseLogLevel(std::string_view text, LogLevel& out)
{
    for (LogLevel l : {LogLevel::Error, LogLevel::Warn, LogLevel::Info, LogLevel::Debug})
    {
        if (text == logLevelName(l))
        {
            out = l;
            return true;
        }
    }
    return false;
}

const char* logLevelName(LogLevel level)
{
    switch (level)
    {
    case LogLevel::Error: return "error";
    case LogLevel::Warn: return "warn";
    case LogLevel::Info: return "info";
    case LogLevel::Debug: return "debug";
    }
    return "?";
}

void setLogLevel(LogLevel level) { gLevel.store(int(level)); }

bool logEnabled(LogLevel level) { return int(level) <= gLevel.load(); }

void logMessage(LogLevel level, const char* format, ...)
{
    if (!logEnabled(level))
        return;
    char text[2048];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    // One event, one line: control characters from clients (paths, names) are escaped as \xNN, so no
    // request can forge a log line.
    std::string line;
    line.reserve(sizeof text);
    for (const char* p = text; *p; ++p)
    {
        const auto c = static_cast<unsigned char>(*p);
        if (c < 0x20 || c == 0x7f)
        {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
            line += escaped;
        }
        else
            line += char(c);
    }

    timespec now{};
    clock_gettime(CLOCK_REALTIME, &now);
    tm utc{};
    gmtime_r(&now.tv_sec, &utc);
    char stamp[40];
    std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc);
    std::lock_guard<std::mutex> lock(gMutex);
    std::fprintf(stderr, "%s.%03dZ %-5s %s\n", stamp, int(now.tv_nsec / 1000000), logLevelName(level), line.c_str());
    std::fflush(stderr);
}

}  // namespace sky
