// Frame timing for --bench: preallocated, so measuring adds no allocation.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace candela {

// When this process started, on the steady clock (from the kernel's record of
// its start, so loading and linking count too); now when that is unknown.
std::chrono::steady_clock::time_point process_start_time();

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
  // The first frame was presented at `at` (json() reports the start-up time:
  // from the process's start, process_start_time(), to then).
  void first_presented(std::chrono::steady_clock::time_point at) {
    if (!first_presented_) first_presented_ = at;
  }
  static double percentile(std::vector<double> v, double p);
  // One JSON line: frames, frame_ms_p50/p95/p99, work_ms_p50, cpu_ms_per_frame,
  // missed_vblanks (null if unknown), peak_rss_mb, first_frame_ms (null if no
  // frame was presented), and the context given.
  std::string json(uint64_t frames, double cpu_seconds, int64_t missed_vblanks,
                   const std::string& display, int width, int height,
                   const std::string& scene) const;

 private:
  std::vector<double> intervals_ms_, work_ms_;
  std::optional<std::chrono::steady_clock::time_point> first_presented_;
};

double process_cpu_seconds();
double peak_rss_mb();

}  // namespace candela
