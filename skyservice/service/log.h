// SPDX-License-Identifier: MIT
// The daemon's log: one line per event on stderr, "2026-06-21T12:00:00.123Z warn  message", filtered
// by level (error < warn < info < debug). Thread-safe; lines never interleave.
#pragma once

#include <string>
#include <string_view>

namespace sky
{

enum class LogLevel : int
{
    Error = 0,
    Warn = 1,
    Info = 2,
    Debug = 3,
};

/// "error", "warn", "info" or "debug"; false for anything else.
bool parseLogLevel(std::string_view text, LogLevel& out);
const char* logLevelName(LogLevel level);

/// Messages above `level` are dropped. Default Info.
void setLogLevel(LogLevel level);
bool logEnabled(LogLevel level);

/// printf-style; the newline is added.
void logMessage(LogLevel level, const char* format, ...) __attribute__((format(printf, 2, 3)));

#define SKY_LOG_ERROR(...) ::sky::logMessage(::sky::LogLevel::Error, __VA_ARGS__)
#define SKY_LOG_WARN(...) ::sky::logMessage(::sky::LogLevel::Warn, __VA_ARGS__)
#define SKY_LOG_INFO(...) ::sky::logMessage(::sky::LogLevel::Info, __VA_ARGS__)
#define SKY_LOG_DEBUG(...) ::sky::logMessage(::sky::LogLevel::Debug, __VA_ARGS__)

}  // namespace sky
