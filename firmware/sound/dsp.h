// The synthesiser's building blocks: a white-noise source and small filters.
// Float, per sample, no allocation. Samples are bit-identical for the same
// seed and build (-ffp-contract=off); which events happen when is decided in
// integers (event_clock.h), so that part holds on any CPU.
#pragma once

#include <cmath>
#include <cstdint>

namespace candela::dsp {

inline constexpr int kSampleRate = 48000;
inline constexpr float kPi = 3.14159265358979f;

// xorshift64* (period 2^64 - 1: at 48 kHz it never comes round).
class WhiteNoise {
 public:
  explicit WhiteNoise(uint64_t seed) : s_(seed ? seed : 0x9E3779B97F4A7C15ULL) {}
  // Uniform in [-1, 1).
  float next() {
    s_ ^= s_ >> 12;
    s_ ^= s_ << 25;
    s_ ^= s_ >> 27;
    const uint64_t r = s_ * 0x2545F4914F6CDD1DULL;
    return static_cast<float>(static_cast<int32_t>(r >> 32)) * (1.0f / 2147483648.0f);
  }

 private:
  uint64_t s_;
};

// y += a (x - y): a first-order low-pass; x - y is its high-pass.
class OnePole {
 public:
  OnePole() = default;
  explicit OnePole(float cutoff_hz) { set_cutoff(cutoff_hz); }
  void set_cutoff(float hz) { a_ = 1.0f - std::exp(-2.0f * kPi * hz / kSampleRate); }
  // The coefficient that makes an envelope follow its target in `seconds`.
  static float for_seconds(float seconds) {
    return 1.0f - std::exp(-1.0f / (seconds * kSampleRate));
  }
  float low(float x) { return y_ += a_ * (x - y_); }
  float high(float x) { return x - low(x); }
  float value() const { return y_; }

 private:
  float a_ = 1.0f;
  float y_ = 0.0f;
};

// RBJ biquad band-pass (constant 0 dB peak gain), direct form I.
class BandPass {
 public:
  void set(float centre_hz, float q) {
    const float w = 2.0f * kPi * centre_hz / kSampleRate;
    const float alpha = std::sin(w) / (2.0f * q);
    const float a0 = 1.0f + alpha;
    b0_ = alpha / a0;
    a1_ = -2.0f * std::cos(w) / a0;
    a2_ = (1.0f - alpha) / a0;
  }
  void reset() { x1_ = x2_ = y1_ = y2_ = 0.0f; }
  float run(float x) {
    const float y = b0_ * (x - x2_) - a1_ * y1_ - a2_ * y2_;
    x2_ = x1_;
    x1_ = x;
    y2_ = y1_;
    y1_ = y;
    return y;
  }

 private:
  float b0_ = 0, a1_ = 0, a2_ = 0;
  float x1_ = 0, x2_ = 0, y1_ = 0, y2_ = 0;
};

// Smooth saturation for the output stage: x - x^3 / 6.75 up to |x| = 1.5,
// where it reaches 1 with zero slope; 1 beyond. Odd, monotonic, y ~ x when small.
inline float soft_clip(float x) {
  if (x >= 1.5f) return 1.0f;
  if (x <= -1.5f) return -1.0f;
  return x - x * x * x * (1.0f / 6.75f);
}

}  // namespace candela::dsp
