#include "pca_view.h"

#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>

#include "elements/eigenflame/eigenflame.h"
#include "gl/gles.h"
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
  return {size_.x / 2 + x1 * r, size_.y / 2 - y2 * r};
}

void PcaView::draw_tracks(const Session& s) {
  const int w = static_cast<int>(size_.x), h = static_cast<int>(size_.y);
  if (!cache_.get() || cached_size_.x != size_.x || cached_size_.y != size_.y) {
    cache_ = make_texture();
    glBindTexture(GL_TEXTURE_2D, cache_.get());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    cache_fbo_ = make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, cache_fbo_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cache_.get(), 0);
  }
  if (!cache_list_) cache_list_ = std::make_unique<ImDrawList>(ImGui::GetDrawListSharedData());
  ImDrawList* list = cache_list_.get();
  list->_ResetForNewFrame();
  list->PushTextureID(ImGui::GetIO().Fonts->TexID);
  list->PushClipRect(ImVec2(0, 0), size_);

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
  for (size_t i = 0; i < points_.size(); ++i) screen_[i] = project(points_[i]);
  // Each clip's track, in its colour.
  for (size_t i = 0; i + 1 < points_.size(); ++i)
    if (clip_[i] == clip_[i + 1])
      list->AddLine(screen_[i], screen_[i + 1], clip_colour(clip_[i], 200), 1.5f);
  // A story's path: its transitions (jumps between model frames) in white.
  if (s.ok() && s.has_story()) {
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
  list->PopClipRect();
  list->PopTextureID();

  ImDrawData dd;
  ImDrawList* lists[1] = {list};
  dd.Valid = true;
  dd.CmdLists = lists;
  dd.CmdListsCount = 1;
  dd.TotalVtxCount = list->VtxBuffer.Size;
  dd.TotalIdxCount = list->IdxBuffer.Size;
  dd.DisplayPos = ImVec2(0, 0);
  dd.DisplaySize = size_;
  dd.FramebufferScale = ImVec2(1, 1);
  GLint bound = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &bound);
  glBindFramebuffer(GL_FRAMEBUFFER, cache_fbo_.get());
  glViewport(0, 0, w, h);
  glClearColor(12 / 255.0f, 12 / 255.0f, 16 / 255.0f, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(&dd);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(bound));
  cached_yaw_ = yaw_;
  cached_pitch_ = pitch_;
  cached_zoom_ = zoom_;
  cached_size_ = size_;
}

void PcaView::draw(ImDrawList* list, ImVec2 origin, ImVec2 size, const Session& s) {
  origin_ = origin;
  size_ = ImVec2(std::floor(std::max(size.x, 1.0f)), std::floor(std::max(size.y, 1.0f)));
  if (!cache_.get() || cached_size_.x != size_.x || cached_size_.y != size_.y ||
      cached_yaw_ != yaw_ || cached_pitch_ != pitch_ || cached_zoom_ != zoom_)
    draw_tracks(s);
  const ImVec2 end(origin.x + size_.x, origin.y + size_.y);
  list->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(cache_.get())), origin, end,
                 ImVec2(0, 1), ImVec2(1, 0));
  if (!s.ok()) return;
  list->PushClipRect(origin, end, true);
  auto at = [&](ImVec2 p) { return ImVec2(origin.x + p.x, origin.y + p.y); };
  // The current frame: where the timeline is, and where the edited flame is.
  const int mf = s.model_frame(s.frame());
  if (mf >= 0)
    list->AddCircle(at(screen_[static_cast<size_t>(mf)]), 7, IM_COL32(255, 255, 255, 255), 16, 2);
  list->AddCircleFilled(at(project(of_weights(s.shown().data()))), 5, IM_COL32(255, 240, 120, 255),
                        16);
  // Legend: clip names in their colours.
  const auto& clips = s.model().model->clips;
  ImVec2 p(origin.x + 8, origin.y + 8);
  for (size_t c = 0; c < clips.size() && c < 16; ++c) {
    list->AddRectFilled(ImVec2(p.x, p.y + 4), ImVec2(p.x + 10, p.y + 12),
                        clip_colour(static_cast<int>(c)));
    list->AddText(ImVec2(p.x + 14, p.y), IM_COL32(220, 220, 220, 255), clips[c].name.c_str());
    p.y += 16;
  }
  if (s.has_story())
    list->AddText(ImVec2(p.x, p.y), IM_COL32(255, 255, 255, 200), "story's joints (white)");
  list->PopClipRect();
}

int PcaView::pick(ImVec2 p) const {
  int best = -1;
  float best_d2 = 12.0f * 12.0f;
  for (size_t i = 0; i < screen_.size(); ++i) {
    const float dx = screen_[i].x - p.x, dy = screen_[i].y - p.y;
    const float d2 = dx * dx + dy * dy;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace candela::studio
