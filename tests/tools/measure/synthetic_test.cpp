// candela-tool measure on clips whose answers are known: shapes with exact or
// analytic isoperimetric ratios, counted pieces, a known clipped-white share, a
// known gradient, a sinusoid's decorrelation time, 1/f^beta series, an exact
// repeat; PIL's resize and gray conversion bit for bit; errors that name the file.
#include <fftw3.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.h"
#include "core/image.h"
#include "measure/measure.h"

namespace cm = candela::measure;
namespace fs = std::filesystem;

namespace {

cm::Frames blank(int w, int h, int n) {
  cm::Frames f;
  f.width = w;
  f.height = h;
  f.count = n;
  f.pixels.assign(f.frame_size() * n, 0);
  return f;
}

void disc(cm::Frames& f, int t, double cx, double cy, double r, uint8_t value) {
  uint8_t* p = f.frame(t);
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) p[y * f.width + x] = value;
}

fs::path temp_dir(const std::string& what) {
  fs::path d =
      fs::temp_directory_path() / ("candela_measure_" + what + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(MeasureShapes, SquareHasTheExactIsoperimetricRatio) {
  // L x L square: 4L - 4 pixels lose a 4-neighbour under erosion.
  const int L = 60;
  cm::Frames f = blank(100, 100, 1);
  for (int y = 20; y < 20 + L; ++y)
    for (int x = 20; x < 20 + L; ++x) f.frame(0)[y * 100 + x] = 200;
  const cm::ShapeStats s = cm::shape_stats(f);
  EXPECT_DOUBLE_EQ(s.iso, (4.0 * L - 4) * (4.0 * L - 4) / (4 * M_PI * L * L));
  EXPECT_EQ(s.parts, 1.0);
}

TEST(MeasureShapes, DiscIsTheRoundestShape) {
  // A digital disc's 4-connected boundary has about 4 sqrt(2) R pixels, so
  // iso -> (4 sqrt 2 R)^2 / (4 pi pi R^2) = 8 / pi^2 (0.81; a continuous disc is 1).
  cm::Frames f = blank(200, 200, 1);
  disc(f, 0, 100, 100, 80, 255);
  const double iso = cm::shape_stats(f).iso;
  EXPECT_NEAR(iso, 8 / (M_PI * M_PI), 0.02 * 8 / (M_PI * M_PI));
  // Tongues raise it: the same disc with a comb of 1-px-apart teeth on top.
  for (int x = 40; x < 160; x += 4)
    for (int y = 5; y < 40; ++y) f.frame(0)[y * 200 + x] = 255;
  EXPECT_GT(cm::shape_stats(f).iso, 2 * iso);
}

TEST(MeasureShapes, SeparatedBlobsCountAsParts) {
  cm::Frames f = blank(160, 100, 2);
  disc(f, 0, 40, 50, 20, 200);
  disc(f, 0, 120, 50, 20, 200);
  f.frame(0)[5 * 160 + 5] = 200;  // a 1-px speck: under 0.5% of the largest, not a part
  // Frame 1: two squares touching only at a corner are two parts (4-connectivity).
  for (int y = 10; y < 30; ++y)
    for (int x = 10; x < 30; ++x) f.frame(1)[y * 160 + x] = 200;
  for (int y = 30; y < 50; ++y)
    for (int x = 30; x < 50; ++x) f.frame(1)[y * 160 + x] = 200;
  EXPECT_EQ(cm::shape_stats(f).parts, 2.0);
  // The area does not change: area_cv 0 when both frames have equal area.
  cm::Frames g = blank(160, 100, 2);
  disc(g, 0, 40, 50, 20, 200);
  disc(g, 1, 100, 40, 20, 200);
  EXPECT_NEAR(cm::shape_stats(g).area_cv, 0.0, 1e-12);
}

TEST(MeasureShapes, CoreIsTheShareOfClippedWhiteFlamePixels) {
  cm::Frames f = blank(50, 40, 1);
  uint8_t* p = f.frame(0);
  for (int i = 0; i < 100; ++i) p[i] = 64;     // just above 0.25: flame
  for (int i = 100; i < 130; ++i) p[i] = 243;  // >= 0.95: clipped
  for (int i = 130; i < 160; ++i) p[i] = 63;   // just below 0.25: background
  EXPECT_DOUBLE_EQ(cm::core(f), 30.0 / 130.0);
}

TEST(MeasureShapes, SharpnessOfARampIsItsSlope) {
  // u = 2x: |grad| = 2/255 per pixel wherever 0.15 < v < 0.6 (x 20..76).
  cm::Frames f = blank(128, 64, 3);
  for (int t = 0; t < 3; ++t)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 128; ++x) f.frame(t)[y * 128 + x] = static_cast<uint8_t>(2 * x);
  EXPECT_NEAR(cm::sharpness(f), 2.0 / 255.0, 1e-12);
}

TEST(MeasureMotion, TauOfASinusoidIsASixthOfItsPeriod) {
  // Pixels following sin(2 pi t / P): autocorrelation cos(2 pi lag / P), 0.5 at P/6.
  const int P = 36, n = 20 * P;
  const double fps = 30;
  cm::Frames f = blank(32, 32, n);
  for (int t = 0; t < n; ++t) {
    const double v = 128 + 80 * std::sin(2 * M_PI * t / P);
    for (size_t i = 0; i < f.frame_size(); ++i)
      f.frame(t)[i] = static_cast<uint8_t>(std::lround(v));
  }
  EXPECT_NEAR(cm::tau(f, fps), P / 6.0 / fps, 0.1 / fps);
}

namespace {

// 1/f^beta noise by spectral synthesis: amplitude f^(-beta/2), random phases,
// nothing below `low_hz`.
std::vector<double> power_law_noise(double beta, int n, double fps, double low_hz, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> phase(0, 2 * M_PI);
  const int bins = n / 2 + 1;
  fftw_complex* spec = fftw_alloc_complex(bins);
  std::vector<double> x(n);
  for (int k = 0; k < bins; ++k) {
    const double f = k * fps / n;
    const double a = k > 0 && f >= low_hz ? std::pow(f, -beta / 2) : 0.0;
    const double ph = phase(rng);
    spec[k][0] = a * std::cos(ph);
    spec[k][1] = a * std::sin(ph);
  }
  fftw_plan p = fftw_plan_dft_c2r_1d(n, spec, x.data(), FFTW_ESTIMATE);
  fftw_execute(p);
  fftw_destroy_plan(p);
  fftw_free(spec);
  return x;
}

}  // namespace

TEST(MeasureSpectra, PowerLawNoiseHasItsSlope) {
  // The band is 0.5 .. 12 Hz; with no power below 0.25 Hz the 2-s Hann
  // periodogram reads the slope as made.
  for (double beta : {1.0, 2.0, 3.0})
    for (uint32_t seed : {1u, 2u}) {
      const auto x = power_law_noise(beta, 8192, 60, 0.25, seed);
      EXPECT_NEAR(cm::spectral_slope(x, 60), -beta, 0.15) << "beta " << beta << " seed " << seed;
    }
  // With strong power below the band (a long 1/f^2 series) realism.py's estimate
  // is steeper: the window leaks it into the lowest bins. A property of the
  // yardstick, kept as it is (the scripts read so too: about -2.58 here).
  EXPECT_LT(cm::spectral_slope(power_law_noise(2.0, 8192, 60, 0.0, 1), 60), -2.3);
  // White noise is flat; two 1/f^2 series have nearly the same spectrum shape,
  // unlike 1/f^2 against white.
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  std::vector<double> w(8192);
  for (double& v : w) v = g(rng);
  EXPECT_NEAR(cm::spectral_slope(w, 60), 0.0, 0.15);
  const auto a = power_law_noise(2.0, 8192, 60, 0.25, 1),
             b = power_law_noise(2.0, 8192, 60, 0.25, 2);
  EXPECT_LT(cm::lsd(a, 60, b, 60), 1.5);
  EXPECT_GT(cm::lsd(a, 60, w, 60), 8.0);
}

TEST(MeasureRepeats, AnExactRepeatIsFoundWithItsLength) {
  const int n = 300;
  cm::Frames f = blank(32, 32, n);
  std::mt19937 rng(3);
  for (uint8_t& p : f.pixels) p = static_cast<uint8_t>(rng() & 255);
  EXPECT_EQ(cm::longest_repeat_s(f, 60), 0.0);
  // Frames 180..239 replay 40..99: a 60-frame (1 s at 60 fps) repeat.
  std::copy(f.frame(40), f.frame(100), f.frame(180));
  EXPECT_DOUBLE_EQ(cm::longest_repeat_s(f, 60), 1.0);
}

TEST(MeasurePil, GrayAndBilinearResizeMatchPillowBitForBit) {
  const fs::path d = temp_dir("pil");
  candela::Image im;
  im.width = 97;
  im.height = 61;
  im.channels = 3;
  std::mt19937 rng(11);
  im.pixels.resize(97 * 61 * 3);
  for (uint8_t& p : im.pixels) p = static_cast<uint8_t>(rng() & 255);
  candela::write_png((d / "00001.png").string(), im);
  const cm::Frames g = cm::load_frames(d.string());
  ASSERT_EQ(g.count, 1);
  struct Size {
    int w, h;
  };
  const Size sizes[] = {{36, 23}, {190, 117}, {97, 30}, {50, 61}, {8, 8}};
  std::string script =
      "import sys\nfrom PIL import Image\nim = Image.open(sys.argv[1]).convert('L')\n"
      "open(sys.argv[2] + '/gray.u8', 'wb').write(im.tobytes())\n";
  for (const Size& s : sizes)
    script += "open(sys.argv[2] + '/" + std::to_string(s.w) + "x" + std::to_string(s.h) +
              ".u8', 'wb').write(im.resize((" + std::to_string(s.w) + ", " + std::to_string(s.h) +
              "), Image.BILINEAR).tobytes())\n";
  std::ofstream(d / "pil.py") << script;
  const std::string cmd = "/usr/bin/python3 " + (d / "pil.py").string() + " " +
                          (d / "00001.png").string() + " " + d.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << " (needs python3-pil: board/install-deps.sh)";
  auto read = [&](const std::string& name) {
    std::ifstream in(d / name, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(read("gray.u8"), g.pixels) << "convert('L')";
  for (const Size& s : sizes) {
    const cm::Frames r = cm::resize_bilinear_pil(g, s.w, s.h);
    EXPECT_EQ(read(std::to_string(s.w) + "x" + std::to_string(s.h) + ".u8"), r.pixels)
        << "resize to " << s.w << "x" << s.h;
  }
  fs::remove_all(d);
}

TEST(MeasureErrors, BadFoldersSayWhatIsWrongAndWhere) {
  const fs::path d = temp_dir("errors");
  auto message = [](const std::string& dir) -> std::string {
    try {
      cm::features(cm::load_frames(dir), 30, dir);
    } catch (const candela::ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(message(d.string()).find("no PNG frames"), std::string::npos) << message(d.string());

  candela::Image black;
  black.width = 40;
  black.height = 30;
  black.channels = 1;
  black.pixels.assign(40 * 30, 0);
  candela::write_png((d / "00001.png").string(), black);
  candela::write_png((d / "00002.png").string(), black);
  EXPECT_NE(message(d.string()).find("no flame found"), std::string::npos) << message(d.string());

  candela::Image other = black;
  other.width = 30;
  other.height = 40;
  candela::write_png((d / "00003.png").string(), other);
  std::string m = message(d.string());
  EXPECT_NE(m.find("00003.png"), std::string::npos) << m;
  EXPECT_NE(m.find("same size"), std::string::npos) << m;

  fs::remove(d / "00003.png");
  std::ofstream(d / "00003.png") << "not a png";
  m = message(d.string());
  EXPECT_NE(m.find("00003.png"), std::string::npos) << m;
  EXPECT_NE(m.find("expected a PNG file"), std::string::npos) << m;

  // A truncated PNG (a real header, then nothing) is named too.
  fs::remove(d / "00003.png");
  {
    std::ifstream in(d / "00001.png", std::ios::binary);
    std::string bytes(std::istreambuf_iterator<char>(in), {});
    std::ofstream(d / "00003.png", std::ios::binary) << bytes.substr(0, 40);
  }
  m = message(d.string());
  EXPECT_NE(m.find("00003.png"), std::string::npos) << m;

  EXPECT_NE(message((d / "missing").string()).find("expected a folder"), std::string::npos);
  fs::remove_all(d);
}

TEST(MeasureErrors, FrameLimitAndSizeLimitHold) {
  const fs::path d = temp_dir("limits");
  candela::Image im;
  im.width = 20;
  im.height = 20;
  im.channels = 1;
  im.pixels.assign(400, 0);
  for (int i = 1; i <= 5; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%05d.png", i);
    candela::write_png((d / name).string(), im);
  }
  cm::LoadLimits l;
  l.max_frames = 3;
  EXPECT_EQ(cm::load_frames(d.string(), l).count, 3);
  l.max_side = 16;
  EXPECT_THROW(cm::load_frames(d.string(), l), candela::ConfigError);
  l = {};
  l.max_bytes = 1000;  // 5 frames of 400 bytes
  EXPECT_THROW(cm::load_frames(d.string(), l), candela::ConfigError);
  fs::remove_all(d);
}

namespace {

// A "clip" with given features and a brightness series (noise of a given
// spectral colour), enough for judge().
cm::Measured made_up(double iso, double parts, double beta, unsigned seed) {
  cm::Measured m;
  m.fps = 30;
  m.features.tau_s = 0.03;
  m.features.sharp = 0.08;
  m.features.spat_slope = -2.8;
  m.features.iso = iso;
  m.features.parts = parts;
  m.features.area_cv = 0.06;
  m.features.core = 0.1;
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  const int n = 600;
  std::vector<double> x(n, 0.0);
  double a = 0, b = 0;
  for (int i = 0; i < n; ++i) {  // a leaky sum: redder as beta grows
    a = beta * a + g(rng);
    b = 0.5 * b + a;
    x[static_cast<size_t>(i)] = 100 + b;
  }
  m.series.I = m.series.H = m.series.X = m.series.W = x;
  return m;
}

}  // namespace

TEST(MeasureJudge, AModelOfOneClipIsJudgedAgainstThatClip) {
  // Three real clips; the model of the first sits just beyond the range on
  // iso (as its source does), inside on parts.
  const std::vector<cm::Measured> real = {made_up(21.4, 7.0, 0.9, 1), made_up(18.0, 6.4, 0.9, 2),
                                          made_up(14.7, 6.3, 0.9, 3)};
  const cm::Measured model = made_up(22.0, 6.6, 0.9, 4);
  const cm::Judgement plain = cm::judge(real, model, {"iso", "parts"}, true);
  EXPECT_FALSE(plain.features[0].inside) << "22.0 is above the real range";
  cm::SourceJudging by{0, 0.1};
  const cm::Judgement sourced = cm::judge(real, model, {"iso", "parts"}, true, 0.0, by);
  EXPECT_TRUE(sourced.features[0].inside) << "within 10% of its source's 21.4";
  EXPECT_DOUBLE_EQ(sourced.features[0].source, 21.4);
  EXPECT_TRUE(sourced.features[1].inside);
  // Each series is measured against the source alone, against the spread of all.
  ASSERT_EQ(sourced.spectra.size(), 4u);
  for (const auto& s : sourced.spectra) {
    EXPECT_EQ(s.lsd_to_ref.size(), 1u);
    EXPECT_DOUBLE_EQ(s.real_max, plain.spectra[0].real_max);
  }
  by.tolerance = 0.01;  // 22.0 is 2.8% from 21.4
  EXPECT_FALSE(cm::judge(real, model, {"iso"}, false, 0.0, by).features[0].inside);
  // A model whose motion is another colour of noise is not its source.
  const cm::Measured white = made_up(21.4, 7.0, 0.0, 5);
  const cm::Judgement far = cm::judge(real, white, {}, true, 0.0, cm::SourceJudging{0, 0.1});
  EXPECT_FALSE(far.spectra[0].inside);
}
