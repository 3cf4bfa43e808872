// The studio's UI (Dear ImGui): the fixed layout of its three windows
// (controls, flame, PCA tracks), the controls themselves (playback, weight
// sliders, colour, save as scene, undo), and the error window shown instead
// when the model cannot be opened. Every edit goes through Session's setters,
// as the scripted input does.
#pragma once

#include <imgui.h>

#include <string>

#include "flame_view.h"

namespace candela::studio {

class Session;
class PcaView;
class ReportsView;

// What the frame is cleared to: the panes' background (they draw none).
inline constexpr float kPaneColour[3] = {0.06f, 0.06f, 0.06f};

struct Layout {
  ImVec2 controls_pos, controls_size, flame_pos, flame_size, pca_pos, pca_size;
  ImVec2 timeline_pos, timeline_size;  // under the flame and the tracks
  float title_h = 0;                   // each window's title bar
  static Layout of(int width, int height);
  // The flame window's content (where its texture goes), window pixels.
  ImVec2 flame_content_size() const { return {flame_size.x, flame_size.y - title_h}; }
};

// Where things were drawn this frame (window pixels, top-left origin).
struct DrawnRects {
  PixelRect flame_image, flame_view, pca;
  // The transfer function's row of place handles: stop k's handle is centred
  // at x + w * place(k), y + h / 2 (all 0 when the row is not shown).
  PixelRect transfer_places;
  PixelRect timeline;     // the story's blocks (all 0 without a story)
  PixelRect joint_steps;  // the selected joint's steps field (0: not shown)
  PixelRect scene_file;   // the "Save as scene" file name field
};

class Panels {
 public:
  Panels();
  // Builds this frame's UI. `flame` may be null (no model).
  void draw(Session& session, FlameView* flame, PcaView& pca, ReportsView& reports,
            double frame_ms);
  const DrawnRects& drawn() const { return drawn_; }
  // What the "Save as scene" file field holds now (UTF-8).
  std::string scene_file_text() const { return path_buf_; }
  bool quit_requested() const { return quit_; }
  std::string scene_path = "studio-scene.toml";
  int selected = 0;           // the timeline's selected segment (its joint: how it is entered)
  bool open_reports = false;  // opens the Reports section at the next draw

 private:
  void draw_controls(Session& s, ReportsView& reports, double frame_ms);
  void draw_error(const Session& s, const Layout& l);
  void draw_timeline(Session& s);
  DrawnRects drawn_;
  bool quit_ = false;
  char path_buf_[512] = {};  // UTF-8, as ImGui keeps text
  char story_buf_[512] = "studio-story.toml";
  char clip_buf_[128] = {};
  int add_from_ = 0, add_to_ = -1;
  float add_seconds_ = 4;
};

// The save-as-scene action (UI button and script): writes and reports.
bool save_scene_reporting(Session& s, const std::string& path);
// The save-story action (UI button and script).
bool save_story_reporting(Session& s, const std::string& path);

}  // namespace candela::studio
