// Camera motion -> wind. MotionDetector differences small gray frames and
// finds where things move (the share of pixels that changed and their
// centroid); CameraWindLogic follows that centroid over a few frames and, when
// something sweeps across fast enough (a hand waved past the screen), emits a
// gust blowing the way it moved -- away from the hand -- as strong as the
// sweep was fast. Still frames, sensor noise and whole-frame changes (lights,
// exposure) give nothing. No I/O: the camera thread and tests feed it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "input/input_event.h"
#include "scene/input_spec.h"

namespace candela {

// Box-averages a gray image by an integer factor (dst: (w/f) x (h/f)).
void downsample_gray(const uint8_t* src, int width, int height, int factor, uint8_t* dst);

struct Motion {
  float area = 0;        // share of pixels that changed since the previous frame
  float centroid_x = 0;  // where they are, 0 (left edge of the image) .. 1 (right)
};

class MotionDetector {
 public:
  MotionDetector(int width, int height, int threshold = 20);
  // The next frame (width x height gray). The first frame gives no motion.
  Motion feed(const uint8_t* gray);
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_, threshold_;
  std::vector<uint8_t> previous_;
  bool has_previous_ = false;
};

class CameraWindLogic {
 public:
  CameraWindLogic(const InputSpec& spec, uint16_t source, const WindSpec& wind);
  // One analysed frame at t_ns; emits at most one gust.
  void frame(const Motion& motion, int64_t t_ns, InputEventSink& sink);
  uint64_t gusts() const { return gusts_; }
  double last_speed() const { return last_speed_; }  // image widths per second, signed

  static constexpr float kMinArea = 0.003f;  // below: noise
  static constexpr float kMaxArea = 0.6f;    // above: lights or exposure changed
  static constexpr double kMinSpeed = 0.35;  // image widths per second
  static constexpr int kTrack = 4;           // frames a sweep must be seen in

 private:
  struct Sample {
    int64_t t_ns;
    float x;
  };
  uint16_t source_;
  bool mirror_;
  double sensitivity_;
  Fixed strength_;
  int64_t cooldown_ns_;
  std::array<Sample, kTrack> track_{};
  int tracked_ = 0;
  bool moving_ = false;  // the previous frame had motion
  int64_t last_gust_ns_ = INT64_MIN / 2;
  uint64_t gusts_ = 0;
  double last_speed_ = 0;
};

}  // namespace candela
