#include "elements/eigenflame/flame_shape.h"

#include <algorithm>

#include "model/flame_model.h"

namespace candela {

void SampledSpline::fit(std::span<const float> v) {
  n_ = std::min(static_cast<int>(v.size()), kMax);
  for (int i = 0; i < n_; ++i) v_[i] = v[static_cast<size_t>(i)], m_[i] = 0;
  if (n_ < 3) return;
  // Equal spacing h: h m_{i-1} + 4 h m_i + h m_{i+1} = 6 (v_{i+1} - 2 v_i + v_{i-1}) / h, m_0 =
  // m_{n-1} = 0.
  const float h = 1.0f / n_;
  std::array<float, kMax> b{}, r{};
  b[0] = 1;
  for (int i = 1; i + 1 < n_; ++i) {
    b[i] = 4 * h;
    r[i] = 6 * (v_[i + 1] - 2 * v_[i] + v_[i - 1]) / h;
  }
  b[n_ - 1] = 1;
  for (int i = 1; i < n_; ++i) {  // forward elimination (a_i = h inside, 0 at the ends)
    const float a = i + 1 < n_ ? h : 0.0f, c_prev = i - 1 > 0 ? h : 0.0f;
    const float k = a / b[i - 1];
    b[i] -= k * c_prev;
    r[i] -= k * r[i - 1];
  }
  m_[n_ - 1] = r[n_ - 1] / b[n_ - 1];
  for (int i = n_ - 1; i-- > 0;) {
    const float c = i > 0 && i + 1 < n_ ? h : 0.0f;
    m_[i] = (r[i] - c * m_[i + 1]) / b[i];
  }
}

float SampledSpline::operator()(float t) const {
  if (n_ == 1) return v_[0];
  const float h = 1.0f / n_;
  const float t0 = 0.5f * h, tn = (n_ - 0.5f) * h;
  if (t <= t0) {
    const float slope = (v_[1] - v_[0]) / h - h * (2 * m_[0] + m_[1]) / 6;
    return v_[0] + slope * (t - t0);
  }
  if (t >= tn) {
    const float slope = (v_[n_ - 1] - v_[n_ - 2]) / h + h * (m_[n_ - 2] + 2 * m_[n_ - 1]) / 6;
    return v_[n_ - 1] + slope * (t - tn);
  }
  const int i = std::min(n_ - 2, static_cast<int>((t - t0) / h));
  const float ti = (i + 0.5f) * h;
  const float A = (ti + h - t) / h, B = 1 - A;
  return A * v_[i] + B * v_[i + 1] +
         ((A * A * A - A) * m_[i] + (B * B * B - B) * m_[i + 1]) * h * h / 6;
}

FlameShapeModel FlameShapeModel::from(const model::FlameModel& m) {
  FlameShapeModel s;
  s.np_ = m.flames.np;
  s.nw_ = m.flames.nw;
  s.ne_ = m.flames.ne;
  s.frame_w_ = static_cast<float>(m.width());
  s.frame_h_ = static_cast<float>(m.height());
  // base_y and span joined the format after version 1's first models: read
  // them from the metadata with the builder's defaults.
  const auto& info = m.file().info();
  s.base_y_ = 0.92f * s.frame_h_;
  if (auto it = info.find("learning_flames"); it != info.end() && it->is_object()) {
    if (auto b = it->find("base_y"); b != it->end() && b->is_number()) s.base_y_ = b->get<float>();
    if (auto sp = it->find("span"); sp != it->end() && sp->is_number()) s.span_ = sp->get<float>();
  }
  return s;
}

void FlameShapeModel::pose(std::span<const float> x, float bend, FlamePose& pose) const {
  std::array<float, SampledSpline::kMax> path{}, width{};
  const int np = std::min(np_, SampledSpline::kMax), nw = std::min(nw_, SampledSpline::kMax);
  const float height = std::max(4.0f, x[static_cast<size_t>(np_ + nw_)]);
  for (int i = 0; i < np; ++i) {
    const float h = (i + 0.5f) / np;
    path[i] = x[static_cast<size_t>(i)] + bend * h * frame_h_;
  }
  for (int i = 0; i < nw; ++i) width[i] = x[static_cast<size_t>(np_ + i)];
  SampledSpline p, w;
  p.fit({path.data(), static_cast<size_t>(np)});
  w.fit({width.data(), static_cast<size_t>(nw)});
  for (int r = 0; r <= FlamePose::kShapeRows; ++r) {
    const float t = static_cast<float>(r) / FlamePose::kShapeRows;
    pose.shape[static_cast<size_t>(2 * r)] = (p(t) - 0.5f * frame_w_) / frame_h_;
    pose.shape[static_cast<size_t>(2 * r + 1)] = 2 * span_ * std::max(1.0f, w(t)) / frame_h_;
  }
  pose.deform = true;
  pose.base = (frame_h_ - base_y_) / frame_h_;
  pose.height_factor = height / frame_h_;
}

}  // namespace candela
