#include "core/log.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace candela {
namespace {
std::atomic<LogLevel> g_level{LogLevel::kInfo};
std::atomic<uint64_t> g_errors{0};
// -1: not decided yet; 0 or 1.
std::atomic<int> g_journal{-1};
const char* const kNames[] = {"debug", "info", "warn", "error"};
// syslog priorities (LOG_DEBUG, LOG_INFO, LOG_WARNING, LOG_ERR).
const char* const kPriorities[] = {"<7>", "<6>", "<4>", "<3>"};

// systemd sets JOURNAL_STREAM=DEV:INODE for a stream connected to the
// journal; it is ours only if stderr is that very stream (systemd.exec(5)).
bool stderr_is_journal() {
  const char* v = std::getenv("JOURNAL_STREAM");
  if (!v || !*v) return false;
  unsigned long long dev = 0, ino = 0;
  if (std::sscanf(v, "%llu:%llu", &dev, &ino) != 2) return false;
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  return static_cast<unsigned long long>(st.st_dev) == dev &&
         static_cast<unsigned long long>(st.st_ino) == ino;
}
}  // namespace

void set_log_level(LogLevel level) { g_level = level; }
LogLevel log_level() { return g_level; }
uint64_t log_error_count() { return g_errors.load(std::memory_order_relaxed); }

bool log_to_journal() {
  int j = g_journal.load(std::memory_order_relaxed);
  if (j < 0) {
    j = stderr_is_journal() ? 1 : 0;
    g_journal.store(j, std::memory_order_relaxed);
  }
  return j == 1;
}
void set_log_to_journal(bool on) { g_journal.store(on ? 1 : 0, std::memory_order_relaxed); }

void log_message(LogLevel level, const char* fmt, ...) {
  if (level == LogLevel::kError) g_errors.fetch_add(1, std::memory_order_relaxed);
  if (level < g_level.load(std::memory_order_relaxed)) return;
  // Format into a stack buffer and write once, so lines from the input and
  // render threads do not interleave.
  char line[1024];
  const int l = static_cast<int>(level);
  int n = std::snprintf(line, sizeof line,
                        "%scandela: %s: ", log_to_journal() ? kPriorities[l] : "", kNames[l]);
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
