// Logging to stderr (journald picks it up under systemd). One line per
// message, prefixed with the level, so a kiosk's log reads well.
#pragma once

#include <cstdarg>

namespace candela {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void set_log_level(LogLevel level);
LogLevel log_level();
void log_message(LogLevel level, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

#define CANDELA_LOG(level, ...) ::candela::log_message(level, __VA_ARGS__)
#define LOG_DEBUG(...) CANDELA_LOG(::candela::LogLevel::kDebug, __VA_ARGS__)
#define LOG_INFO(...) CANDELA_LOG(::candela::LogLevel::kInfo, __VA_ARGS__)
#define LOG_WARN(...) CANDELA_LOG(::candela::LogLevel::kWarn, __VA_ARGS__)
#define LOG_ERROR(...) CANDELA_LOG(::candela::LogLevel::kError, __VA_ARGS__)

}  // namespace candela
