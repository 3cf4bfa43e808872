// candela-tool measure agrees with the shared Python yardsticks
// (../shared/eval/flame_features.py and realism.py, run here with python3) on the
// shared real clips: every feature, every series statistic, the repeats and the
// log-spectral distances.
//
// Tolerances: the C++ works in double, numpy in float32 (the gray frames and
// their sums), so small differences are expected. Measured: below 6e-8 for every
// feature; below 1e-4 for the distances and slopes; series mean/std within 1.3e-5
// relative (numpy's float32 width W = sqrt(E[x^2] - X^2) on the triplet clip).
// Bounds are set about 10x above that: features 1e-6 absolute (about 1e-5 of the
// narrowest real range, area_cv's), series mean/std 1e-4 relative, spectral
// slopes 1e-3, distances 2e-3 dB; the repeats exact.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

#include "measure/measure.h"

namespace cm = candela::measure;
namespace fs = std::filesystem;
using nlohmann::json;

#ifndef CANDELA_MEASURE_TEST_FRAMES
#define CANDELA_MEASURE_TEST_FRAMES 900
#endif

namespace {

struct Clip {
  const char* name;
  double fps;
};
// So ctest lists the clip, not its bytes.
void PrintTo(const Clip& c, std::ostream* os) { *os << c.name << " at " << c.fps << " fps"; }

const Clip kClips[] = {
    {"candle_schodl_singan", 30},          {"candle_red_ngasocute", 25},
    {"candle_breeze_tfg_flameshaken", 60}, {"candle_triplet_oscillating_cpldcpu", 30},
    {"campfire_night_slowmo_implax", 30},  {"campfire_night_arvideo", 25},
    {"fireplace_logs_grpatter", 29.92},    {"fireplace_logs_meditation", 29.97},
};

std::string frames_dir(const Clip& c) {
  return (fs::path(CANDELA_FLAMES_DIR) / c.name / "frames").string();
}

// Runs eval_reference.py on the clips (each read once) and returns its JSON.
json python_reference(const std::vector<Clip>& clips,
                      const std::vector<std::pair<std::string, std::string>>& pairs) {
  const fs::path out =
      fs::temp_directory_path() / ("candela_measure_ref_" + std::to_string(getpid()) + ".json");
  std::string cmd = "/usr/bin/python3 " + std::string(CANDELA_SOURCE_DIR) +
                    "/tests/tools/measure/eval_reference.py " + CANDELA_EVAL_DIR + " " +
                    std::to_string(CANDELA_MEASURE_TEST_FRAMES) + " " + out.string();
  for (const Clip& c : clips)
    cmd += std::string(" ") + c.name + " " + frames_dir(c) + " " + std::to_string(c.fps);
  if (!pairs.empty()) {
    cmd += " --pair";
    for (const auto& [a, b] : pairs) cmd += " " + a + " " + b;
  }
  if (std::system(cmd.c_str()) != 0) {
    ADD_FAILURE() << "the Python yardsticks failed (python3-numpy, python3-scipy and "
                     "python3-pil are in board/install-deps.sh): "
                  << cmd;
    return {};
  }
  std::ifstream in(out);
  json j = json::parse(in);
  fs::remove(out);
  return j;
}

double value(const json& j) { return j.is_null() ? std::nan("") : j.get<double>(); }

void expect_close(double cpp, const json& py, double tol, const std::string& what) {
  const double p = value(py);
  if (std::isnan(p)) {
    EXPECT_TRUE(std::isnan(cpp)) << what << ": Python gives NaN, C++ " << cpp;
    return;
  }
  EXPECT_NEAR(cpp, p, tol) << what;
}

bool have_footage(std::string& why) {
  if (fs::is_directory(CANDELA_FLAMES_DIR) && fs::is_directory(CANDELA_EVAL_DIR)) return true;
  why = std::string("the shared clips (") + CANDELA_FLAMES_DIR + ") or yardsticks (" +
        CANDELA_EVAL_DIR + ") are not here";
  return false;
}

cm::LoadLimits limits() {
  cm::LoadLimits l;
  l.max_frames = CANDELA_MEASURE_TEST_FRAMES;
  return l;
}

class MeasureAgreement : public ::testing::TestWithParam<Clip> {};

}  // namespace

