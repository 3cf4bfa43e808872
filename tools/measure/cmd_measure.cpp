// candela-tool measure: how close a flame clip (a folder of PNG frames) is to real
// footage, by the yardsticks of ../shared/eval/ (flame_features.py, realism.py).
//   measure features DIR --fps F [--json]
//   measure stats DIR --fps F [--json]
//   measure compare DIR_A FPS_A DIR_B FPS_B [--json]
//   measure repeats DIR --fps F [--json]
//   measure DIR --fps F --against REFS|candle|fire [--flames DIR] [--json]
// Exit status: 0 done (judge: everything asked for is inside the real range),
// 1 judged outside (or the tool failed), 2 bad usage or unusable input.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "candela-tool/subcommand.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "measure/measure.h"

#ifndef CANDELA_MEASURE_FLAMES_DIR
#define CANDELA_MEASURE_FLAMES_DIR ""
#endif

namespace candela::tool {
namespace {

namespace cm = candela::measure;
using nlohmann::json;

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json to_json(const cm::Features& f) {
  json j = {{"frames", f.frames}, {"fps", f.fps}};
  for (const auto& k : cm::feature_names()) j[k] = num(cm::feature(f, k));
  return j;
}

// What every subcommand takes: how many frames to read at most, and --json.
struct Common {
  cm::LoadLimits limits;
  bool as_json = false;
};
void add_common(CLI::App& app, Common& c) {
  app.add_option("--max-frames", c.limits.max_frames,
                 "read at most this many frames (first by name; the scripts read 900)")
      ->check(CLI::Range(2, 100000));
  app.add_flag("--json", c.as_json, "print one JSON object");
}

// The clip a subcommand measures: a folder of PNG frames and its frame rate.
struct Clip {
  std::string dir;
  double fps = 0;
};
void add_clip(CLI::App& app, Clip& clip, const char* what = "folder of PNG frames") {
  app.add_option("DIR", clip.dir, what)->required();
  app.add_option("--fps", clip.fps, "frame rate of the clip")
      ->required()
      ->check(CLI::PositiveNumber);
}

// The options of a subcommand that measures one clip, added to `app` (kept
// where they are: CLI11 writes to the members it was given).
struct OneClip {
  Clip clip;
  Common common;
  explicit OneClip(CLI::App& app) {
    add_clip(app, clip);
    add_common(app, common);
  }
};

int parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  return -1;
}

int run_features(int argc, char** argv) {
  CLI::App app{"Scale-free appearance and motion features of one flame clip (flame_features.py)",
               "candela-tool measure features"};
  OneClip options(app);
  const auto& [dir, fps] = options.clip;
  const auto& [limits, as_json] = options.common;
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  const cm::Features f = cm::features(cm::load_frames(dir, limits), fps, dir, limits);
  if (as_json) {
    std::printf("%s\n", to_json(f).dump().c_str());
    return 0;
  }
  std::printf("%s: %d frames at %g fps\n", dir.c_str(), f.frames, f.fps);
  for (const auto& k : cm::feature_names())
    std::printf("  %-10s %10.4f\n", k.c_str(), cm::feature(f, k));
  return 0;
}

int run_stats(int argc, char** argv) {
  CLI::App app{"Brightness I, height H, sway X, width W: mean, std and spectral slope (realism.py)",
               "candela-tool measure stats"};
  OneClip options(app);
  const auto& [dir, fps] = options.clip;
  const auto& [limits, as_json] = options.common;
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  const cm::Frames raw = cm::load_frames(dir, limits);
  const cm::Stats s = cm::stats(cm::series(raw), fps);
  json j = {{"frames", s.frames}, {"fps", s.fps}};
  for (int i = 0; i < 4; ++i)
    j[cm::kSeriesNames[i]] = {
        {"mean", num(s.s[i].mean)}, {"std", num(s.s[i].std)}, {"slope", num(s.s[i].slope)}};
  if (as_json) {
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  std::printf("%s: %d frames at %g fps\n  series       mean        std      slope\n", dir.c_str(),
              s.frames, s.fps);
  for (int i = 0; i < 4; ++i)
    std::printf("  %-6s %10.4f %10.4f %10.3f\n", cm::kSeriesNames[i], s.s[i].mean, s.s[i].std,
                s.s[i].slope);
  return 0;
}

int run_compare(int argc, char** argv) {
  CLI::App app{
      "Log-spectral distance (dB) and std ratio B/A of the I/H/X/W series of two clips "
      "(realism.py compare)",
      "candela-tool measure compare"};
  std::string da, db;
  double fa = 0, fb = 0;
  Common common;
  app.add_option("DIR_A", da, "folder of PNG frames")->required();
  app.add_option("FPS_A", fa, "its frame rate")->required()->check(CLI::PositiveNumber);
  app.add_option("DIR_B", db, "folder of PNG frames")->required();
  app.add_option("FPS_B", fb, "its frame rate")->required()->check(CLI::PositiveNumber);
  add_common(app, common);
  const auto& [limits, as_json] = common;
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  const cm::Series sa = cm::series(cm::load_frames(da, limits));
  const cm::Series sb = cm::series(cm::load_frames(db, limits));
  const cm::Comparison c = cm::compare(sa, fa, sb, fb);
  json j;
  for (int i = 0; i < 4; ++i)
    j[cm::kSeriesNames[i]] = {{"lsd_db", num(c.s[i].lsd_db)}, {"std_ratio", num(c.s[i].std_ratio)}};
  if (as_json) {
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  std::printf("A %s (%g fps)\nB %s (%g fps)\n  series  lsd (dB)  std B/A\n", da.c_str(), fa,
              db.c_str(), fb);
  for (int i = 0; i < 4; ++i)
    std::printf("  %-6s %9.2f %8.3f\n", cm::kSeriesNames[i], c.s[i].lsd_db, c.s[i].std_ratio);
  return 0;
}

int run_repeats(int argc, char** argv) {
  CLI::App app{
      "Longest stretch of frames that nearly repeats an earlier one, in seconds "
      "(realism.py repeats)",
      "candela-tool measure repeats"};
  OneClip options(app);
  const auto& [dir, fps] = options.clip;
  const auto& [limits, as_json] = options.common;
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  const double r = cm::longest_repeat_s(cm::load_frames(dir, limits), fps);
  if (as_json)
    std::printf("%s\n", json({{"longest_repeat_s", r}}).dump().c_str());
  else
    std::printf("%s: longest repeated stretch %.3f s\n", dir.c_str(), r);
  return 0;
}

std::string default_flames_dir() {
  if (const char* e = std::getenv("CANDELA_FLAMES_DIR"); e && *e) return e;
  return CANDELA_MEASURE_FLAMES_DIR;
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

int run_judge(int argc, char** argv) {
  CLI::App app{
      "Judge a flame clip against real ones: per feature the real range and whether the clip "
      "lies inside; per series (I/H/X/W) the log-spectral distance to each real clip next to "
      "the real-vs-real spread. Exit 0 when everything asked for is inside, 1 when not.\n"
      "Also: measure features|stats|compare|repeats ... (measure SUBCOMMAND --help)",
      "candela-tool measure"};
  std::string against, flames = default_flames_dir(), only;
  double spectra_margin = 0;
  bool no_spectra = false;
  Clip judged;
  Common common;
  add_clip(app, judged, "folder of PNG frames to judge");
  app.add_option("--against", against,
                 "the real clips: a file of lines \"DIR FPS\", or a kind: candle (the four "
                 "shared candle clips) or fire (the three real-speed fire clips)")
      ->required();
  app.add_option("--flames", flames, "where the shared clips of a kind are")->capture_default_str();
  app.add_option("--features", only,
                 "judge only these features (comma-separated; default all: tau_s,sharp,"
                 "spat_slope,iso,parts,area_cv,core)");
  app.add_flag("--no-spectra", no_spectra, "judge the features only, not the I/H/X/W spectra");
  app.add_option("--spectra-margin", spectra_margin,
                 "a series is inside within this many dB beyond the real-vs-real spread "
                 "(default 0: the spread itself)")
      ->check(CLI::Range(0.0, 40.0))
      ->capture_default_str();
  std::string source;
  cm::SourceJudging by_source;
  app.add_option("--source", source,
                 "DIR is a model of this one of the real clips (its name, e.g. "
                 "campfire_night_arvideo), played back: each series is judged by its distance to "
                 "that clip against the real clips' spread, and a feature is also inside within "
                 "--source-tolerance of that clip's own value");
  app.add_option("--source-tolerance", by_source.tolerance,
                 "with --source: relative distance to the source's feature value that counts "
                 "as inside")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  add_common(app, common);
  const auto& [dir, fps] = judged;
  const auto& [limits, as_json] = common;
  if (int rc = parse(app, argc, argv); rc >= 0) return rc;
  const std::vector<std::string> names = split_list(only);
  for (const auto& n : names)
    if (std::find(cm::feature_names().begin(), cm::feature_names().end(), n) ==
        cm::feature_names().end()) {
      std::fprintf(stderr, "candela-tool measure: --features: unknown feature '%s'\n", n.c_str());
      return 2;
    }

  std::vector<cm::ClipRef> refs = cm::clips_of_kind(against);
  std::string kind;
  if (!refs.empty()) {
    kind = against;
    if (flames.empty() || !std::filesystem::is_directory(flames))
      throw ConfigError(flames.empty() ? std::string("--flames") : flames, "",
                        "the shared clips folder (with " + refs[0].name +
                            "/frames/ ...) is not there; pass --flames DIR");
    for (auto& r : refs) r.name = (std::filesystem::path(flames) / r.name / "frames").string();
  } else if (std::filesystem::is_regular_file(against)) {
    refs = cm::read_refs_file(against);
  } else {
    std::fprintf(stderr,
                 "candela-tool measure: --against: expected a file of \"DIR FPS\" lines or a "
                 "kind (candle, fire), got '%s'\n",
                 against.c_str());
    return 2;
  }
  if (!source.empty()) {
    for (size_t i = 0; i < refs.size(); ++i) {
      const std::filesystem::path p(refs[i].name);
      const std::string clip_name =
          p.filename() == "frames" ? p.parent_path().filename().string() : p.filename().string();
      if (clip_name == source || refs[i].name == source) by_source.source = static_cast<int>(i);
    }
    if (by_source.source < 0) {
      std::fprintf(
          stderr,
          "candela-tool measure: --source: '%s' is not one of the real clips of --against\n",
          source.c_str());
      return 2;
    }
  }
  std::vector<cm::Measured> real;
  for (const auto& r : refs) real.push_back(cm::measure_clip(r.name, r.fps, limits));
  const cm::Measured clip = cm::measure_clip(dir, fps, limits);
  const cm::Judgement j = cm::judge(real, clip, names, !no_spectra, spectra_margin, by_source);
  const bool all = j.inside == j.of;

  if (as_json) {
    json out = {{"clip", dir}, {"fps", fps}, {"inside", j.inside}, {"of", j.of}};
    out["real"] = json::array();
    for (const auto& r : real) out["real"].push_back({{"dir", r.dir}, {"fps", r.fps}});
    out["features"] = json::object();
    for (const auto& f : j.features)
      out["features"][f.name] = {{"real_min", num(f.real_min)},
                                 {"real_max", num(f.real_max)},
                                 {"value", num(f.value)},
                                 {"inside", f.inside}};
    if (by_source.source >= 0)
      for (const auto& f : j.features) out["features"][f.name]["source"] = num(f.source);
    if (!no_spectra) {
      out["spectra"] = json::object();
      for (const auto& s : j.spectra) {
        json d = json::array(), r = json::array();
        for (double v : s.lsd_to_ref) d.push_back(num(v));
        for (double v : s.std_ratio) r.push_back(num(v));
        out["spectra"][s.series] = {{"lsd_db", d},
                                    {"std_ratio", r},
                                    {"real_min", num(s.real_min)},
                                    {"real_max", num(s.real_max)},
                                    {"margin_db", spectra_margin},
                                    {"inside", s.inside}};
      }
    }
    std::printf("%s\n", out.dump().c_str());
    return all ? 0 : 1;
  }
  std::printf("%s (%d frames at %g fps) against %zu real clips%s%s:\n", dir.c_str(),
              clip.features.frames, fps, real.size(), kind.empty() ? "" : " of kind ",
              kind.c_str());
  for (const auto& r : real) std::printf("  %s (%g fps)\n", r.dir.c_str(), r.fps);
  const bool sourced = by_source.source >= 0;
  if (sourced)
    std::printf("  source: %s (features within %g of its own values count as inside)\n",
                real[static_cast<size_t>(by_source.source)].dir.c_str(), by_source.tolerance);
  std::printf("\n  feature      real min   real max %s     value  verdict\n",
              sourced ? "    source" : "");
  for (const auto& f : j.features) {
    char src[32] = "";
    if (sourced) std::snprintf(src, sizeof src, "%10.4f ", f.source);
    const bool in_range = f.real_min <= f.value && f.value <= f.real_max;
    std::printf("  %-10s %10.4f %10.4f %s%10.4f  %s\n", f.name.c_str(), f.real_min, f.real_max, src,
                f.value,
                f.inside && !in_range  ? "inside (as the source)"
                : f.inside             ? "inside"
                : f.value < f.real_min ? "outside (below)"
                : f.value > f.real_max ? "outside (above)"
                                       : "outside (undefined)");
  }
  if (!no_spectra) {
    std::printf("\n  series  real-real lsd (dB)   lsd to %-20s verdict",
                sourced ? "the source (dB)" : "each real clip (dB)");
    if (spectra_margin > 0) std::printf(" (within %.1f dB of the spread)", spectra_margin);
    std::printf("\n");
    for (const auto& s : j.spectra) {
      std::string d;
      char buf[32];
      for (double v : s.lsd_to_ref) {
        std::snprintf(buf, sizeof buf, " %5.1f", v);
        d += buf;
      }
      std::printf("  %-6s  %6.1f .. %6.1f      %-26s  %s\n", s.series.c_str(), s.real_min,
                  s.real_max, d.c_str(), s.inside ? "inside" : "outside");
    }
  }
  std::printf("\ninside on %d of %d\n", j.inside, j.of);
  return all ? 0 : 1;
}

int run_measure(int argc, char** argv) {
  // Bad input (no frames, no flame, mixed sizes, an unreadable PNG, a bad REFS
  // line) is the user's to fix: status 2, so judging scripts can tell it from
  // "outside" (1).
  try {
    if (argc >= 2) {
      const std::string sub = argv[1];
      std::string name = std::string(argv[0]) + " " + sub;
      std::vector<char*> args(argv + 1, argv + argc);
      args[0] = name.data();
      const int n = static_cast<int>(args.size());
      if (sub == "features") return run_features(n, args.data());
      if (sub == "stats") return run_stats(n, args.data());
      if (sub == "compare") return run_compare(n, args.data());
      if (sub == "repeats") return run_repeats(n, args.data());
    }
    return run_judge(argc, argv);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "candela-tool measure: %s\n", e.what());
    return 2;
  }
}

}  // namespace
}  // namespace candela::tool

int candela::tool::cmd_measure(int argc, char** argv) { return run_measure(argc, argv); }
