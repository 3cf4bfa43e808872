#include "studio.h"

#include <X11/Xlib.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <vector>

#include "app/frame_stats.h"
#include "core/error.h"
#include "core/image.h"
#include "core/log.h"
#include "display/display.h"
#include "flame_view.h"
#include "gl/gles.h"
#include "panels.h"
#include "pca_view.h"
#include "reports_view.h"
#include "script.h"
#include "session.h"
#include "x11_platform.h"

namespace candela::studio {
namespace {

class Events final : public DisplayEvents {
 public:
  explicit Events(X11Platform& p) : platform_(p) {}
  void on_key(Key) override {}
  bool on_x11_event(const XEvent& e) override { return platform_.handle(e); }

 private:
  X11Platform& platform_;
};

// ImGui's context and renderer for as long as the GL context lives.
struct ImGuiScope {
  ImGuiScope() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the layout is fixed: no imgui.ini in the user's folder
    ImGui::StyleColorsDark();
    if (!ImGui_ImplOpenGL3_Init("#version 300 es")) {
      ImGui::DestroyContext();
      throw RuntimeError("studio: Dear ImGui's OpenGL ES 3 renderer did not start");
    }
  }
  ~ImGuiScope() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext();
  }
};

void screenshot(const std::string& path, int w, int h) {
  std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4), flipped(rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  const size_t row = static_cast<size_t>(w) * 4;
  for (int y = 0; y < h; ++y)
    std::copy_n(rgba.data() + static_cast<size_t>(h - 1 - y) * row, row,
                flipped.data() + static_cast<size_t>(y) * row);
  Image img;
  img.width = w;
  img.height = h;
  img.channels = 3;
  img.pixels.resize(static_cast<size_t>(w) * h * 3);
  for (size_t i = 0, n = static_cast<size_t>(w) * h; i < n; ++i)
    for (int c = 0; c < 3; ++c) img.pixels[i * 3 + c] = flipped[i * 4 + c];
  write_png(path, img);
}

// A script's X input, sent now: the window backend reads it at the next poll.
void send(X11Platform& p, const ScriptFrame::XInput& in) {
  bool ok = true;
  switch (in.kind) {
    case ScriptFrame::XInput::kPress:
      ok = p.send_button(1, true, in.x, in.y);
      break;
    case ScriptFrame::XInput::kRelease:
      ok = p.send_button(1, false, in.x, in.y);
      break;
    case ScriptFrame::XInput::kMove:
      ok = p.send_motion(in.x, in.y);
      break;
    case ScriptFrame::XInput::kWheel:
      for (int i = 0; i < std::abs(in.steps) && ok; ++i) {
        const int b = in.steps > 0 ? 4 : 5;
        ok = p.send_button(b, true, in.x, in.y) && p.send_button(b, false, in.x, in.y);
      }
      break;
    case ScriptFrame::XInput::kKey:
    case ScriptFrame::XInput::kKeyUp:
      ok = p.send_key(in.key.c_str(), in.kind == ScriptFrame::XInput::kKey, in.ctrl);
      break;
  }
  if (!ok) LOG_WARN("studio: script: X input not sent (no window yet, or an unknown key)");
}

std::string rect_text(const PixelRect& r) {
  return std::to_string(r.x) + " " + std::to_string(r.y) + " " + std::to_string(r.w) + " " +
         std::to_string(r.h);
}

void dump(const std::string& path, const Session& s, const PcaView& pca, const Panels& p,
          const ReportsView& reports, int w, int h) {
  std::ofstream out(path, std::ios::trunc);
  out << "ok = " << (s.ok() ? 1 : 0) << "\n";
  out << "error = " << s.error() << "\n";
  out << "window = " << w << " " << h << "\n";
  out << "flame_image = " << rect_text(p.drawn().flame_image) << "\n";
  out << "flame_view = " << rect_text(p.drawn().flame_view) << "\n";
  out << "pca = " << rect_text(p.drawn().pca) << "\n";
  out << "transfer_places = " << rect_text(p.drawn().transfer_places) << "\n";
  out << "timeline = " << rect_text(p.drawn().timeline) << "\n";
  out << "joint_steps = " << rect_text(p.drawn().joint_steps) << "\n";
  out << "scene_file = " << rect_text(p.drawn().scene_file) << "\n";
  out << "scene_file_text = " << p.scene_file_text() << "\n";
  out << "pca_yaw = " << pca.yaw() << "\npca_pitch = " << pca.pitch()
      << "\npca_zoom = " << pca.scale() << "\n";
  out << "status = " << s.status << "\n";
  out << "reports = ";
  for (size_t i = 0; i < reports.count(); ++i) out << (i ? " " : "") << reports.name(i);
  out << "\n";
  const ImVec2 m = pca.screen_of(s.model_frame(s.frame()));
  out << "pca_marker = " << m.x << " " << m.y << "\n";
  if (s.ok()) {
    out << "frame = " << s.frame() << "\nmodel_frame = " << s.model_frame(s.frame())
        << "\nplaying = " << (s.playing ? 1 : 0) << "\nframes = " << s.frames() << "\n";
    char buf[64];
    out << "shown =";
    for (float v : s.shown()) std::snprintf(buf, sizeof buf, " %.9g", v), out << buf;
    out << "\nbase =";
    for (float v : s.base()) std::snprintf(buf, sizeof buf, " %.9g", v), out << buf;
    const Look& l = s.edits().look;
    out << "\nhue = " << l.hue << "\nhue_top = " << (l.has_hue_top ? l.hue_top : l.hue)
        << "\nsaturation = " << l.saturation << "\nbrightness = " << l.brightness
        << "\nglow_radius = " << l.glow_radius << "\nglow_strength = " << l.glow_strength
        << "\ntransfer_stops = " << l.transfer.size() << "\ntransfer_at =";
    for (float v : l.transfer_at) out << ' ' << v;
    out << "\ndetail_scale = " << s.edits().weights.detail_scale
        << "\nundo_depth = " << s.undo_depth() << "\n";
    // The story being composed: its segments and where each one's joint starts.
    const int n = s.story() ? static_cast<int>(s.story()->segments.size()) : 0;
    out << "story_segments = " << n << "\nstory_selected = " << p.selected
        << "\nstory_joint_frames =";
    for (int i = 0; i < n; ++i) out << ' ' << s.joint_frame(i);
    out << "\nstory_seams =";
    for (int i = 0; i < n; ++i) out << ' ' << s.joint_seam(i);
    out << "\n";
  }
  if (!out) throw RuntimeError(path + ": cannot write the dump");
}

}  // namespace

