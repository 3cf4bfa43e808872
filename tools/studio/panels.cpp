#include "panels.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "elements/eigenflame/eigenflame.h"
#include "model/flame_model.h"
#include "pca_view.h"
#include "reports_view.h"
#include "session.h"
#include "story/story_plan.h"
#include "x11_platform.h"

namespace candela::studio {
namespace {

// The panes tile the window, so none draws a background: the frame is cleared
// to the panes' colour (kPaneColour) once, which on llvmpipe saves blending
// the whole window again (fragment work is most of a frame there).
constexpr ImGuiWindowFlags kFixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                    ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings |
                                    ImGuiWindowFlags_NoBringToFrontOnFocus |
                                    ImGuiWindowFlags_NoBackground;

void place(ImVec2 pos, ImVec2 size) {
  ImGui::SetNextWindowPos(pos, ImGuiCond_Always);
  ImGui::SetNextWindowSize(size, ImGuiCond_Always);
}

PixelRect rect_of(ImVec2 pos, ImVec2 size) {
  return {static_cast<int>(pos.x), static_cast<int>(pos.y), static_cast<int>(size.x),
          static_cast<int>(size.y)};
}

// The transfer function: a ramp preview over its colour stops, a row of
// place handles under it (drag one along the ramp: it stays between its
// neighbours), each stop's colour a handle (click: a colour picker), stops
// added or removed at the end (evenly spaced ones stay evenly spaced).
template <typename UndoPoint>
bool transfer_editor(Look& look, UndoPoint& undo_point, Session& s, PixelRect& places_row) {
  bool changed = false;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 14, hw = 6, hh = 10;
  const size_t n = look.transfer.size();
  if (look.transfer_at.size() != n) look.transfer_at = Look::even_places(n);
  std::vector<float>& p = look.transfer_at;
  auto col = [](const std::array<float, 3>& c) {
    return ImGui::ColorConvertFloat4ToU32(ImVec4(c[0], c[1], c[2], 1));
  };
  // Below the first stop the first colour, above the last the last.
  dl->AddRectFilled(at, ImVec2(at.x + w * p[0], at.y + h), col(look.transfer[0]));
  dl->AddRectFilled(ImVec2(at.x + w * p[n - 1], at.y), ImVec2(at.x + w, at.y + h),
                    col(look.transfer[n - 1]));
  for (size_t i = 0; i + 1 < n; ++i) {
    const float x0 = at.x + w * p[i], x1 = at.x + w * p[i + 1];
    if (x1 > x0)
      dl->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + h), col(look.transfer[i]),
                                  col(look.transfer[i + 1]), col(look.transfer[i + 1]),
                                  col(look.transfer[i]));
  }
  ImGui::Dummy(ImVec2(w, h));
  const bool even = look.evenly_spaced();
  // The place handles: a triangle under each stop's place.
  const ImVec2 row = ImGui::GetCursorScreenPos();
  places_row = rect_of(row, ImVec2(w, hh));
  for (size_t i = 0; i < n; ++i) {
    const float x = row.x + w * p[i];
    ImGui::SetCursorScreenPos(ImVec2(x - hw, row.y));
    ImGui::PushID(static_cast<int>(i));
    ImGui::InvisibleButton("place", ImVec2(2 * hw, hh));
    undo_point();
    if (ImGui::IsItemActive()) {
      const float lo = i > 0 ? p[i - 1] : 0.0f, hi = i + 1 < n ? p[i + 1] : 1.0f;
      const float v = std::clamp((ImGui::GetIO().MousePos.x - row.x) / w, lo, hi);
      if (v != p[i]) p[i] = v, changed = true;
    }
    if (ImGui::IsItemHovered() || ImGui::IsItemActive())
      ImGui::SetTooltip("stop %u at %.3f", static_cast<unsigned>(i), p[i]);
    const bool lit = ImGui::IsItemHovered() || ImGui::IsItemActive();
    dl->AddTriangleFilled(ImVec2(x, row.y), ImVec2(x - hw, row.y + hh), ImVec2(x + hw, row.y + hh),
                          lit ? IM_COL32(255, 255, 255, 255) : IM_COL32(170, 170, 170, 255));
    ImGui::PopID();
  }
  ImGui::SetCursorScreenPos(row);
  ImGui::Dummy(ImVec2(w, hh));
  for (size_t i = 0; i < n; ++i) {
    char id[32];
    std::snprintf(id, sizeof id, "##stop%u", static_cast<unsigned>(i));
    if (i > 0) ImGui::SameLine();
    changed |= ImGui::ColorEdit3(id, look.transfer[i].data(), ImGuiColorEditFlags_NoInputs);
    undo_point();
  }
  ImGui::SameLine();
  if (n < Look::kMaxStops && ImGui::SmallButton("+")) {
    s.begin_edit();
    look.transfer.push_back(look.transfer.back());
    if (even) {
      p = Look::even_places(n + 1);
    } else {
      p.push_back(1.0f);
    }
    changed = true;
  }
  ImGui::SameLine();
  if (n > 2 && ImGui::SmallButton("-")) {
    s.begin_edit();
    look.transfer.pop_back();
    if (even) {
      p = Look::even_places(n - 1);
    } else {
      p.pop_back();
    }
    changed = true;
  }
  ImGui::SameLine();
  if (!even && ImGui::SmallButton("even")) {
    s.begin_edit();
    p = Look::even_places(n);
    changed = true;
  }
  return changed;
}

}  // namespace

