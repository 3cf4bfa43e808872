// The report plots `candela-tool build` writes (MODEL.report/) can be read:
// the PSNR curve has its axes, tick labels, axis titles, a legend and a
// title; the eigen-image sheet names each image; the trajectory plot shows
// three viewpoints with a legend entry (colour and name) per clip. Text is
// found by stamping the expected words in the plots' own font and looking
// for them, pixel for pixel.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/image.h"
#include "model_build.h"
#include "render.h"

namespace ct = candela::tools;
namespace fs = std::filesystem;

namespace {

using Rgb = std::array<uint8_t, 3>;

// Two clips of a dot: one circling, one swaying (distinct tracks).
ct::Dataset two_clips() {
  ct::Dataset d;
  d.width = 16;
  d.height = 20;
  const int n = 60;
  d.pixels.resize(d.frame_pixels() * 2 * n);
  d.multi_plume.assign(2 * n, 0);
  for (int f = 0; f < 2 * n; ++f) {
    const double t = f % n;
    const double cx = f < n ? 8 + 4 * std::cos(0.3 * t) : 8 + 5 * std::sin(0.17 * t);
    const double cy = f < n ? 10 + 5 * std::sin(0.3 * t) : 14 - 0.1 * t;
    for (int y = 0; y < d.height; ++y)
      for (int x = 0; x < d.width; ++x) {
        const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
        d.pixels[d.frame_pixels() * f + y * d.width + x] =
            static_cast<uint8_t>(std::lround(250 * std::exp(-r2 / 5)));
      }
  }
  d.clips.push_back({"circling-dot", "synthetic", 0, n, 30, {}});
  d.clips.push_back({"swaying-dot", "synthetic", n, n, 30, {}});
  return d;
}

// Where `text` (in the plots' font, colour `ink`, on `paper`) first appears
// in `img` at or below row `from_y`, or {-1, -1}: every stamp pixel matches.
std::pair<int, int> find_text(const candela::Image& img, const std::string& text, Rgb ink,
                              Rgb paper, int scale = 1, int from_y = 0, bool up = false) {
  const int tw = ct::Canvas::text_width(text, scale) + 2, th = ct::Canvas::kTextHeight * scale + 2;
  const int w = up ? th : tw, h = up ? tw : th;
  ct::Canvas stamp(w, h, paper);
  if (up) {
    stamp.text_up(1, h - 1, text, ink, scale);
  } else {
    stamp.text(1, 1, text, ink, scale);
  }
  for (int y = std::max(0, from_y - 1); y + h <= img.height; ++y)
    for (int x = 0; x + w <= img.width; ++x) {
      bool same = true;
      for (int j = 0; j < h && same; ++j)
        for (int i = 0; i < w && same; ++i)
          for (int k = 0; k < 3 && same; ++k)
            same = img.at(x + i, y + j, k) == stamp.img.at(i, j, k);
      if (same) return {x + 1, y + 1};
    }
  return {-1, -1};
}

// Whether a solid w x h block of colour c is in `img` (a legend swatch: the
// plotted lines are one or two pixels wide).
bool has_block(const candela::Image& img, Rgb c, int w, int h) {
  for (int y = 0; y + h <= img.height; ++y)
    for (int x = 0; x + w <= img.width; ++x) {
      bool all = true;
      for (int j = 0; j < h && all; ++j)
        for (int i = 0; i < w && all; ++i)
          for (int k = 0; k < 3 && all; ++k) all = img.at(x + i, y + j, k) == c[k];
      if (all) return true;
    }
  return false;
}

// The longest run of black pixels along a row (dx = 1) or column.
int longest_black_run(const candela::Image& img, bool rows) {
  int best = 0;
  const int outer = rows ? img.height : img.width, inner = rows ? img.width : img.height;
  for (int o = 0; o < outer; ++o) {
    int run = 0;
    for (int i = 0; i < inner; ++i) {
      const int x = rows ? i : o, y = rows ? o : i;
      const bool black = img.at(x, y, 0) == 0 && img.at(x, y, 1) == 0 && img.at(x, y, 2) == 0;
      run = black ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best;
}

class Reports : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // A folder of this run's own (other builds may run this test at the same time).
    dir_ =
        (fs::temp_directory_path() / ("candela-report-test-" + std::to_string(getpid()))).string();
    fs::remove_all(dir_);
    ct::BuildOptions o;
    o.pca.components = 8;
    o.learning_flames = false;
    data_ = new ct::Dataset(two_clips());
    const ct::BuiltModel m = ct::build_model(*data_, o);
    ct::write_reports(*data_, m, dir_);
  }
  static void TearDownTestSuite() {
    fs::remove_all(dir_);
    delete data_;
    data_ = nullptr;
  }
  static candela::Image png(const std::string& name) {
    return candela::read_png(dir_ + "/" + name, 3);
  }
  static std::string dir_;
  static ct::Dataset* data_;
};
std::string Reports::dir_;
ct::Dataset* Reports::data_ = nullptr;

const Rgb kInk{0, 0, 0}, kWhite{255, 255, 255};

TEST_F(Reports, PsnrCurveHasAxesLabelsLegendAndTitle) {
  const auto img = png("psnr.png");
  EXPECT_GE(longest_black_run(img, true), 400) << "the x axis";
  EXPECT_GE(longest_black_run(img, false), 250) << "the y axis";
  EXPECT_GE(find_text(img, "Reconstruction PSNR vs components", kInk, kWhite, 2).first, 0)
      << "the title";
  EXPECT_GE(find_text(img, "components E (log scale)", kInk, kWhite).first, 0) << "x title";
  // The x ticks: E = 1, 2, 4 and 8 labelled under the axis (the plot's
  // bottom 52 rows), left to right; the y ticks every 5 dB left of the axis.
  int last_x = -1;
  for (const char* e : {"1", "2", "4", "8"}) {
    const int x = find_text(img, e, kInk, kWhite, 1, img.height - 52).first;
    EXPECT_GT(x, last_x) << "tick " << e;
    last_x = x;
  }
  int last_y = img.height;
  for (const char* db : {"15", "20", "25"}) {
    const auto [x, y] = find_text(img, db, kInk, kWhite);
    EXPECT_GE(x, 0) << db << " dB";
    EXPECT_LT(x, 64) << db << " dB left of the axis";
    EXPECT_LT(y, last_y) << db << " dB above the one below";
    last_y = y;
  }
  const auto ytitle = find_text(img, "PSNR (dB, peak 255)", kInk, kWhite, 1, 0, true);
  EXPECT_GE(ytitle.first, 0) << "the y axis's title, reading upwards";
  EXPECT_LT(ytitle.first, 30);
  // The legend: each series' colour as a swatch, beside its name.
  const auto train = find_text(img, "train", kInk, kWhite);
  const auto held = find_text(img, "held-out frames", kInk, kWhite);
  EXPECT_GE(train.first, 0);
  EXPECT_GE(held.first, 0);
  EXPECT_TRUE(has_block(img, {220, 50, 32}, 14, 8)) << "the train swatch";
  EXPECT_TRUE(has_block(img, {30, 120, 200}, 14, 8)) << "the held-out swatch";
}

TEST_F(Reports, EigenSheetNamesEveryImage) {
  const auto img = png("eigenfires.png");
  const Rgb label{255, 220, 120};
  EXPECT_GE(find_text(img, "Mean and eigen-images 0-7 (mid-gray = 0)", kWhite, {0, 0, 0}).first, 0);
  const auto mean = find_text(img, "mean", label, {0, 0, 0});
  ASSERT_GE(mean.first, 0);
  // Components 0..7 each named, left to right along a row of six.
  std::pair<int, int> prev = mean;
  for (int k = 0; k < 8; ++k) {
    const auto at = find_text(img, std::to_string(k), label, {0, 0, 0});
    ASSERT_GE(at.first, 0) << "component " << k;
    if (k % 6 != 5) {
      EXPECT_GT(at.first, prev.first) << "component " << k << " right of the one before";
    }
    prev = at;
  }
}

TEST_F(Reports, TrajectoryShowsThreeViewsAndALegendPerClip) {
  const auto img = png("trajectory.png");
  EXPECT_GE(
      find_text(img, "First three weights (w0, w1, w2): one track per clip", kInk, kWhite, 2).first,
      0);
  for (const char* view :
       {"oblique", "from above: w0 right, w1 up", "from the front: w0 right, w2 up"}) {
    EXPECT_GE(find_text(img, view, kInk, kWhite).first, 0) << view;
  }
  for (int i = 0; i < 2; ++i) {
    const Rgb colour = ct::palette(i + 3);
    const auto name = find_text(img, data_->clips[static_cast<size_t>(i)].name, kInk, kWhite);
    EXPECT_GE(name.first, 0) << "clip " << i << " named";
    EXPECT_TRUE(has_block(img, colour, 14, 8)) << "clip " << i << "'s swatch";
    // Its track in each of the three views (thirds of the width).
    for (int v = 0; v < 3; ++v) {
      int n = 0;
      for (int y = 0; y < img.height; ++y)
        for (int x = v * img.width / 3; x < (v + 1) * img.width / 3; ++x)
          n += img.at(x, y, 0) == colour[0] && img.at(x, y, 1) == colour[1] &&
               img.at(x, y, 2) == colour[2];
      EXPECT_GT(n, 40) << "clip " << i << " in view " << v;
    }
  }
}

}  // namespace
