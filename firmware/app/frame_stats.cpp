#include "app/frame_stats.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
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
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
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