Layout Layout::of(int width, int height) {
  Layout l;
  const float w = static_cast<float>(std::max(width, 200));
  const float h = static_cast<float>(std::max(height, 150));
  l.title_h = ImGui::GetFontSize() + 2 * ImGui::GetStyle().FramePadding.y;
  const float cw = std::min(360.0f, std::max(240.0f, w * 0.28f));
  const float rest = w - cw;
  l.controls_pos = {0, 0};
  l.controls_size = {cw, h};
  // The story timeline under the flame and the tracks.
  const float th = std::floor(std::min(230.0f, h * 0.4f));
  l.flame_pos = {cw, 0};
  l.flame_size = {std::floor(rest * 0.45f), h - th};
  l.pca_pos = {cw + l.flame_size.x, 0};
  l.pca_size = {rest - l.flame_size.x, h - th};
  l.timeline_pos = {cw, h - th};
  l.timeline_size = {rest, th};
  return l;
}

Panels::Panels() { std::snprintf(path_buf_, sizeof path_buf_, "%s", scene_path.c_str()); }

bool save_scene_reporting(Session& s, const std::string& path) {
  try {
    s.save_scene(path);
    s.status = "saved " + path;
    return true;
  } catch (const std::exception& e) {
    s.status = e.what();
    return false;
  }
}

bool save_story_reporting(Session& s, const std::string& path) {
  try {
    s.save_story(path);
    s.status = "saved " + path;
    return true;
  } catch (const std::exception& e) {
    s.status = e.what();
    return false;
  }
}

