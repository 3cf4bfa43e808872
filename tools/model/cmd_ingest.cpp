// candela-tool ingest INPUT... --out DATASET
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/cli_usage.h"
#include "core/error.h"
#include "ingest.h"
#include "subcommand.h"

namespace {

int run_ingest(int argc, char** argv) {
  CLI::App app{
      "Turn flame footage (PNG frame folders or video files) into an aligned, background-free "
      "dataset of gray frames of one size, with a manifest",
      "candela-tool ingest"};
  std::vector<std::string> inputs, labels;
  std::string out;
  candela::tools::IngestOptions opt;
  int max_frames = 0, step = 1;
  double fps = 0;
  app.add_option("INPUT", inputs, "PNG folders (or clip folders with frames/) and video files")
      ->required();
  app.add_option("--out", out, "dataset folder to write")->required();
  auto* width = app.add_option("--width", opt.width, "output width (--as-filmed: the footage's)")
                    ->check(CLI::Range(8, 4096))
                    ->capture_default_str();
  auto* height =
      app.add_option("--height", opt.height, "output height (--as-filmed: the footage's)")
          ->check(CLI::Range(8, 4096))
          ->capture_default_str();
  app.add_flag("--as-filmed", opt.as_filmed,
               "keep each frame whole (scaled to fit, centred; not cropped to the flame), at "
               "the first input's size (at most 512 rows) unless --width/--height say, with no "
               "background level taken off unless --threshold says: your footage as it looked");
  app.add_option("--threshold", opt.threshold,
                 "background level, linear 0..1 (default: estimated per clip)")
      ->check(candela::finite_range(0.0, 1.0));
  app.add_option("--dark", opt.dark_frame, "dark reference frame (PNG) subtracted first")
      ->check(CLI::ExistingFile);
  app.add_option("--max-frames", max_frames, "at most this many frames per input (0: all)")
      ->check(CLI::Range(0, 1 << 24));
  app.add_option("--step", step, "keep every n-th frame")->check(CLI::Range(1, 1000));
  app.add_option("--fps", fps, "frame rate of PNG folders (default: from info.txt, else 30)")
      ->check(candela::finite_range(0.1, 1000.0));
  bool force = false;
  app.add_flag("--force", force, "replace a dataset already in --out");
  app.add_option(
      "--label", labels,
      "label a range: CLIP:FROM-TO:LABEL (clip-local frames), e.g. breeze:55-100:wind-right");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  // A dataset is hours of someone's footage: not replaced unless asked.
  if (!force && std::filesystem::exists(out + "/manifest.json")) {
    std::fprintf(stderr,
                 "candela-tool ingest: --out %s already holds a dataset; choose another folder "
                 "or add --force to replace it\n",
                 out.c_str());
    return candela::kUsageExitStatus;
  }
  for (const auto& l : labels) opt.labels.push_back(candela::tools::parse_label(l, "--label"));
  std::vector<candela::tools::SourceClip> clips;
  for (const auto& in : inputs) {
    std::fprintf(stderr, "ingest: reading %s\n", in.c_str());
    clips.push_back(candela::tools::read_source(in, max_frames, step, fps));
  }
  if (opt.as_filmed && !clips.empty()) {
    // The footage's own size, unless asked; at most 512 rows (the runtime's
    // texture budget), the aspect kept.
    const auto& c0 = clips.front();
    const double shrink = std::min(1.0, 512.0 / c0.height);
    if (width->count() == 0 && height->count() == 0) {
      opt.width = std::max(8, static_cast<int>(std::lround(c0.width * shrink)));
      opt.height = std::max(8, static_cast<int>(std::lround(c0.height * shrink)));
    } else if (width->count() == 0) {
      opt.width =
          std::max(8, static_cast<int>(std::lround(opt.height * double(c0.width) / c0.height)));
    } else if (height->count() == 0) {
      opt.height =
          std::max(8, static_cast<int>(std::lround(opt.width * double(c0.height) / c0.width)));
    }
  }
  auto d = candela::tools::ingest(
      clips, opt, [](const std::string& s) { std::fprintf(stderr, "ingest: %s\n", s.c_str()); });
  candela::tools::save_dataset(d, out);
  int plumes = 0;
  for (auto p : d.multi_plume) plumes += p;
  std::printf(
      "%s: %d frames %dx%d from %zu clips; %d with several plumes (left out of Learning "
      "Flames)\n",
      out.c_str(), d.frames(), d.width, d.height, d.clips.size(), plumes);
  return 0;
}

}  // namespace

int candela::tool::cmd_ingest(int argc, char** argv) { return run_ingest(argc, argv); }
