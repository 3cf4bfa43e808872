#include "core/log.h"

#include <atomic>
#include <cstdio>

namespace candela {
namespace {
std::atomic<LogLevel> g_level{LogLevel::kInfo};
const char* const kNames[] = {"debug", "info", "warn", "error"};
}  // namespace

void set_log_level(LogLevel level) { g_level = level; }
LogLevel log_level() { return g_level; }

void log_message(LogLevel level, const char* fmt, ...) {
  if (level < g_level.load(std::memory_order_relaxed)) return;
  // Format into a stack buffer and write once, so lines from the input and
  // render threads do not interleave.
  char line[1024];
  int n = std::snprintf(line, sizeof line, "candela: %s: ", kNames[static_cast<int>(level)]);
  va_list ap;
  va_start(ap, fmt);
  const int m = std::vsnprintf(line + n, sizeof line - n - 1, fmt, ap);
  va_end(ap);
  n += m < 0 ? 0
             : (m < static_cast<int>(sizeof line) - n - 1 ? m
                                                          : static_cast<int>(sizeof line) - n - 2);
  line[n++] = '\n';
  std::fwrite(line, 1, n, stderr);
}

}  // namespace candela