void Panels::draw(Session& s, FlameView* flame, PcaView& pca, ReportsView& reports,
                  double frame_ms) {
  const ImGuiIO& io = ImGui::GetIO();
  const Layout l =
      Layout::of(static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y));
  if (io.KeyCtrl && ImGui::IsKeyPressed(ImGuiKey_Z, false) && !io.WantTextInput) {
    if (s.undo()) s.status = "undone";
  }
  if (io.KeyCtrl && ImGui::IsKeyPressed(letter_key('q'), false)) quit_ = true;
  // Space plays/pauses, the arrows step (not while a text field has the keys).
  if (s.ok() && !io.WantTextInput && !io.KeyCtrl) {
    if (ImGui::IsKeyPressed(ImGuiKey_Space, false)) s.playing = !s.playing;
    if (ImGui::IsKeyPressed(ImGuiKey_LeftArrow, true)) s.step(-1);
    if (ImGui::IsKeyPressed(ImGuiKey_RightArrow, true)) s.step(1);
  }

  if (!s.ok()) {
    draw_error(s, l);
  } else {
    place(l.controls_pos, l.controls_size);
    ImGui::Begin("Studio", nullptr, kFixed);
    draw_controls(s, reports, frame_ms);
    ImGui::End();
  }

  // The flame, as the runtime renders it.
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  place(l.flame_pos, l.flame_size);
  ImGui::Begin("Flame", nullptr, kFixed | ImGuiWindowFlags_NoScrollbar);
  {
    const ImVec2 at = ImGui::GetCursorScreenPos();
    if (flame && flame->texture()) {
      const ImVec2 sz(static_cast<float>(flame->width()), static_cast<float>(flame->height()));
      ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(flame->texture())), sz,
                   ImVec2(0, 1), ImVec2(1, 0));
      const PixelRect r = flame->image_rect();
      drawn_.flame_image = {static_cast<int>(at.x) + r.x, static_cast<int>(at.y) + r.y, r.w, r.h};
      drawn_.flame_view = rect_of(at, sz);
    }
  }
  ImGui::End();

  // The PCA tracks.
  place(l.pca_pos, l.pca_size);
  ImGui::Begin("PCA tracks: w0, w1, w2 (drag: rotate, wheel: zoom, click: jump)", nullptr,
               kFixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  {
    const ImVec2 at = ImGui::GetCursorScreenPos();
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 sz(std::max(avail.x, 1.0f), std::max(avail.y, 1.0f));
    ImGui::InvisibleButton("pca", sz);
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f))
      pca.rotate(io.MouseDelta.x, io.MouseDelta.y);
    if (ImGui::IsItemHovered() && io.MouseWheel != 0) pca.zoom(io.MouseWheel);
    if (ImGui::IsItemDeactivated() && io.MouseDragMaxDistanceSqr[0] < 4.0f) {
      const int f = pca.pick(ImVec2(io.MousePos.x - at.x, io.MousePos.y - at.y));
      if (f >= 0 && s.ok()) {
        s.seek_model_frame(f);
        s.playing = false;
      }
    }
    pca.draw(ImGui::GetWindowDrawList(), at, sz, s);
    drawn_.pca = rect_of(at, sz);
  }
  ImGui::End();
  ImGui::PopStyleVar();

  drawn_.timeline = drawn_.joint_steps = {};
  if (s.ok()) {
    place(l.timeline_pos, l.timeline_size);
    ImGui::Begin("Story timeline", nullptr, kFixed);
    draw_timeline(s);
    ImGui::End();
  }
}

namespace {

// A segment's label: clip and range, "walk N s" / "arp N s", repeats.
std::string segment_label(const story::SegmentSpec& g) {
  char buf[160];
  if (g.kind == story::SegmentKind::kFrames) {
    const std::string to = g.to >= 0 ? std::to_string(g.to) : "end";
    std::snprintf(buf, sizeof buf, "%s %d-%s", g.clip.empty() ? "frames" : g.clip.c_str(), g.from,
                  to.c_str());
  } else {
    std::snprintf(buf, sizeof buf, "%s %g s", g.kind == story::SegmentKind::kWalk ? "walk" : "arp",
                  g.seconds);
  }
  std::string s = buf;
  if (g.repeat > 1) s += " x" + std::to_string(g.repeat);
  return s;
}

int segment_of(const std::string& piece_key) {  // "segment[2] repeat 2" -> 2
  return std::atoi(piece_key.c_str() + piece_key.find('[') + 1);
}

ImU32 segment_colour(int i, bool lit) {
  float r, g, b;
  ImGui::ColorConvertHSVtoRGB(std::fmod(0.08f + 0.17f * static_cast<float>(i), 1.0f), 0.55f,
                              lit ? 0.75f : 0.5f, r, g, b);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, 1));
}

}  // namespace

