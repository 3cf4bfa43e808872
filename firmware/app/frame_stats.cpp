#include "app/frame_stats.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

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
  char buf[1024];
  char missed_s[32];
  if (missed < 0)
    std::snprintf(missed_s, sizeof missed_s, "null");
  else
    std::snprintf(missed_s, sizeof missed_s, "%lld", static_cast<long long>(missed));
  double mean = 0;
  for (double x : iv) mean += x;
  mean = iv.empty() ? 0 : mean / iv.size();
  std::string esc;
  for (char c : scene) {
    if (c == '"' || c == '\\') esc += '\\';
    esc += c;
  }
  std::snprintf(
      buf, sizeof buf,
      "{\"bench\":\"candela\",\"scene\":\"%s\",\"display\":\"%s\",\"width\":%d,\"height\":%d,"
      "\"frames\":%llu,\"frame_ms_p50\":%.3f,\"frame_ms_p95\":%.3f,\"frame_ms_p99\":%.3f,"
      "\"frame_ms_mean\":%.3f,\"fps\":%.1f,\"work_ms_p50\":%.3f,\"cpu_ms_per_frame\":%.3f,"
      "\"missed_vblanks\":%s,\"peak_rss_mb\":%.1f}",
      esc.c_str(), display.c_str(), width, height, static_cast<unsigned long long>(frames),
      percentile(iv, 50), percentile(iv, 95), percentile(iv, 99), mean,
      mean > 0 ? 1000.0 / mean : 0.0, percentile(wk, 50),
      frames ? cpu_seconds * 1000.0 / frames : 0.0, missed_s, peak_rss_mb());
  return buf;
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
