#include "app/frame_stats.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <nlohmann/json.hpp>

#include "core/json.h"

namespace candela {

double FrameStats::percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double rank = p / 100.0 * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (rank - lo);
}

std::string FrameStats::json(uint64_t frames, double cpu_seconds, int64_t missed,
                             const std::string& display, int width, int height,
                             const std::string& scene) const {
  // The first frames compile shaders and fill caches: leave them out of the
  // percentiles when there are enough frames.
  const size_t skip = intervals_ms_.size() > 20 ? 5 : 0;
  std::vector<double> iv(intervals_ms_.begin() + skip, intervals_ms_.end());
  std::vector<double> wk(work_ms_.begin() + skip, work_ms_.end());
  double mean = 0;
  for (double x : iv) mean += x;
  mean = iv.empty() ? 0 : mean / iv.size();
  nlohmann::ordered_json j;
  j["bench"] = "candela";
  j["scene"] = scene;
  j["display"] = display;
  j["width"] = width;
  j["height"] = height;
  j["frames"] = frames;
  j["frame_ms_p50"] = json_decimals(percentile(iv, 50), 3);
  j["frame_ms_p95"] = json_decimals(percentile(iv, 95), 3);
  j["frame_ms_p99"] = json_decimals(percentile(iv, 99), 3);
  j["frame_ms_mean"] = json_decimals(mean, 3);
  j["fps"] = json_decimals(mean > 0 ? 1000.0 / mean : 0.0, 1);
  j["work_ms_p50"] = json_decimals(percentile(wk, 50), 3);
  j["cpu_ms_per_frame"] = json_decimals(frames ? cpu_seconds * 1000.0 / frames : 0.0, 3);
  j["missed_vblanks"] =
      missed < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(missed);
  j["peak_rss_mb"] = json_decimals(peak_rss_mb(), 1);
  // Read here, once the run is over: the kiosk's start pays nothing for it.
  j["first_frame_ms"] =
      first_presented_
          ? nlohmann::ordered_json(json_decimals(
                std::chrono::duration<double, std::milli>(*first_presented_ - process_start_time())
                    .count(),
                1))
          : nlohmann::ordered_json(nullptr);
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::chrono::steady_clock::time_point process_start_time() {
  const auto now = std::chrono::steady_clock::now();
  // /proc/self/stat's 22nd field: the start in clock ticks since boot (on
  // CLOCK_BOOTTIME). The 2nd, the command name, may hold spaces: count
  // fields after its closing parenthesis.
  char buf[1024] = {};
  FILE* f = std::fopen("/proc/self/stat", "r");
  if (!f) return now;
  const size_t n = std::fread(buf, 1, sizeof buf - 1, f);
  std::fclose(f);
  buf[n] = '\0';
  const char* p = std::strrchr(buf, ')');
  unsigned long long start_ticks = 0;
  if (!p || std::sscanf(
                p + 1,
                " %*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %*u %*u %*d %*d %*d %*d %*d %*d %llu",
                &start_ticks) != 1)
    return now;
  timespec boot{};
  const long hz = sysconf(_SC_CLK_TCK);
  if (hz <= 0 || clock_gettime(CLOCK_BOOTTIME, &boot) != 0) return now;
  const double age_s = boot.tv_sec + boot.tv_nsec * 1e-9 - static_cast<double>(start_ticks) / hz;
  if (!(age_s >= 0 && age_s < 1e6)) return now;
  return now - std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                   std::chrono::duration<double>(age_s));
}

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

double peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss / 1024.0;
}

}  // namespace candela
