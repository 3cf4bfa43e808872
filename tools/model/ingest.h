// From footage to a dataset: gray luma, dark background removed in linear light, flame
// base found and aligned, cropped and resized to a common size, frames with
// several disjoint plumes flagged.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "dataset.h"

namespace candela::tools {

// One decoded clip: linear luma in [0, 1], frames x height x width.
struct SourceClip {
  std::string name, source;
  double fps = 30;
  int width = 0, height = 0;
  std::vector<float> luma;
  int frames() const {
    return width > 0 && height > 0
               ? static_cast<int>(luma.size() / (static_cast<size_t>(width) * height))
               : 0;
  }
};

// A folder of PNG frames (or a clip folder with frames/ inside; an info.txt
// saying "NN fps" sets the rate), or a video file (mp4/avi/mkv/mpg/webm...)
// decoded with FFmpeg. `max_frames` > 0 stops early; `step` keeps every n-th.
// Throws ConfigError naming the input on any problem.
SourceClip read_source(const std::string& input, int max_frames = 0, int step = 1,
                       double fps_override = 0);

struct IngestOptions {
  int width = 128, height = 208;  // common output size
  float threshold = -1;           // background level (linear 0..1); <0: estimate per clip
  // As filmed: each clip's whole frame scaled to fit the output (centred, its
  // aspect kept), not cropped to the flame's base and top; no background level
  // unless `threshold` is given. For footage to play back as it looked (a
  // fireplace's dim logs and wall are part of the picture).
  bool as_filmed = false;
  std::string dark_frame;        // optional dark reference PNG, subtracted first
  float base_row = 0.92f;        // where the flame base lands (fraction of height)
  float top_row = 0.06f;         // where the typical flame top lands
  float plume_level = 0.25f;     // plume mask: this fraction of the frame's peak
  float plume_min_area = 0.03f;  // a plume has at least this share of the mask
  struct Label {
    std::string clip;
    int from = 0, to = 0;  // clip-local frames [from, to)
    std::string label;
  };
  std::vector<Label> labels;
};
// Parses "CLIP:FROM-TO:LABEL" (ConfigError naming `what` on bad text).
IngestOptions::Label parse_label(const std::string& text, const std::string& what);

using Progress = std::function<void(const std::string&)>;
Dataset ingest(const std::vector<SourceClip>& clips, const IngestOptions& opt,
               const Progress& progress = {});

// Number of disjoint bright regions big enough to count as plumes.
int count_plumes(const uint8_t* frame, int width, int height, float level, float min_area);

}  // namespace candela::tools
