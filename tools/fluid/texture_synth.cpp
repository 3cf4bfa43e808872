#include "texture_synth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace candela::fluid {

Exemplar make_exemplar(const Image& photo, ControlChannel channel, int min_size) {
  if (photo.width < min_size || photo.height < min_size)
    throw std::invalid_argument(
        "photo: at least " + std::to_string(min_size) + "x" + std::to_string(min_size) +
        " pixels (got " + std::to_string(photo.width) + "x" + std::to_string(photo.height) + ")");
  const bool has_alpha = photo.channels == 2 || photo.channels == 4;
  if (channel == ControlChannel::kAuto)
    channel = has_alpha ? ControlChannel::kAlpha : ControlChannel::kLuminance;
  if (channel == ControlChannel::kAlpha && !has_alpha)
    throw std::invalid_argument("photo: --control alpha needs a photo with an alpha channel");
  Exemplar e;
  e.width = photo.width;
  e.height = photo.height;
  const size_t n = static_cast<size_t>(e.width) * e.height;
  e.rgb.resize(3 * n);
  e.control.resize(n);
  float maxc = 0.0f;
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const size_t k = static_cast<size_t>(y) * e.width + x;
      float rgb[3];
      float alpha = 1.0f;
      if (photo.channels <= 2) {
        rgb[0] = rgb[1] = rgb[2] = photo.at(x, y, 0) / 255.0f;
      } else {
        for (int c = 0; c < 3; ++c) rgb[c] = photo.at(x, y, c) / 255.0f;
      }
      if (has_alpha) alpha = photo.at(x, y, photo.channels - 1) / 255.0f;
      for (int c = 0; c < 3; ++c) e.rgb[3 * k + c] = rgb[c] * alpha;
      const float ctl =
          channel == ControlChannel::kAlpha
              ? alpha
              : 0.2126f * e.rgb[3 * k] + 0.7152f * e.rgb[3 * k + 1] + 0.0722f * e.rgb[3 * k + 2];
      e.control[k] = ctl;
      maxc = std::max(maxc, ctl);
    }
  if (maxc <= 0.0f)
    throw std::invalid_argument("photo: its control channel (alpha or luminance) is all zero");
  for (float& c : e.control) c /= maxc;
  return e;
}

void validate(const SynthParams& p) {
  if (p.neighbourhood < 3 || p.neighbourhood > 15 || p.neighbourhood % 2 == 0)
    throw std::invalid_argument("neighbourhood: an odd size in 3..15");
  if (p.random_candidates < 0 || p.random_candidates > 64)
    throw std::invalid_argument("random-candidates: 0..64");
  if (!std::isfinite(p.control_weight) || p.control_weight < 0.0)
    throw std::invalid_argument("control-weight: a number >= 0");
  if (p.passes < 1 || p.passes > 8) throw std::invalid_argument("passes: 1..8");
}

TextureSynthesizer::TextureSynthesizer(const Exemplar& photo, const SynthParams& params)
    : photo_(photo), params_(params), r_(params.neighbourhood / 2) {
  validate(params);
  pw_ = photo.width + 2 * r_;
  ph_ = photo.height + 2 * r_;
  prgb_.resize(3 * static_cast<size_t>(pw_) * ph_);
  pctl_.resize(static_cast<size_t>(pw_) * ph_);
  for (int y = 0; y < ph_; ++y)
    for (int x = 0; x < pw_; ++x) {
      const int sx = std::clamp(x - r_, 0, photo.width - 1);
      const int sy = std::clamp(y - r_, 0, photo.height - 1);
      const size_t s = static_cast<size_t>(sy) * photo.width + sx;
      const size_t d = static_cast<size_t>(y) * pw_ + x;
      for (int c = 0; c < 3; ++c) prgb_[3 * d + c] = photo.rgb[3 * s + c];
      pctl_[d] = photo.control[s];
    }
}

