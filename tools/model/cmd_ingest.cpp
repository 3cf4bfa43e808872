// candela-tool ingest INPUT... --out DATASET
#include <CLI/CLI.hpp>
#include <cstdio>

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
  app.add_option("--width", opt.width, "output width")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  app.add_option("--height", opt.height, "output height")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  app.add_option("--threshold", opt.threshold,
                 "background level, linear 0..1 (default: estimated per clip)");
  app.add_option("--dark", opt.dark_frame, "dark reference frame (PNG) subtracted first")
      ->check(CLI::ExistingFile);
  app.add_option("--max-frames", max_frames, "at most this many frames per input");
  app.add_option("--step", step, "keep every n-th frame")->check(CLI::Range(1, 1000));
  app.add_option("--fps", fps, "frame rate of PNG folders (default: from info.txt, else 30)");
  app.add_option(
      "--label", labels,
      "label a range: CLIP:FROM-TO:LABEL (clip-local frames), e.g. breeze:55-100:wind-right");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  for (const auto& l : labels) opt.labels.push_back(candela::tools::parse_label(l, "--label"));
  std::vector<candela::tools::SourceClip> clips;
  for (const auto& in : inputs) {
    std::fprintf(stderr, "ingest: reading %s\n", in.c_str());
    clips.push_back(candela::tools::read_source(in, max_frames, step, fps));
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
