// Frame timing for --bench: preallocated, so measuring adds no allocation.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace candela {

class FrameStats {
 public:
  // Statistics cover at most this many frames (the first ones): 16 MB, whatever --frames says.
  static constexpr size_t kMaxFrames = size_t{1} << 20;
  explicit FrameStats(size_t capacity = 1 << 16) {
    intervals_ms_.reserve(std::min(capacity, kMaxFrames));
    work_ms_.reserve(std::min(capacity, kMaxFrames));
  }
  // interval: present-to-present; work: begin of frame to end of present.
  void add(double interval_ms, double work_ms) {
    if (intervals_ms_.size() < intervals_ms_.capacity()) {
      intervals_ms_.push_back(interval_ms);
      work_ms_.push_back(work_ms);
    }
  }
  size_t count() const { return intervals_ms_.size(); }
  static double percentile(std::vector<double> v, double p);
  // One JSON line: frames, frame_ms_p50/p95/p99, work_ms_p50, cpu_ms_per_frame,
  // missed_vblanks (null if unknown), peak_rss_mb, and the context given.
  std::string json(uint64_t frames, double cpu_seconds, int64_t missed_vblanks,
                   const std::string& display, int width, int height,
                   const std::string& scene) const;

 private:
  std::vector<double> intervals_ms_, work_ms_;
};

double process_cpu_seconds();
double peak_rss_mb();

}  // namespace candela
