// Logging to stderr (journald picks it up under systemd). One line per
// message, prefixed with the level, so a kiosk's log reads well. When stderr
// is the journal ($JOURNAL_STREAM names stderr's device and inode, as
// systemd sets it), each line starts with its syslog priority as
// sd-daemon(3) prefixes do ("<3>" error, "<4>" warn, "<6>" info, "<7>"
// debug), so `journalctl -p warning -u candela` shows warnings and errors.
#pragma once

#include <cstdarg>
#include <cstdint>

namespace candela {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void set_log_level(LogLevel level);
LogLevel log_level();
void log_message(LogLevel level, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
// Errors logged so far (whatever the log level shows): `state` reports it.
uint64_t log_error_count();
// Whether lines carry the "<N>" priority prefix: decided once, on the first
// line, from $JOURNAL_STREAM against stderr; tests may force it.
bool log_to_journal();
void set_log_to_journal(bool on);

#define CANDELA_LOG(level, ...) ::candela::log_message(level, __VA_ARGS__)
#define LOG_DEBUG(...) CANDELA_LOG(::candela::LogLevel::kDebug, __VA_ARGS__)
#define LOG_INFO(...) CANDELA_LOG(::candela::LogLevel::kInfo, __VA_ARGS__)
#define LOG_WARN(...) CANDELA_LOG(::candela::LogLevel::kWarn, __VA_ARGS__)
#define LOG_ERROR(...) CANDELA_LOG(::candela::LogLevel::kError, __VA_ARGS__)

}  // namespace candela