int run_studio(const StudioOptions& o) {
  std::optional<Script> script;
  if (!o.script.empty()) script = Script::load(o.script);  // its mistakes before any window
  DisplayOptions d;
  d.kind = "window";
  d.width = o.width;
  d.height = o.height;
  d.vsync = o.vsync && !script && o.bench_frames == 0;
  d.title = "Candela studio: " + o.model;
  auto display = open_window_display(d);

  Session session(o.model, o.story);
  if (!session.ok()) LOG_ERROR("studio: %s", session.error().c_str());
  ImGuiScope imgui;
  X11Platform platform;
  Events events(platform);
  std::unique_ptr<FlameView> flame;
  if (session.ok()) flame = std::make_unique<FlameView>(session.model());
  PcaView pca(session);
  ReportsView reports(o.model);
  Panels panels;

  FrameStats stats(static_cast<size_t>(std::max(o.bench_frames, 1)));
  const int warmup = o.bench_frames > 0 ? 10 : 0;
  double cpu_start = process_cpu_seconds();
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now();
  double frame_ms = 0;
  int status = 0;
  // Scripts and benchmarks step the clock by 1/60 s a frame: the same run gives the same frames.
  const double fixed_dt = script || o.bench_frames > 0 ? 1.0 / 60 : 0;
  for (uint64_t n = 0;; ++n) {
    const auto t0 = Clock::now();
    if (!display->poll_events(events)) break;
    const int w = display->width(), h = display->height();
    platform.new_frame(w, h, fixed_dt);
    ScriptFrame sf;
    if (script) {
      try {
        sf = script->run_frame(session, pca);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "candela-tool studio: %s\n", e.what());
        status = 2;
        break;
      }
    }
    if (sf.resize_w > 0 && !platform.resize_window(sf.resize_w, sf.resize_h))
      LOG_WARN("studio: script: resize before the window was seen");
    for (const auto& in : sf.x_input) send(platform, in);
    if (sf.show_reports) panels.open_reports = true;
    session.advance(ImGui::GetIO().DeltaTime);

    // The flame first, at the size its window gives it this frame (the UI
    // then shows the finished texture).
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    if (flame) {
      const ImVec2 fs = Layout::of(w, h).flame_content_size();
      flame->render(session.shown(), session.edits().look, static_cast<int>(fs.x),
                    static_cast<int>(fs.y));
    }
    panels.draw(session, flame.get(), pca, reports, frame_ms);
    ImGui::Render();

    display->begin_frame();
    glClearColor(kPaneColour[0], kPaneColour[1], kPaneColour[2], 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    for (const auto& path : sf.screenshots) screenshot(path, w, h);
    for (const auto& path : sf.dumps) dump(path, session, pca, panels, reports, w, h);
    display->present();

    const auto t1 = Clock::now();
    const double interval = std::chrono::duration<double, std::milli>(t1 - last).count();
    frame_ms = frame_ms == 0 ? interval : frame_ms * 0.9 + interval * 0.1;
    last = t1;
    if (o.bench_frames > 0) {
      if (static_cast<int>(n) == warmup - 1) cpu_start = process_cpu_seconds();
      if (static_cast<int>(n) >= warmup)
        stats.add(interval, std::chrono::duration<double, std::milli>(t1 - t0).count());
      if (static_cast<int>(n) + 1 >= warmup + o.bench_frames) break;
    }
    if (sf.quit || panels.quit_requested()) break;
    if (script && script->done() && o.bench_frames == 0) break;
  }
  if (o.bench_frames > 0)
    std::printf("%s\n", stats
                            .json(stats.count(), process_cpu_seconds() - cpu_start, -1, "window",
                                  display->width(), display->height(), "studio " + o.model)
                            .c_str());
  return status;
}

}  // namespace candela::studio