void Panels::draw_timeline(Session& s) {
  const model::FlameModel& m = *s.model().model;
  if (!s.story()) {
    ImGui::TextDisabled("No story: the model's clips play one after another.");
    if (ImGui::Button("New story from the model's clips")) s.new_story();
    return;
  }
  // A field typed into is one undo step until no widget is active.
  if (!ImGui::IsAnyItemActive()) s.end_gesture();
  const story::StoryDesc& d = *s.story();
  const story::StoryPlan& p = *s.plan();
  const int n = static_cast<int>(d.segments.size());
  selected = std::clamp(selected, 0, n - 1);

  // The blocks: each piece (a segment or one of its repeats) as wide as its
  // planned frames, each joint between them, the play position a white line.
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float w = std::max(ImGui::GetContentRegionAvail().x, 1.0f), h = 40, jh = 16;
  const float per = w / static_cast<float>(std::max(p.frames(), 1));
  drawn_.timeline = rect_of(at, ImVec2(w, h + jh));
  ImGui::InvisibleButton("blocks", ImVec2(w, h + jh));
  const bool clicked = ImGui::IsItemClicked();
  const float mx = ImGui::GetIO().MousePos.x;
  for (const auto& pc : p.pieces()) {
    const int seg = segment_of(pc.key);
    const float x0 = at.x + per * static_cast<float>(pc.first);
    const float x1 = x0 + per * static_cast<float>(pc.count);
    if (clicked && mx >= x0 && mx < x1) selected = seg;
    dl->AddRectFilled(ImVec2(x0, at.y), ImVec2(x1, at.y + h), segment_colour(seg, seg == selected));
    if (seg == selected)
      dl->AddRect(ImVec2(x0, at.y), ImVec2(x1, at.y + h), IM_COL32(255, 220, 80, 255), 0, 0, 2);
    const std::string label = segment_label(d.segments[static_cast<size_t>(seg)]);
    dl->PushClipRect(ImVec2(x0 + 2, at.y), ImVec2(x1 - 2, at.y + h), true);
    dl->AddText(ImVec2(x0 + 4, at.y + 4), IM_COL32(255, 255, 255, 255), label.c_str());
    dl->PopClipRect();
  }
  for (const auto& j : p.joints()) {
    const int seg = segment_of(j.key);
    const float x0 = at.x + per * static_cast<float>(j.first);
    const float x1 =
        std::max(x0 + 3, at.x + per * static_cast<float>(std::min(j.last, p.frames())));
    if (clicked && mx >= x0 && mx < x1) selected = seg;
    const bool over = j.seam_ratio > p.seam_bound();
    dl->AddRectFilled(ImVec2(x0, at.y + h), ImVec2(x1, at.y + h + jh),
                      over ? IM_COL32(230, 70, 50, 255) : IM_COL32(220, 220, 220, 255));
    // The method and the seam ratio beside the joint (to its left at the window's end).
    char t[48];
    std::snprintf(t, sizeof t, "%s %.2f", story::method_name(j.method), j.seam_ratio);
    const float tw = ImGui::CalcTextSize(t).x;
    const float tx = x1 + 2 + tw > at.x + w ? x0 - 2 - tw : x1 + 2;
    dl->AddLine(ImVec2(x0, at.y), ImVec2(x0, at.y + h), IM_COL32(0, 0, 0, 255));
    dl->AddText(ImVec2(tx, at.y + h + 1),
                over ? IM_COL32(230, 70, 50, 255) : IM_COL32(200, 200, 200, 255), t);
  }
  const float px = at.x + per * static_cast<float>(s.frame());
  dl->AddLine(ImVec2(px, at.y - 2), ImVec2(px, at.y + h + jh), IM_COL32(255, 255, 255, 255), 2);

  // The selected segment and the joint that enters it. Every edit below
  // re-plans the story and replaces `d` and `p`: what the rest of this frame
  // shows is copied from them first (a frame later it shows the edit).
  const story::SegmentSpec g = d.segments[static_cast<size_t>(selected)];
  const bool looped = d.loop;
  const float seam_bound = p.seam_bound();
  const int planned_frames = p.frames();
  ImGui::Text("segment %d: %s", selected, segment_label(g).c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("<") && selected > 0 && s.edit_story([&](story::StoryDesc& e) {
        std::swap(e.segments[static_cast<size_t>(selected)],
                  e.segments[static_cast<size_t>(selected - 1)]);
      }))
    --selected;
  ImGui::SameLine();
  if (ImGui::SmallButton(">") && selected + 1 < n && s.edit_story([&](story::StoryDesc& e) {
        std::swap(e.segments[static_cast<size_t>(selected)],
                  e.segments[static_cast<size_t>(selected + 1)]);
      }))
    ++selected;
  ImGui::SameLine();
  if (ImGui::SmallButton("delete") && n > 1)
    s.edit_story([&](story::StoryDesc& e) { e.segments.erase(e.segments.begin() + selected); });
  ImGui::SameLine();
  int repeat = g.repeat;
  ImGui::SetNextItemWidth(90);
  if (ImGui::InputInt("repeats", &repeat))
    s.edit_story(
        [&](story::StoryDesc& e) { e.segments[static_cast<size_t>(selected)].repeat = repeat; },
        "repeats");
  ImGui::SameLine();
  bool loop = looped;
  if (ImGui::Checkbox("loop", &loop)) s.edit_story([&](story::StoryDesc& e) { e.loop = loop; });

  story::TransitionSpec t = g.transition;
  static const char* methods[] = {"cut", "lowpass", "bridge", "grow"};
  int method = static_cast<int>(t.method);
  ImGui::SetNextItemWidth(100);
  if (ImGui::Combo("joint", &method, methods, 4)) {
    set_method(t, static_cast<story::Method>(method));
    s.edit_story(
        [&](story::StoryDesc& e) { e.segments[static_cast<size_t>(selected)].transition = t; });
  }
  bool changed = false;
  ImGui::SameLine();
  ImGui::PushItemWidth(90);
  if (t.method == story::Method::kLowpass) {
    changed |= ImGui::InputFloat3("kernel", t.kernel.data(), "%.3f");
    ImGui::SameLine();
    changed |= ImGui::InputInt("components", &t.components);
  } else if (t.method != story::Method::kCut) {
    changed |= ImGui::InputInt("steps", &t.steps);
    drawn_.joint_steps = rect_of(ImGui::GetItemRectMin(), ImGui::GetItemRectSize());
    ImGui::SameLine();
    changed |= ImGui::InputFloat("theta_min", &t.theta_min, 0, 0, "%.3g");
    ImGui::SameLine();
    changed |= ImGui::InputInt("reject_tail", &t.reject_tail);
  }
  ImGui::PopItemWidth();
  if (changed)
    s.edit_story(
        [&](story::StoryDesc& e) { e.segments[static_cast<size_t>(selected)].transition = t; },
        "joint");
  const float seam = s.joint_seam(selected);
  if (seam >= 0) {
    ImGui::TextColored(seam > seam_bound ? ImVec4(1, 0.4f, 0.3f, 1) : ImVec4(0.7f, 0.9f, 0.7f, 1),
                       "seam ratio %.2f (bound %.2f)", seam, seam_bound);
    ImGui::SameLine();
    if (ImGui::SmallButton("preview joint")) s.preview_joint(selected);
  }

  // Adding a segment at the end: a clip (and range) of the model, or seconds of walk / ARP.
  ImGui::SetNextItemWidth(140);
  if (ImGui::BeginCombo("##clip", clip_buf_[0] ? clip_buf_ : "(model frames)")) {
    for (const auto& c : m.clips)
      if (ImGui::Selectable(c.name.c_str()))
        std::snprintf(clip_buf_, sizeof clip_buf_, "%s", c.name.c_str());
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  ImGui::PushItemWidth(70);
  ImGui::InputInt("from", &add_from_, 0);
  ImGui::SameLine();
  ImGui::InputInt("to (-1: end)", &add_to_, 0);
  ImGui::SameLine();
  if (ImGui::Button("add clip"))
    s.edit_story([&](story::StoryDesc& e) {
      story::SegmentSpec a;
      a.clip = clip_buf_;
      a.from = std::max(0, add_from_);
      a.to = add_to_ < 0 ? -1 : add_to_;
      e.segments.push_back(a);
    });
  ImGui::SameLine();
  ImGui::InputFloat("s", &add_seconds_, 0, 0, "%.1f");
  ImGui::PopItemWidth();
  for (const auto k : {story::SegmentKind::kWalk, story::SegmentKind::kArp}) {
    ImGui::SameLine();
    if (ImGui::Button(k == story::SegmentKind::kWalk ? "add walk" : "add arp"))
      s.edit_story([&](story::StoryDesc& e) {
        story::SegmentSpec a;
        a.kind = k;
        a.seconds = add_seconds_;
        e.segments.push_back(a);
      });
  }
  ImGui::SetNextItemWidth(200);
  ImGui::InputText("##story", story_buf_, sizeof story_buf_);
  ImGui::SameLine();
  if (ImGui::Button("Save story")) save_story_reporting(s, story_buf_);
  ImGui::SameLine();
  if (ImGui::Button("Undo") && s.undo()) s.status = "undone";
  ImGui::SameLine();
  ImGui::TextDisabled("%d frames, %d segments", planned_frames, n);
  if (!s.status.empty()) ImGui::TextWrapped("%s", s.status.c_str());  // a refused edit says why
}

void Panels::draw_error(const Session& s, const Layout& l) {
  place(l.controls_pos, l.controls_size);
  ImGui::Begin("Studio", nullptr, kFixed);
  ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1),
                     s.story_failed() ? "Cannot play the story" : "Cannot open the model");
  ImGui::Separator();
  ImGui::PushTextWrapPos(0);
  ImGui::TextUnformatted(s.error().c_str());
  ImGui::Spacing();
  ImGui::TextDisabled(
      s.story_failed() ? "Fix the story (candela-tool story STORY --no-render) and open it again."
                       : "Fix the file (candela-tool inspect MODEL) and open it again.");
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void Panels::draw_controls(Session& s, ReportsView& reports, double frame_ms) {
  const model::FlameModel& m = *s.model().model;
  const Edits before = s.edits();  // what a widget's gesture undoes to
  drawn_.transfer_places = {};
  auto undo_point = [&] {
    if (ImGui::IsItemActivated()) s.begin_edit(before);
  };

  ImGui::TextUnformatted(s.model_name().c_str());
  ImGui::Text("%dx%d, %d components, %d frames, %zu clips", m.width(), m.height(), m.components(),
              m.frames(), m.clips.size());
  if (s.has_story()) ImGui::Text("story %s: %d frames", s.story_name().c_str(), s.frames());
  ImGui::Text("%.1f ms a frame", frame_ms);

  if (ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button(s.playing ? "Pause" : "Play")) s.playing = !s.playing;
    ImGui::SameLine();
    if (ImGui::ArrowButton("back", ImGuiDir_Left)) s.step(-1);
    ImGui::SameLine();
    if (ImGui::ArrowButton("forward", ImGuiDir_Right)) s.step(1);
    ImGui::SameLine();
    const int mf = s.model_frame(s.frame());
    const int clip = s.clip_of_frame(mf);
    ImGui::Text("%s", clip >= 0 ? m.clips[static_cast<size_t>(clip)].name.c_str() : "(transition)");
    int f = s.frame();
    if (ImGui::SliderInt("frame", &f, 0, std::max(0, s.frames() - 1))) {
      s.seek(f);
      s.playing = false;
    }
    ImGui::SliderFloat("speed", &s.speed, 0.05f, 8.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
    ImGui::Text("model frame %d", mf);
  }

  if (ImGui::CollapsingHeader("Colour", ImGuiTreeNodeFlags_DefaultOpen)) {
    Look look = s.edits().look;
    bool changed = false;
    bool use_transfer = look.transfer.size() >= 2;
    if (ImGui::RadioButton("HLS", !use_transfer) && use_transfer) {
      s.begin_edit();
      look.transfer.clear();
      changed = true;
    }
    ImGui::SameLine();
    if (ImGui::RadioButton("transfer function", use_transfer) && !use_transfer) {
      s.begin_edit();
      look.transfer = {{0, 0, 0}, {0.54f, 0.094f, 0}, {1, 0.5f, 0.125f}, {1, 0.94f, 0.75f}};
      changed = true;
    }
    if (look.transfer.size() >= 2) {
      changed |= transfer_editor(look, undo_point, s, drawn_.transfer_places);
    } else {
      changed |= ImGui::SliderFloat("hue", &look.hue, 0, 360, "%.0f deg");
      undo_point();
      // The hue of the brightest gray: follows the hue until moved.
      if (!look.has_hue_top) look.hue_top = look.hue;
      if (look.has_hue_top) {  // room for "= hue" after the label, as wide as the other rows
        const ImGuiStyle& st = ImGui::GetStyle();
        ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - ImGui::CalcTextSize("= hue").x -
                                st.FramePadding.x * 2 - st.ItemSpacing.x);
      }
      if (ImGui::SliderFloat("hue at top", &look.hue_top, 0, 360, "%.0f deg"))
        changed = look.has_hue_top = true;
      undo_point();
      if (look.has_hue_top) {
        ImGui::SameLine();
        if (ImGui::SmallButton("= hue")) {
          s.begin_edit();
          look.has_hue_top = false;
          changed = true;
        }
      }
      changed |= ImGui::SliderFloat("saturation", &look.saturation, 0, 1);
      undo_point();
    }
    changed |= ImGui::SliderFloat("brightness", &look.brightness, 0, 4);
    undo_point();
    changed |= ImGui::SliderFloat("glow radius", &look.glow_radius, 0, 0.5f);
    undo_point();
    changed |= ImGui::SliderFloat("glow strength", &look.glow_strength, 0, 4);
    undo_point();
    if (changed) s.set_look(look);
  }

  if (ImGui::CollapsingHeader("Save as scene", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::InputText("file", path_buf_, sizeof path_buf_);
    drawn_.scene_file = rect_of(ImGui::GetItemRectMin(), ImGui::GetItemRectSize());
    if (ImGui::Button("Save scene")) {
      scene_path = path_buf_;
      save_scene_reporting(s, scene_path);
    }
    ImGui::SameLine();
    if (ImGui::Button("Undo (Ctrl+Z)") && s.undo()) s.status = "undone";
    if (!s.status.empty()) ImGui::TextWrapped("%s", s.status.c_str());
  }

  if (open_reports) ImGui::SetNextItemOpen(true);
  open_reports = false;
  if (ImGui::CollapsingHeader("Reports")) reports.draw(ImGui::GetContentRegionAvail().x);

  if (ImGui::CollapsingHeader("Weights", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button("Reset weights")) s.reset_edits();
    float detail = s.edits().weights.detail_scale;
    if (ImGui::SliderFloat("detail scale", &detail, 0, 4, "x%.2f")) s.set_detail_scale(detail);
    undo_point();
    ImGui::TextDisabled("offsets in standard deviations of each weight");
    ImGui::BeginChild("weights", ImVec2(0, 0), false);
    for (int k = 0; k < s.shape_weights(); ++k) {
      float v = s.edits().weights.offset_sigma[static_cast<size_t>(k)];
      char label[16];
      std::snprintf(label, sizeof label, "w%d", k);
      if (ImGui::SliderFloat(label, &v, -5, 5, "%+.2f")) s.set_offset(k, v);
      undo_point();
    }
    ImGui::EndChild();
  }
}

}  // namespace candela::studio