TEST_P(MeasureAgreement, FeaturesStatsAndRepeatsMatchTheScripts) {
  std::string why;
  if (!have_footage(why)) GTEST_SKIP() << why;
  const Clip c = GetParam();
  const json ref = python_reference({c}, {});
  ASSERT_TRUE(ref.contains("clips")) << "no reference numbers";
  const json& r = ref["clips"][c.name];

  const cm::Frames raw = cm::load_frames(frames_dir(c), limits());
  const cm::Features f = cm::features(raw, c.fps, frames_dir(c), limits());
  EXPECT_EQ(f.frames, r["features"]["frames"].get<int>());
  for (const auto& k : cm::feature_names())
    expect_close(cm::feature(f, k), r["features"][k], 1e-6, std::string(c.name) + " " + k);

  const cm::Stats s = cm::stats(cm::series(raw), c.fps);
  EXPECT_EQ(s.frames, r["stats"]["frames"].get<int>());
  for (int i = 0; i < 4; ++i) {
    const json& p = r["stats"][cm::kSeriesNames[i]];
    const std::string what = std::string(c.name) + " " + cm::kSeriesNames[i];
    expect_close(s.s[i].mean, p["mean"], 1e-4 * std::abs(value(p["mean"])) + 1e-9, what + " mean");
    expect_close(s.s[i].std, p["std"], 1e-4 * std::abs(value(p["std"])) + 1e-9, what + " std");
    expect_close(s.s[i].slope, p["slope"], 1e-3, what + " slope");
  }
  EXPECT_DOUBLE_EQ(cm::longest_repeat_s(raw, c.fps), value(r["repeats"])) << c.name << " repeats";
}

INSTANTIATE_TEST_SUITE_P(SharedClips, MeasureAgreement, ::testing::ValuesIn(kClips),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(MeasureCompareAgreement, LogSpectralDistancesMatchRealismPy) {
  std::string why;
  if (!have_footage(why)) GTEST_SKIP() << why;
  // Different frame rates (30/60, 60/29.97, 25/30) so the common band differs.
  const std::vector<Clip> clips = {kClips[0], kClips[2], kClips[7], kClips[1]};
  const std::vector<std::pair<std::string, std::string>> pairs = {{kClips[0].name, kClips[2].name},
                                                                  {kClips[2].name, kClips[7].name},
                                                                  {kClips[1].name, kClips[0].name}};
  const json ref = python_reference(clips, pairs);
  ASSERT_TRUE(ref.contains("pairs")) << "no reference numbers";
  std::map<std::string, std::pair<cm::Series, double>> series;
  for (const Clip& c : clips)
    series[c.name] = {cm::series(cm::load_frames(frames_dir(c), limits())), c.fps};
  for (const auto& [a, b] : pairs) {
    const cm::Comparison cmp =
        cm::compare(series[a].first, series[a].second, series[b].first, series[b].second);
    const json& p = ref["pairs"][a + " " + b];
    for (int i = 0; i < 4; ++i) {
      const std::string what = a + " vs " + b + " " + cm::kSeriesNames[i];
      expect_close(cmp.s[i].lsd_db, p[cm::kSeriesNames[i]]["lsd_db"], 2e-3, what + " lsd");
      const double ratio = value(p[cm::kSeriesNames[i]]["std_ratio"]);
      expect_close(cmp.s[i].std_ratio, p[cm::kSeriesNames[i]]["std_ratio"], 1e-5 * ratio,
                   what + " std ratio");
    }
  }
}
