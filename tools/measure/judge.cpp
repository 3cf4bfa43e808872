// Judging a clip against real ones: per feature the real range (flame_features.py
// judge), per series the distances to each real clip next to the real-real spread.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "measure/measure.h"

namespace candela::measure {

Measured measure_clip(const std::string& dir, double fps, const LoadLimits& limits) {
  const Frames raw = load_frames(dir, limits);
  Measured m;
  m.dir = dir;
  m.fps = fps;
  m.features = features(raw, fps, dir, limits);
  m.series = series(raw);
  return m;
}

Judgement judge(const std::vector<Measured>& refs, const Measured& clip,
                const std::vector<std::string>& names, bool spectra, double spectra_margin_db,
                const SourceJudging& by_source) {
  const bool sourced = by_source.source >= 0 && by_source.source < static_cast<int>(refs.size());
  Judgement j;
  for (const std::string& k : names.empty() ? feature_names() : names) {
    FeatureVerdict v{k, INFINITY, -INFINITY, feature(clip.features, k), false};
    for (const Measured& r : refs) {
      const double x = feature(r.features, k);
      v.real_min = std::min(v.real_min, x);
      v.real_max = std::max(v.real_max, x);
    }
    v.inside = v.real_min <= v.value && v.value <= v.real_max;  // NaN: outside
    if (sourced) {
      v.source = feature(refs[static_cast<size_t>(by_source.source)].features, k);
      v.inside =
          v.inside || std::abs(v.value - v.source) <= by_source.tolerance * std::abs(v.source);
    }
    j.features.push_back(v);
    j.inside += v.inside;
    ++j.of;
  }
  if (!spectra) return j;
  for (int i = 0; i < 4; ++i) {
    SpectrumVerdict s;
    s.series = kSeriesNames[i];
    for (size_t r_at = 0; r_at < refs.size(); ++r_at) {
      if (sourced && static_cast<int>(r_at) != by_source.source) continue;
      const Measured& r = refs[r_at];
      const Comparison c = compare(clip.series, clip.fps, r.series, r.fps);
      s.lsd_to_ref.push_back(c.s[i].lsd_db);
      s.std_ratio.push_back(c.s[i].std_ratio);
    }
    s.real_min = INFINITY;
    s.real_max = -INFINITY;
    for (size_t a = 0; a < refs.size(); ++a)
      for (size_t b = a + 1; b < refs.size(); ++b) {
        const Comparison c = compare(refs[a].series, refs[a].fps, refs[b].series, refs[b].fps);
        s.real_min = std::min(s.real_min, c.s[i].lsd_db);
        s.real_max = std::max(s.real_max, c.s[i].lsd_db);
      }
    // Inside: no further from any real clip than the real clips are from each
    // other (plus the margin asked for).
    s.inside = refs.size() >= 2 && !s.lsd_to_ref.empty();
    for (double d : s.lsd_to_ref) s.inside = s.inside && d <= s.real_max + spectra_margin_db;
    j.spectra.push_back(s);
    j.inside += s.inside;
    ++j.of;
  }
  return j;
}

std::vector<ClipRef> clips_of_kind(const std::string& kind) {
  // The table in ../shared/eval/README.md (real speed; the slow-motion campfire
  // is for appearance only and stays out).
  if (kind == "candle")
    return {{"candle_schodl_singan", 30},
            {"candle_red_ngasocute", 25},
            {"candle_breeze_tfg_flameshaken", 60},
            {"candle_triplet_oscillating_cpldcpu", 30}};
  if (kind == "fire")
    return {{"campfire_night_arvideo", 25},
            {"fireplace_logs_grpatter", 29.92},
            {"fireplace_logs_meditation", 29.97}};
  return {};
}

std::vector<ClipRef> read_refs_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path, "", "cannot open the list of reference clips");
  std::vector<ClipRef> out;
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    const size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    const size_t b = line.find_last_not_of(" \t\r");
    const std::string s = line.substr(a, b - a + 1);
    const size_t sp = s.find_last_of(" \t");
    const std::string where = "line " + std::to_string(no);
    if (sp == std::string::npos)
      throw ConfigError(path, where, "expected \"DIR FPS\", got \"" + s + "\"");
    const std::string dir = s.substr(0, s.find_last_not_of(" \t", sp) + 1);
    const std::string fps_text = s.substr(sp + 1);
    char* end = nullptr;
    const double fps = std::strtod(fps_text.c_str(), &end);
    if (end == fps_text.c_str() || *end || !(fps > 0) || !std::isfinite(fps))
      throw ConfigError(path, where,
                        "expected a frame rate > 0 after the folder, got \"" + fps_text + "\"");
    out.push_back({dir, fps});
  }
  if (out.empty()) throw ConfigError(path, "", "no reference clips (lines \"DIR FPS\")");
  return out;
}

}  // namespace candela::measure
