#include "flame_drivers/arp_driver.h"

#include <algorithm>

#include "core/error.h"
#include "model/flame_model.h"

namespace candela {

ArpView ArpView::of(const model::LearningFlamesModel& flames) {
  ArpView v;
  v.dim = flames.dim;
  v.order = flames.order;
  v.A = flames.A;
  v.d = flames.d;
  v.B = flames.B;
  v.training = flames.params;
  return v;
}

float ArpProcess::gaussian(Pcg32& rng) {
  int64_t sum = 0;
  for (int i = 0; i < 12; ++i) sum += rng.next_u32() >> 8;  // 24-bit uniforms
  sum -= int64_t{6} << 24;                                  // mean 0, variance 1 (x 2^48)
  return static_cast<float>(sum) * (1.0f / 16777216.0f);
}

ArpProcess::ArpProcess(const ArpView& view, uint64_t seed)
    : v_(view), dim_(view.dim), order_(view.order), rng_(seed, 0xa2b) {
  if (dim_ < 1 || dim_ > kMaxDim || order_ < 1 || order_ > kMaxOrder)
    throw RuntimeError("arp: unsupported dimension or order");
  const int t = view.frames();
  if (t < order_) throw RuntimeError("arp: fewer training frames than the process order");
  for (int i = 0; i < dim_; ++i) {
    float lo = view.training[static_cast<size_t>(i)], hi = lo;
    for (int f = 1; f < t; ++f) {
      const float x = view.training[static_cast<size_t>(f) * dim_ + i];
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    const float half = 0.5f * (hi - lo);
    lo_[i] = lo - half;
    hi_[i] = hi + half;
  }
  const int start = static_cast<int>(rng_.below(static_cast<uint32_t>(t - order_ + 1)));
  for (int k = 0; k < order_; ++k)  // x_[0] = the latest of the K frames
    for (int i = 0; i < dim_; ++i)
      x_[k][i] = view.training[static_cast<size_t>(start + order_ - 1 - k) * dim_ + i];
}

std::span<const float> ArpProcess::step() {
  const int d = dim_;
  for (int j = 0; j < d; ++j) w_[j] = gaussian(rng_);
  std::array<float, kMaxDim> next{};
  for (int i = 0; i < d; ++i) {
    float y = 0.0f;
    for (int k = 0; k < order_; ++k) {
      const float* a = v_.A.data() + (static_cast<size_t>(k) * d + i) * d;
      float s = 0.0f;
      for (int j = 0; j < d; ++j) s = s + a[j] * x_[k][j];
      y = y + s;
    }
    y = y + v_.d[i];
    const float* b = v_.B.data() + static_cast<size_t>(i) * d;
    float n = 0.0f;
    for (int j = 0; j < d; ++j) n = n + b[j] * w_[j];
    y = y + n;
    if (!(y >= lo_[i])) y = lo_[i], ++clamped_;  // also catches NaN
    if (y > hi_[i]) y = hi_[i], ++clamped_;
    next[i] = y;
  }
  for (int k = order_ - 1; k > 0; --k) x_[k] = x_[k - 1];
  x_[0] = next;
  return state();
}

}  // namespace candela
