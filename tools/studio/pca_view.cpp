#include "pca_view.h"

#include <algorithm>
#include <cmath>

#include "elements/eigenflame/eigenflame.h"
#include "model/flame_model.h"
#include "session.h"

namespace candela::studio {
namespace {

ImU32 clip_colour(int i, int alpha = 255) {
  static const ImU32 rgb[] = {0xff8c1a, 0x3fa7ff, 0x5ee05e, 0xff5ad2,
                              0xffe14d, 0x9e7bff, 0x4de8d9, 0xff6b6b};
  const ImU32 c = rgb[static_cast<unsigned>(i) % (sizeof rgb / sizeof rgb[0])];
  return IM_COL32((c >> 16) & 255, (c >> 8) & 255, c & 255, alpha);
}

}  // namespace

PcaView::PcaView(const Session& s) {
  if (!s.ok()) return;
  const model::FlameModel& m = *s.model().model;
  const int f = m.frames();
  dims_ = std::min(3, m.components());
  float spread = 0;
  for (int k = 0; k < dims_; ++k) spread = std::max(spread, s.sigma(k));
  norm_ = spread > 0 ? 1.0f / (2.5f * spread) : 1.0f;
  points_.reserve(static_cast<size_t>(f));
  clip_.reserve(static_cast<size_t>(f));
  for (int i = 0; i < f; ++i) {
    points_.push_back(of_weights(m.weights_of(i).data()));
    clip_.push_back(m.clip_of(i));
  }
  screen_.resize(points_.size());
}

PcaView::P3 PcaView::of_weights(const float* w) const {
  // Models with fewer than three components lie in a plane or on a line.
  return {dims_ > 0 ? w[0] * norm_ : 0.0f, dims_ > 1 ? w[1] * norm_ : 0.0f,
          dims_ > 2 ? w[2] * norm_ : 0.0f};
}

void PcaView::rotate(float dx, float dy) {
  yaw_ += dx * 0.01f;
  pitch_ = std::clamp(pitch_ + dy * 0.01f, -1.55f, 1.55f);
}

void PcaView::zoom(float steps) { zoom_ = std::clamp(zoom_ * std::pow(1.15f, steps), 0.1f, 20.0f); }

ImVec2 PcaView::project(P3 p) const {
  const float cy = std::cos(yaw_), sy = std::sin(yaw_);
  const float cp = std::cos(pitch_), sp = std::sin(pitch_);
  // Yaw about the vertical (w1) axis, then pitch about the screen's x axis.
  const float x1 = cy * p.x + sy * p.z, z1 = -sy * p.x + cy * p.z;
  const float y2 = cp * p.y - sp * z1, z2 = sp * p.y + cp * z1;
  const float persp = 1.0f / (1.0f + 0.15f * std::clamp(-z2 * zoom_, -3.0f, 3.0f));
  const float r = 0.45f * std::min(size_.x, size_.y) * zoom_ * persp;
  return {origin_.x + size_.x / 2 + x1 * r, origin_.y + size_.y / 2 - y2 * r};
}

void PcaView::draw(ImDrawList* list, ImVec2 origin, ImVec2 size, const Session& s) {
  origin_ = origin;
  size_ = ImVec2(std::max(size.x, 1.0f), std::max(size.y, 1.0f));
  list->PushClipRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), true);
  list->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y),
                      IM_COL32(12, 12, 16, 255));
  // Axes w0, w1, w2 (one unit = 2.5 standard deviations of the widest).
  const char* names[3] = {"w0", "w1", "w2"};
  const ImU32 axis_col[3] = {IM_COL32(230, 80, 80, 255), IM_COL32(80, 220, 80, 255),
                             IM_COL32(90, 140, 255, 255)};
  const ImVec2 o = project({0, 0, 0});
  for (int a = 0; a < 3; ++a) {
    P3 e{a == 0 ? 1.0f : 0.0f, a == 1 ? 1.0f : 0.0f, a == 2 ? 1.0f : 0.0f};
    const ImVec2 t = project(e);
    list->AddLine(o, t, axis_col[a], 1.0f);
    list->AddText(t, axis_col[a], names[a]);
  }
  if (!s.ok()) {
    list->PopClipRect();
    return;
  }
  for (size_t i = 0; i < points_.size(); ++i) screen_[i] = project(points_[i]);
  // Each clip's track, in its colour.
  for (size_t i = 0; i + 1 < points_.size(); ++i)
    if (clip_[i] == clip_[i + 1])
      list->AddLine(screen_[i], screen_[i + 1], clip_colour(clip_[i], 200), 1.5f);
  // A story's path: its transitions (frames no clip holds, and jumps) in white.
  if (s.has_story()) {
    ImVec2 prev{};
    int prev_mf = -2;
    for (int i = 0; i < s.frames(); ++i) {
      const int mf = s.model_frame(i);
      if (mf < 0) continue;  // low-passed frames: their neighbours draw the path
      const ImVec2 p = screen_[static_cast<size_t>(mf)];
      if (prev_mf >= 0 && mf != prev_mf + 1)
        list->AddLine(prev, p, IM_COL32(255, 255, 255, 150), 1.0f);
      prev = p;
      prev_mf = mf;
    }
  }
  // The current frame: where the timeline is, and where the edited flame is.
  const int mf = s.model_frame(s.frame());
  if (mf >= 0)
    list->AddCircle(screen_[static_cast<size_t>(mf)], 7, IM_COL32(255, 255, 255, 255), 16, 2);
  const ImVec2 now = project(of_weights(s.shown().data()));
  list->AddCircleFilled(now, 5, IM_COL32(255, 240, 120, 255), 16);
  // Legend: clip names in their colours.
  const auto& clips = s.model().model->clips;
  ImVec2 at(origin.x + 8, origin.y + 8);
  for (size_t c = 0; c < clips.size() && c < 16; ++c) {
    list->AddRectFilled(ImVec2(at.x, at.y + 4), ImVec2(at.x + 10, at.y + 12),
                        clip_colour(static_cast<int>(c)));
    list->AddText(ImVec2(at.x + 14, at.y), IM_COL32(220, 220, 220, 255), clips[c].name.c_str());
    at.y += 16;
  }
  list->PopClipRect();
}

int PcaView::pick(ImVec2 p) const {
  int best = -1;
  float best_d2 = 12.0f * 12.0f;
  for (size_t i = 0; i < screen_.size(); ++i) {
    const float dx = screen_[i].x - origin_.x - p.x, dy = screen_[i].y - origin_.y - p.y;
    const float d2 = dx * dx + dy * dy;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace candela::studio