// SSD of the two L-shaped halves for photo pixel `cand` at output (px, py);
// stops early once it exceeds `best`.
float TextureSynthesizer::cost(int px, int py, int cand, const std::vector<float>& target, int w,
                               int h, float best) const {
  const int cx = cand % photo_.width + r_, cy = cand / photo_.width + r_;
  const float wc = static_cast<float>(params_.control_weight);
  float sum = 0.0f;
  for (int dy = -r_; dy <= r_; ++dy) {
    const int oy = py + dy;
    if (oy < 0 || oy >= h) continue;
    const float* prow = &prgb_[3 * (static_cast<size_t>(cy + dy) * pw_ + cx)];
    const float* crow = &pctl_[static_cast<size_t>(cy + dy) * pw_ + cx];
    const float* orow = &out_[3 * static_cast<size_t>(oy) * w];
    const float* trow = &target[static_cast<size_t>(oy) * w];
    for (int dx = -r_; dx <= r_; ++dx) {
      const int ox = px + dx;
      if (ox < 0 || ox >= w) continue;
      if (dy < 0 || (dy == 0 && dx < 0)) {  // upper L: colour
        const float* o = orow + 3 * ox;
        const float* q = prow + 3 * dx;
        const float a = o[0] - q[0], b = o[1] - q[1], c = o[2] - q[2];
        sum += a * a + b * b + c * c;
      } else {  // lower L: temperature vs the photo's control
        const float d = trow[ox] - crow[dx];
        sum += wc * d * d;
      }
    }
    if (sum > best) return sum;
  }
  return sum;
}

RgbImage TextureSynthesizer::synthesize(const std::vector<float>& target, int w, int h,
                                        Pcg32& rng) {
  if (w < 1 || h < 1 || target.size() != static_cast<size_t>(w) * h)
    throw std::invalid_argument("synthesize: the target must hold width*height values");
  const int n_photo = photo_.width * photo_.height;
  source_.resize(static_cast<size_t>(w) * h);
  out_.resize(3 * source_.size());
  auto set = [&](int x, int y, int src) {
    const size_t k = static_cast<size_t>(y) * w + x;
    source_[k] = src;
    for (int c = 0; c < 3; ++c) out_[3 * k + c] = photo_.rgb[3 * static_cast<size_t>(src) + c];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) set(x, y, static_cast<int>(rng.below(n_photo)));

  std::vector<int> cands;
  cands.reserve(static_cast<size_t>(params_.neighbourhood) * params_.neighbourhood +
                params_.random_candidates);
  for (int pass = 0; pass < params_.passes; ++pass) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        cands.clear();
        // Coherent candidates from the upper L (on later passes the whole
        // neighbourhood is synthesised, so all of it).
        for (int dy = -r_; dy <= (pass > 0 ? r_ : 0); ++dy)
          for (int dx = -r_; dx <= r_; ++dx) {
            if (pass == 0 && dy == 0 && dx >= 0) break;
            if (dx == 0 && dy == 0) continue;
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qx >= w || qy < 0 || qy >= h) continue;
            const int s = source_[static_cast<size_t>(qy) * w + qx];
            const int sx = s % photo_.width - dx, sy = s / photo_.width - dy;
            if (sx < 0 || sx >= photo_.width || sy < 0 || sy >= photo_.height) continue;
            const int c = sy * photo_.width + sx;
            if (std::find(cands.begin(), cands.end(), c) == cands.end()) cands.push_back(c);
          }
        for (int k = 0; k < params_.random_candidates; ++k)
          cands.push_back(static_cast<int>(rng.below(n_photo)));
        if (cands.empty()) cands.push_back(static_cast<int>(rng.below(n_photo)));
        float best = std::numeric_limits<float>::max();
        int best_c = cands.front();
        for (int c : cands) {
          const float e = cost(x, y, c, target, w, h, best);
          if (e < best) {
            best = e;
            best_c = c;
          }
        }
        set(x, y, best_c);
      }
  }
  RgbImage img;
  img.width = w;
  img.height = h;
  img.px = out_;
  return img;
}

}  // namespace candela::fluid
