// candela-tool studio under Xvfb (ctest runs this program inside xvfb-run),
// driven by --script: the studio's flame answers a weight edit as
// render-weights does, the PCA view rotates without touching the flame, "save
// as scene" writes what candela --check accepts with the edited values, and a
// broken model shows its error in the window.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/image.h"
#include "story/story_file.h"
#include "support/correlation.h"

namespace fs = std::filesystem;

namespace {

const std::string kFire = std::string(CANDELA_SOURCE_DIR) + "/firmware/models/fire.cmodel";

std::string work(const std::string& name) {
  fs::create_directories(STUDIO_WORK_DIR);
  return std::string(STUDIO_WORK_DIR) + "/" + name;
}

int run(const std::string& cmd) {
  const int rc = std::system((cmd + " > " + work("last.log") + " 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string log_text() {
  std::ifstream in(work("last.log"));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs the studio with these script lines; returns its exit status.
int studio(const std::string& model, const std::string& name, const std::string& lines) {
  const std::string script = work(name + ".script");
  std::ofstream(script) << lines;
  return run(std::string(CANDELA_TOOL) + " studio " + model + " --size 1280x720 --script " +
             script);
}

std::map<std::string, std::string> read_dump(const std::string& path) {
  std::map<std::string, std::string> d;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find(" = ");
    if (eq != std::string::npos) d[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return d;
}

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::istringstream in(s);
  for (double x; in >> x;) v.push_back(x);
  return v;
}

double luma(const candela::Image& img, int x, int y) {
  return 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
}

// The window's pixels inside `rect` (x y w h) averaged down to w x h luma.
std::vector<double> region(const candela::Image& img, const std::vector<double>& rect, int w,
                           int h) {
  std::vector<double> out(static_cast<size_t>(w) * h, 0.0);
  const double sx = rect[2] / w, sy = rect[3] / h;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const int x0 = static_cast<int>(rect[0] + i * sx),
                x1 = static_cast<int>(rect[0] + (i + 1) * sx);
      const int y0 = static_cast<int>(rect[1] + j * sy),
                y1 = static_cast<int>(rect[1] + (j + 1) * sy);
      double s = 0;
      int n = 0;
      for (int y = y0; y < std::max(y1, y0 + 1); ++y)
        for (int x = x0; x < std::max(x1, x0 + 1); ++x) s += luma(img, x, y), ++n;
      out[static_cast<size_t>(j) * w + i] = s / n;
    }
  return out;
}

std::vector<double> whole(const candela::Image& img) {
  return region(img, {0, 0, static_cast<double>(img.width), static_cast<double>(img.height)},
                img.width, img.height);
}

std::vector<double> minus(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> d(a.size());
  for (size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
  return d;
}

double mean_abs(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += std::abs(x);
  return s / v.size();
}

TEST(Studio, AWeightEditChangesTheFlameAsRenderWeightsDoes) {
  ASSERT_EQ(studio(kFire, "weight",
                   "pause\nframe 40\nwait 2\ndump " + work("w0.txt") + "\nscreenshot " +
                       work("w0.png") + "\nset weight 3 +2.0\nwait 2\ndump " + work("w1.txt") +
                       "\nscreenshot " + work("w1.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d0 = read_dump(work("w0.txt")), d1 = read_dump(work("w1.txt"));
  ASSERT_EQ(d1.at("ok"), "1");
  EXPECT_EQ(d1.at("model_frame"), "40");
  const auto base = numbers(d1.at("base")), shown = numbers(d1.at("shown"));
  ASSERT_GT(shown.size(), 3u);
  EXPECT_GT(shown[3] - base[3], 0) << "a +2 sigma offset raises weight 3";
  EXPECT_EQ(numbers(d0.at("shown"))[3], base[3]) << "before the edit the frame's own weight";
  for (size_t k = 0; k < shown.size(); ++k)
    if (k != 3) {
      EXPECT_EQ(shown[k], base[k]) << "weight " << k << " untouched";
    }

  // The same edit through render-weights (the CPU reconstruction and colour).
  char set[64];
  std::snprintf(set, sizeof set, "3=%.9g", shown[3]);
  const std::string rw = std::string(CANDELA_TOOL) + " render-weights " + kFire + " --frame 40";
  ASSERT_EQ(run(rw + " --out " + work("r0.png")), 0) << log_text();
  ASSERT_EQ(run(rw + " --set " + set + " --out " + work("r1.png")), 0) << log_text();
  const auto r0 = candela::read_png(work("r0.png"), 3), r1 = candela::read_png(work("r1.png"), 3);
  const auto s0 = candela::read_png(work("w0.png"), 3), s1 = candela::read_png(work("w1.png"), 3);
  const auto rect = numbers(d1.at("flame_image"));
  ASSERT_EQ(rect.size(), 4u);
  const auto ds =
      minus(region(s1, rect, r0.width, r0.height), region(s0, rect, r0.width, r0.height));
  const auto dr = minus(whole(r1), whole(r0));
  const double c = candela::test::correlation(ds, dr), ratio = mean_abs(ds) / mean_abs(dr);
  std::printf(
      "weight 3 +2 sigma: studio change %.2f, render-weights %.2f (ratio %.2f), correlation %.3f\n",
      mean_abs(ds), mean_abs(dr), ratio, c);
  EXPECT_GT(mean_abs(dr), 1.0) << "the edit is visible in render-weights";
  EXPECT_GT(c, 0.8) << "the flame changes where and as render-weights' does";
  EXPECT_GT(ratio, 0.6);
  EXPECT_LT(ratio, 1.6);
}

TEST(Studio, RotatingThePcaViewChangesItAndNotTheFlame) {
  ASSERT_EQ(studio(kFire, "rotate",
                   "pause\nframe 10\nwait 2\ndump " + work("p0.txt") + "\nscreenshot " +
                       work("p0.png") + "\ndrag pca 120 0\nwait 2\ndump " + work("p1.txt") +
                       "\nscreenshot " + work("p1.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d0 = read_dump(work("p0.txt")), d1 = read_dump(work("p1.txt"));
  EXPECT_NEAR(std::stod(d1.at("pca_yaw")) - std::stod(d0.at("pca_yaw")), 1.2, 1e-4);
  const auto a = candela::read_png(work("p0.png"), 3), b = candela::read_png(work("p1.png"), 3);
  const auto pca = numbers(d1.at("pca")), flame = numbers(d1.at("flame_view"));
  const int pw = static_cast<int>(pca[2]), ph = static_cast<int>(pca[3]);
  const double pca_change = mean_abs(minus(region(b, pca, pw, ph), region(a, pca, pw, ph)));
  const int fw = static_cast<int>(flame[2]), fh = static_cast<int>(flame[3]);
  const double flame_change = mean_abs(minus(region(b, flame, fw, fh), region(a, flame, fw, fh)));
  std::printf("PCA view change %.3f, flame change %.3f (mean |luma| difference)\n", pca_change,
              flame_change);
  EXPECT_GT(pca_change, 0.3) << "the tracks moved";
  EXPECT_LT(flame_change, 0.01) << "the flame did not";
}

TEST(Studio, SaveAsSceneWritesACheckedSceneWithTheEdits) {
  const std::string scene = work("edited.toml");
  fs::remove(scene);
  ASSERT_EQ(studio(kFire, "save",
                   "set hue 200\nset saturation 0.5\nset brightness 1.25\nset glow_radius 0.2\n"
                   "set glow_strength 0.75\nspeed 1.5\nsave-scene " +
                       scene + "\ndump " + work("s.txt") + "\nquit\n"),
            0)
      << log_text();
  EXPECT_EQ(read_dump(work("s.txt")).at("status"), "saved " + scene);
  ASSERT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + scene), 0) << log_text();
  std::ifstream in(scene);
  std::map<std::string, std::string> keys;
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find(" = ");
    if (eq != std::string::npos && line[0] != '#') keys[line.substr(0, eq)] = line.substr(eq + 3);
  }
  EXPECT_EQ(keys["kind"], "\"eigenflame\"");
  EXPECT_EQ(keys["model"], "\"" + fs::absolute(kFire).lexically_normal().string() + "\"");
  EXPECT_DOUBLE_EQ(std::stod(keys["hue"]), 200);
  EXPECT_DOUBLE_EQ(std::stod(keys["saturation"]), 0.5);
  EXPECT_DOUBLE_EQ(std::stod(keys["brightness"]), 1.25);
  EXPECT_DOUBLE_EQ(std::stod(keys["glow_radius"]), 0.2);
  EXPECT_DOUBLE_EQ(std::stod(keys["glow_strength"]), 0.75);
  EXPECT_DOUBLE_EQ(std::stod(keys["speed"]), 1.5);
}

// Green over red of the flame's bright pixels (the colour of the ramp shown).
double green_over_red(const candela::Image& img, const std::vector<double>& r) {
  double red = 0, green = 0;
  for (int y = static_cast<int>(r[1]); y < r[1] + r[3]; ++y)
    for (int x = static_cast<int>(r[0]); x < r[0] + r[2]; ++x)
      if (img.at(x, y, 0) > 60) red += img.at(x, y, 0), green += img.at(x, y, 1);
  return red > 0 ? green / red : -1;
}

TEST(Studio, ATransferFunctionColoursTheFlameAndIsSaved) {
  const std::string scene = work("transfer.toml");
  fs::remove(scene);
  ASSERT_EQ(studio(kFire, "transfer",
                   "pause\nframe 40\nwait 2\ndump " + work("f0.txt") + "\nscreenshot " +
                       work("f0.png") + "\nset transfer #000000 #a00000 #ff2000 #ffd0d0\nwait 2\n" +
                       "screenshot " + work("f1.png") + "\nsave-scene " + scene +
                       "\nundo\nwait 2\n" + "screenshot " + work("f2.png") + "\nquit\n"),
            0)
      << log_text();
  const auto rect = numbers(read_dump(work("f0.txt")).at("flame_image"));
  const double hls = green_over_red(candela::read_png(work("f0.png"), 3), rect);
  const double red = green_over_red(candela::read_png(work("f1.png"), 3), rect);
  const double undone = green_over_red(candela::read_png(work("f2.png"), 3), rect);
  std::printf("green/red of the flame: HLS %.3f, red transfer %.3f, undone %.3f\n", hls, red,
              undone);
  EXPECT_GT(hls, 0.3) << "the model's orange";
  EXPECT_LT(red, 0.6 * hls) << "the red ramp";
  EXPECT_NEAR(undone, hls, 0.01) << "undo brings the HLS ramp back";
  ASSERT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + scene), 0) << log_text();
  std::ifstream in(scene);
  std::stringstream saved;
  saved << in.rdbuf();
  EXPECT_NE(saved.str().find("\ntransfer = \"#000000 #a00000 #ff2000 #ffd0d0\""), std::string::npos)
      << saved.str();
}

TEST(Studio, FindsTheModelsReports) {
  // A model with what `candela-tool build` writes beside it: MODEL.report/*.png.
  const std::string model = work("reported.cmodel"), folder = model + ".report";
  fs::copy_file(kFire, model, fs::copy_options::overwrite_existing);
  fs::create_directories(folder);
  candela::Image img;
  img.width = 64;
  img.height = 32;
  img.channels = 3;
  img.pixels.assign(64 * 32 * 3, 200);
  candela::write_png(folder + "/psnr.png", img);
  candela::write_png(folder + "/eigenfires.png", img);
  std::ofstream(folder + "/notes.txt") << "not a report";
  ASSERT_EQ(studio(model, "reports",
                   "wait 1\nshow reports\nwait 3\ndump " + work("r.txt") + "\nscreenshot " +
                       work("r.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d = read_dump(work("r.txt"));
  EXPECT_EQ(d.at("reports"), "eigenfires.png psnr.png");
  // The first tab's image (uniform gray 200), fitted to the controls' width.
  const auto shot = candela::read_png(work("r.png"), 3);
  const int controls_w = static_cast<int>(numbers(d.at("flame_view"))[0]);
  int gray = 0;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < controls_w; ++x)
      gray += shot.at(x, y, 0) == 200 && shot.at(x, y, 1) == 200 && shot.at(x, y, 2) == 200;
  EXPECT_GT(gray, 200 * 100) << "the report is shown";
  ASSERT_EQ(studio(kFire, "noreports", "wait 1\ndump " + work("r0.txt") + "\nquit\n"), 0);
  EXPECT_EQ(read_dump(work("r0.txt")).at("reports"), "");
}

TEST(Studio, ABrokenModelShowsItsErrorInTheWindow) {
  const std::string broken = work("truncated.cmodel");
  {
    std::ifstream in(kFire, std::ios::binary);
    std::vector<char> bytes(4096);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    std::ofstream(broken, std::ios::binary).write(bytes.data(), in.gcount());
  }
  ASSERT_EQ(studio(broken, "broken",
                   "wait 2\ndump " + work("e.txt") + "\nscreenshot " + work("e.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d = read_dump(work("e.txt"));
  EXPECT_EQ(d.at("ok"), "0");
  EXPECT_NE(d.at("error").find(broken), std::string::npos) << d.at("error");
  EXPECT_GT(d.at("error").size(), broken.size() + 10) << "and says what is wrong";
  // The window shows it: the controls' corner holds text (light pixels on the dark panel).
  const auto img = candela::read_png(work("e.png"), 3);
  int light = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 300; ++x) light += luma(img, x, y) > 150;
  EXPECT_GT(light, 200);
}

TEST(Studio, AStoryThatCannotBePlannedShowsWhy) {
  const std::string story =
      std::string(CANDELA_SOURCE_DIR) + "/tests/elements/eigenflame/data/bad-clip.story.toml";
  ASSERT_EQ(
      studio("builtin:fire " + story, "badstory", "wait 2\ndump " + work("b.txt") + "\nquit\n"), 0)
      << log_text();
  const auto d = read_dump(work("b.txt"));
  EXPECT_EQ(d.at("ok"), "0");
  EXPECT_NE(
      d.at("error").find("bad-clip.story.toml: segment[1].clip: expected a clip of the model"),
      std::string::npos)
      << d.at("error");
}

TEST(Studio, ClickingATrackJumpsToThatFrame) {
  ASSERT_EQ(studio(kFire, "click",
                   "pause\nframe 50\nwait 2\ndump " + work("c0.txt") +
                       "\nframe 200\nwait 2\ndump " + work("c1.txt") + "\n"),
            0)
      << log_text();
  const auto at50 = numbers(read_dump(work("c0.txt")).at("pca_marker"));
  ASSERT_EQ(read_dump(work("c1.txt")).at("model_frame"), "200");
  // Click where frame 50 was drawn (a tiny offset: a user is never exact),
  // with real X button events at the window's pixel.
  const auto pca = numbers(read_dump(work("c0.txt")).at("pca"));
  const std::string px = std::to_string(static_cast<int>(std::lround(pca[0] + at50[0] + 0.6))) +
                         " " +
                         std::to_string(static_cast<int>(std::lround(pca[1] + at50[1] - 0.4)));
  ASSERT_EQ(studio(kFire, "click2",
                   "pause\nframe 200\nwait 2\nx-move " + px + "\nwait 1\nx-press " + px +
                       "\nwait 1\nx-release " + px + "\nwait 2\ndump " + work("c2.txt") + "\n"),
            0)
      << log_text();
  const auto d = read_dump(work("c2.txt"));
  EXPECT_EQ(d.at("playing"), "0") << "a click pauses on the frame";
  const auto now = numbers(d.at("pca_marker"));
  // Frame 50, or a frame drawn on the very same spot.
  EXPECT_LT(std::hypot(now[0] - at50[0], now[1] - at50[1]), 2.0)
      << "jumped to frame " << d.at("model_frame");
  EXPECT_NE(d.at("model_frame"), "200");
}

TEST(Studio, UndoTakesBackEditsOneAtATime) {
  ASSERT_EQ(studio(kFire, "undo",
                   "pause\nset weight 2 1.5\nset hue 100\nwait 1\ndump " + work("u0.txt") +
                       "\nundo\nwait 1\ndump " + work("u1.txt") + "\nundo\nwait 1\ndump " +
                       work("u2.txt") + "\nquit\n"),
            0)
      << log_text();
  const auto u0 = read_dump(work("u0.txt")), u1 = read_dump(work("u1.txt")),
             u2 = read_dump(work("u2.txt"));
  EXPECT_EQ(u0.at("hue"), "100");
  EXPECT_EQ(u0.at("undo_depth"), "2");
  EXPECT_NE(u1.at("hue"), "100") << "the hue edit undone";
  EXPECT_NE(numbers(u1.at("shown"))[2], numbers(u1.at("base"))[2]) << "the weight edit kept";
  EXPECT_EQ(numbers(u2.at("shown"))[2], numbers(u2.at("base"))[2]) << "and then undone";
  EXPECT_EQ(u2.at("undo_depth"), "0");
}

// Real X events (sent to the window through the X server) take the path a
// user's input takes: window backend -> X11 platform -> ImGui -> the views.
TEST(Studio, MouseAndKeysWorkThroughX) {
  ASSERT_EQ(studio(kFire, "xlayout", "wait 1\ndump " + work("x0.txt") + "\nquit\n"), 0)
      << log_text();
  const auto pca = numbers(read_dump(work("x0.txt")).at("pca"));
  const int cx = static_cast<int>(pca[0] + pca[2] / 2), cy = static_cast<int>(pca[1] + pca[3] / 2);
  auto at = [](int x, int y) { return std::to_string(x) + " " + std::to_string(y); };
  std::string s =
      "pause\nwait 1\nx-move " + at(cx, cy) + "\nwait 1\nx-press " + at(cx, cy) + "\nwait 1\n";
  for (int i = 1; i <= 4; ++i) s += "x-move " + at(cx + 20 * i, cy - 10 * i) + "\nwait 1\n";
  s += "x-release " + at(cx + 80, cy - 40) + "\nwait 1\nx-wheel " + at(cx, cy) +
       " 2\nwait 2\nset weight 2 1.0\nwait 1\ndump " + work("x1.txt") +
       "\nx-key ctrl+z\nwait 2\nx-key space\nwait 2\ndump " + work("x2.txt") + "\nquit\n";
  ASSERT_EQ(studio(kFire, "xinput", s), 0) << log_text();
  const auto d0 = read_dump(work("x0.txt")), d1 = read_dump(work("x1.txt")),
             d2 = read_dump(work("x2.txt"));
  // A drag of (+80, -40) pixels turns the view by 0.01 rad a pixel.
  EXPECT_NEAR(std::stod(d1.at("pca_yaw")) - std::stod(d0.at("pca_yaw")), 0.8, 1e-4);
  EXPECT_NEAR(std::stod(d1.at("pca_pitch")) - std::stod(d0.at("pca_pitch")), -0.4, 1e-4);
  EXPECT_NEAR(std::stod(d1.at("pca_zoom")), 1.15 * 1.15, 1e-4) << "two wheel clicks";
  EXPECT_EQ(d1.at("undo_depth"), "1");
  EXPECT_EQ(d2.at("undo_depth"), "0") << "Ctrl+Z undid the weight edit";
  EXPECT_EQ(numbers(d2.at("shown"))[2], numbers(d2.at("base"))[2]);
  EXPECT_EQ(d1.at("playing"), "0");
  EXPECT_EQ(d2.at("playing"), "1") << "space plays";
}

TEST(Studio, TheWindowResizesAndTheLayoutFollows) {
  ASSERT_EQ(studio(kFire, "resize",
                   "pause\nframe 40\nresize 1000 600\nwait 6\ndump " + work("z.txt") +
                       "\nscreenshot " + work("z.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d = read_dump(work("z.txt"));
  EXPECT_EQ(d.at("window"), "1000 600");
  const auto img = candela::read_png(work("z.png"), 3);
  EXPECT_EQ(img.width, 1000);
  EXPECT_EQ(img.height, 600);
  const auto pca = numbers(d.at("pca")), fl = numbers(d.at("flame_image"));
  EXPECT_LE(pca[0] + pca[2], 1000);
  EXPECT_LE(pca[1] + pca[3], 600);
  EXPECT_LE(fl[1] + fl[3], 600);
  // The flame is drawn in its resized view: bright pixels inside the image.
  const auto lum = region(img, fl, static_cast<int>(fl[2]), static_cast<int>(fl[3]));
  int bright = 0;
  for (double v : lum) bright += v > 100;
  EXPECT_GT(bright, 200);
}

TEST(Studio, AStoryPlaysItsPlannedFrames) {
  // The same planner as `candela-tool story`: as many frames as it prints.
  ASSERT_EQ(run(std::string(CANDELA_TOOL) + " story builtin:fire-tour --no-render"), 0)
      << log_text();
  const std::string text = log_text();
  const size_t at = text.find("<built-in story fire-tour>: ");
  ASSERT_NE(at, std::string::npos) << text;
  const int planned = std::stoi(text.substr(at + 28));
  ASSERT_EQ(
      studio("builtin:fire builtin:fire-tour", "story",
             "wait 30\ndump " + work("t.txt") + "\nsave-scene " + work("story.toml") + "\nquit\n"),
      0)
      << log_text();
  const auto d = read_dump(work("t.txt"));
  ASSERT_EQ(d.at("ok"), "1") << d.at("error");
  EXPECT_EQ(std::stoi(d.at("frames")), planned);
  EXPECT_GT(std::stoi(d.at("frame")), 5) << "it plays";
  // Saved as a scene, the element plays the story (no model key: the story names it).
  ASSERT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + work("story.toml")), 0)
      << log_text();
  std::ifstream in(work("story.toml"));
  std::stringstream saved;
  saved << in.rdbuf();
  EXPECT_NE(saved.str().find("story = \"builtin:fire-tour\"\n"), std::string::npos) << saved.str();
  EXPECT_EQ(saved.str().find("\nmodel = "), std::string::npos) << saved.str();
}

// ---------------------------------------------------------------------------
// Weight edits saved as the element's keys (weight_offsets, detail_scale) and
// played by `candela` headless.

// A story that holds one stretch of the fire (frames 40-47): at speed 0.05 the
// scene shows its first frame for the first 30 animation steps, the frame the
// paused studio shows at timeline frame 0.
std::string still_story() {
  const std::string path = work("still.story.toml");
  std::ofstream(path) << "model = \"builtin:fire\"\nseed = 3\nloop = true\n[[segment]]\n"
                         "clip = \"fire-calm\"\nfrom = 40\nto = 48\n";
  return path;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The scene's text without the lines that start with `key = `.
std::string without_key(std::string text, const std::string& key) {
  for (size_t at; (at = text.find("\n" + key + " = ")) != std::string::npos;)
    text.erase(at + 1, text.find('\n', at + 1) - at);
  return text;
}

constexpr int kSceneW = 640, kSceneH = 480;

// Renders a scene headless (its second frame) and returns it.
candela::Image render_scene(const std::string& scene, const std::string& name) {
  const std::string dir = work(name + ".frames");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int rc = run(std::string(CANDELA_BIN) + " --display headless --scene " + scene +
                     " --size " + std::to_string(kSceneW) + "x" + std::to_string(kSceneH) +
                     " --frames 2 --mute --out " + dir);
  EXPECT_EQ(rc, 0) << log_text();
  return candela::read_png(dir + "/frame_000001.png", 3);
}

// Where the studio's saved scene draws the model's image (x y w h, pixels of
// a kSceneW x kSceneH frame): its camera (position [0, 0.32, 1.7], target
// [0, 0.3, 0], fov 40) looking at the upright billboard at the origin, 0.62 high.
std::vector<double> scene_image_rect(double aspect) {
  const double cx = 0, cy = 0.32, cz = 1.7, tx = 0, ty = 0.3, tz = 0, h = 0.62;
  double fx = tx - cx, fy = ty - cy, fz = tz - cz;
  const double fl = std::sqrt(fx * fx + fy * fy + fz * fz);
  fx /= fl, fy /= fl, fz /= fl;
  // right = f x up (0, 1, 0); u = right x f
  double rx = -fz, ry = 0, rz = fx;
  const double rl = std::sqrt(rx * rx + rz * rz);
  rx /= rl, rz /= rl;
  const double ux = ry * fz - rz * fy, uy = rz * fx - rx * fz, uz = rx * fy - ry * fx;
  const double t = std::tan(20.0 * M_PI / 180.0), a = static_cast<double>(kSceneW) / kSceneH;
  auto project = [&](double x, double y) {
    const double dx = x - cx, dy = y - cy, dz = -cz;
    const double xc = dx * rx + dy * ry + dz * rz, yc = dx * ux + dy * uy + dz * uz,
                 zc = dx * fx + dy * fy + dz * fz;
    return std::pair{(xc / (zc * t * a) + 1) / 2 * kSceneW, (1 - yc / (zc * t)) / 2 * kSceneH};
  };
  const auto [x0, y0] = project(-aspect * h / 2, h);
  const auto [x1, y1] = project(aspect * h / 2, 0);
  return {x0, y0, x1 - x0, y1 - y0};
}

// Mean |horizontal + vertical gray steps|: how much fine detail an image holds.
double detail(const std::vector<double>& img, int w, int h) {
  double s = 0;
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      const double v = img[static_cast<size_t>(y) * w + x];
      s += std::abs(img[static_cast<size_t>(y) * w + x + 1] - v) +
           std::abs(img[static_cast<size_t>(y + 1) * w + x] - v);
    }
  return s / ((w - 1.0) * (h - 1.0));
}

struct EditComparison {
  double studio_change, scene_change, change_correlation, image_correlation;
  double studio_detail[2], scene_detail[2];  // before, after the edit
};

// The studio (paused on the still story, after `setup`) before and after
// `edit`, saved as a scene; the scene rendered headless as saved and as
// `unedit` makes it (default: without its weight keys); the change each
// shows, on the model's pixel grid.
EditComparison compare_edit(
    const std::string& name, const std::string& edit, std::string* saved = nullptr,
    const std::string& setup = "",
    const std::function<std::string(const std::string&)>& unedit = [](const std::string& t) {
      return without_key(without_key(t, "weight_offsets"), "detail_scale");
    }) {
  const std::string scene = work(name + ".toml");
  fs::remove(scene);
  EditComparison r{};
  EXPECT_EQ(studio("builtin:fire " + still_story(), name,
                   "pause\nframe 0\nspeed 0.05\n" + setup + "wait 2\ndump " + work(name + "0.txt") +
                       "\nscreenshot " + work(name + "0.png") + "\n" + edit + "wait 2\ndump " +
                       work(name + "1.txt") + "\nscreenshot " + work(name + "1.png") +
                       "\nsave-scene " + scene + "\nquit\n"),
            0)
      << log_text();
  EXPECT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + scene), 0) << log_text();
  const std::string text = file_text(scene);
  if (saved) *saved = text;
  const std::string plain = work(name + "-plain.toml");
  std::ofstream(plain) << unedit(text);

  const auto d1 = read_dump(work(name + "1.txt"));
  const auto rect = numbers(d1.at("flame_image"));
  const int mw = 64, mh = static_cast<int>(std::lround(64 * rect[3] / rect[2]));
  const auto s0 = region(candela::read_png(work(name + "0.png"), 3), rect, mw, mh);
  const auto s1 = region(candela::read_png(work(name + "1.png"), 3), rect, mw, mh);
  const auto srect = scene_image_rect(rect[2] / rect[3]);
  const auto f0 = region(render_scene(plain, name + "-plain"), srect, mw, mh);
  const auto f1 = region(render_scene(scene, name), srect, mw, mh);
  const auto ds = minus(s1, s0), df = minus(f1, f0);
  r.studio_change = mean_abs(ds);
  r.scene_change = mean_abs(df);
  r.change_correlation = candela::test::correlation(ds, df);
  r.image_correlation = candela::test::correlation(s1, f1);
  r.studio_detail[0] = detail(s0, mw, mh), r.studio_detail[1] = detail(s1, mw, mh);
  r.scene_detail[0] = detail(f0, mw, mh), r.scene_detail[1] = detail(f1, mw, mh);
  std::printf(
      "%s: studio change %.2f, scene change %.2f (mean |luma| on a %dx%d grid), change "
      "correlation %.3f, edited flames' correlation %.3f; detail studio %.2f -> %.2f, scene "
      "%.2f -> %.2f\n",
      name.c_str(), r.studio_change, r.scene_change, mw, mh, r.change_correlation,
      r.image_correlation, r.studio_detail[0], r.studio_detail[1], r.scene_detail[0],
      r.scene_detail[1]);
  return r;
}

TEST(Studio, WeightEditsAreSavedAsKeysAndTheScenePlaysThem) {
  std::string saved;
  const auto r = compare_edit("wkeys", "set weight 1 -2.0\nset weight 4 2.5\n", &saved);
  EXPECT_NE(saved.find("\nweight_offsets = [0.0, -2.0, 0.0, 0.0, 2.5]\n"), std::string::npos)
      << saved;
  EXPECT_EQ(saved.find("detail_scale"), std::string::npos) << "unchanged: not written";
  EXPECT_EQ(saved.find("# studio weight edits"), std::string::npos) << "no longer a comment";
  EXPECT_GT(r.studio_change, 2.0) << "the edit is visible";
  EXPECT_GT(r.scene_change, 2.0) << "and the scene plays it";
  EXPECT_GT(r.change_correlation, 0.8) << "where and as the studio showed it";
  EXPECT_GT(r.scene_change / r.studio_change, 0.6);
  EXPECT_LT(r.scene_change / r.studio_change, 1.6);
  EXPECT_GT(r.image_correlation, 0.9) << "the edited flame is the studio's";
}

// The fire has 256 components: detail_scale = 0 drops the 206 from 50 on.
TEST(Studio, DetailScaleOnTheFireIsSavedAndPlayed) {
  std::string saved;
  const auto r = compare_edit("wdetail", "set detail 0\n", &saved);
  EXPECT_NE(saved.find("\ndetail_scale = 0.0\n"), std::string::npos) << saved;
  EXPECT_EQ(saved.find("weight_offsets"), std::string::npos) << "no offsets: not written";
  EXPECT_LT(r.studio_detail[1], 0.9 * r.studio_detail[0]) << "a smoother flame in the studio";
  EXPECT_LT(r.scene_detail[1], 0.9 * r.scene_detail[0]) << "and in the scene";
  EXPECT_GT(r.change_correlation, 0.7) << "the same detail removed";
  EXPECT_GT(r.scene_change / r.studio_change, 0.5);
  EXPECT_LT(r.scene_change / r.studio_change, 2.0);
}

// The colour panel's "hue at top" (the element's hue_top): a higher top hue
// turns the bright body yellower; saved as the key; undo takes it back.
TEST(Studio, HueTopMakesTheBrightBodyYellowerAndIsSaved) {
  const std::string scene = work("huetop.toml");
  fs::remove(scene);
  ASSERT_EQ(studio(kFire, "huetop",
                   "pause\nframe 40\nset hue 20\nwait 2\ndump " + work("h0.txt") + "\nscreenshot " +
                       work("h0.png") + "\nset hue_top 55\nwait 2\ndump " + work("h1.txt") +
                       "\nscreenshot " + work("h1.png") + "\nsave-scene " + scene +
                       "\nundo\nwait 2\ndump " + work("h2.txt") + "\nscreenshot " + work("h2.png") +
                       "\nquit\n"),
            0)
      << log_text();
  const auto rect = numbers(read_dump(work("h0.txt")).at("flame_image"));
  const auto img0 = candela::read_png(work("h0.png"), 3),
             img1 = candela::read_png(work("h1.png"), 3);
  // The mean hue (HSV, degrees) where the flame is bright (luma over 100) and
  // still coloured (not the white core): its body.
  auto body = [&](const candela::Image& img) {
    double sum = 0;
    int n = 0;
    for (int y = static_cast<int>(rect[1]); y < rect[1] + rect[3]; ++y)
      for (int x = static_cast<int>(rect[0]); x < rect[0] + rect[2]; ++x) {
        const double r = img.at(x, y, 0), g = img.at(x, y, 1), b = img.at(x, y, 2);
        const double hi = std::max({r, g, b}), lo = std::min({r, g, b});
        if (luma(img, x, y) <= 100 || hi - lo <= 20 || hi != r) continue;  // red-led hues only
        sum += 60 * (g - b) / (hi - lo), ++n;
      }
    return n > 0 ? sum / n : -1;
  };
  const double before = body(img0), after = body(img1);
  const double undone = body(candela::read_png(work("h2.png"), 3));
  std::printf(
      "mean hue of the bright body: hue_top = hue %.1f deg, hue_top 55 %.1f deg, "
      "undone %.1f deg\n",
      before, after, undone);
  EXPECT_NEAR(before, 20, 3) << "the hue throughout";
  EXPECT_GT(after, before + 8) << "a yellower body";
  EXPECT_NEAR(undone, before, 0.1) << "undo takes it back";
  EXPECT_EQ(read_dump(work("h1.txt")).at("hue_top"), "55");
  EXPECT_EQ(read_dump(work("h2.txt")).at("hue_top"), "20") << "undone: the hue throughout";
  ASSERT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + scene), 0) << log_text();
  const std::string saved = file_text(scene);
  EXPECT_NE(saved.find("\nhue = 20.0\nhue_top = 55.0\n"), std::string::npos) << saved;
}

// Transfer-function stops moved to chosen places: the flame changes in the
// studio, the scene keeps the places ("#rrggbb@PLACE") and plays the same
// change; a stop stays between its neighbours; undo takes back one move at a time.
TEST(Studio, TransferStopsAtChosenPlacesAreSavedAndPlayed) {
  std::string saved;
  const std::string stops = "#000000 #a00000 #ff2000 #ffd0d0";
  const auto r = compare_edit("tplace", "set stop 1 0.08\nset stop 2 0.35\n", &saved,
                              "set transfer " + stops + "\n", [&](const std::string& t) {
                                const size_t at = t.find("\ntransfer = ");
                                return t.substr(0, at) + "\ntransfer = \"" + stops + "\"\n" +
                                       t.substr(t.find('\n', at + 1) + 1);
                              });
  EXPECT_NE(saved.find("\ntransfer = \"#000000@0.0 #a00000@0.08 #ff2000@0.35 #ffd0d0@1.0\""),
            std::string::npos)
      << saved;
  EXPECT_GT(r.studio_change, 3.0) << "stops lower on the ramp: a brighter flame";
  EXPECT_GT(r.change_correlation, 0.9) << "the scene plays the same ramp";
  EXPECT_GT(r.scene_change / r.studio_change, 0.7);
  EXPECT_LT(r.scene_change / r.studio_change, 1.4);
  EXPECT_EQ(read_dump(work("tplace1.txt")).at("transfer_at"), "0 0.08 0.35 1");
  ASSERT_EQ(studio("builtin:fire", "tundo",
                   "set transfer " + stops + "\nset stop 1 0.08\nset stop 1 0.9\ndump " +
                       work("tu0.txt") + "\nundo\ndump " + work("tu1.txt") + "\nundo\ndump " +
                       work("tu2.txt") + "\nquit\n"),
            0)
      << log_text();
  EXPECT_EQ(read_dump(work("tu0.txt")).at("transfer_at"), "0 0.666667 0.666667 1")
      << "stop 1 stops at stop 2";
  EXPECT_EQ(read_dump(work("tu1.txt")).at("transfer_at"), "0 0.08 0.666667 1");
  EXPECT_EQ(read_dump(work("tu2.txt")).at("transfer_at"), "0 0.333333 0.666667 1");
}

// A stop's place handle dragged with real X input (press on it, move, release).
TEST(Studio, DraggingAStopsPlaceHandleMovesIt) {
  const std::string stops = "#000000 #a00000 #ff2000 #ffd0d0";
  ASSERT_EQ(
      studio("builtin:fire", "tdrag0",
             "pause\nset transfer " + stops + "\nwait 2\ndump " + work("td0.txt") + "\nquit\n"),
      0)
      << log_text();
  const auto row = numbers(read_dump(work("td0.txt")).at("transfer_places"));
  ASSERT_EQ(row.size(), 4u);
  ASSERT_GT(row[2], 100) << "the row of handles is shown";
  auto at = [&](double place) {
    return std::to_string(static_cast<int>(std::lround(row[0] + row[2] * place))) + " " +
           std::to_string(static_cast<int>(std::lround(row[1] + row[3] / 2)));
  };
  // Stop 1 (at 1/3) dragged to 0.15, in steps, and let go; then stop 2 (at
  // 2/3) dragged far left: it stops at stop 1.
  std::string s = "pause\nset transfer " + stops + "\nwait 2\nx-move " + at(1.0 / 3) +
                  "\nwait 1\nx-press " + at(1.0 / 3) + "\nwait 1\n";
  for (double p : {0.28, 0.22, 0.15}) s += "x-move " + at(p) + "\nwait 1\n";
  s += "x-release " + at(0.15) + "\nwait 1\ndump " + work("td1.txt") + "\nx-move " + at(2.0 / 3) +
       "\nwait 1\nx-press " + at(2.0 / 3) + "\nwait 1\nx-move " + at(0.4) + "\nwait 1\nx-move " +
       at(0.02) + "\nwait 1\nx-release " + at(0.02) + "\nwait 1\ndump " + work("td2.txt") +
       "\nquit\n";
  ASSERT_EQ(studio("builtin:fire", "tdrag", s), 0) << log_text();
  const auto p1 = numbers(read_dump(work("td1.txt")).at("transfer_at"));
  const auto p2 = numbers(read_dump(work("td2.txt")).at("transfer_at"));
  ASSERT_EQ(p1.size(), 4u);
  ASSERT_EQ(p2.size(), 4u);
  EXPECT_NEAR(p1[1], 0.15, 1.0 / row[2] + 1e-3) << "stop 1 where it was let go";
  EXPECT_NEAR(p1[2], 2.0 / 3, 1e-5) << "the others stay";
  EXPECT_NEAR(p2[2], p1[1], 1e-6) << "stop 2 stops at stop 1";
  EXPECT_EQ(read_dump(work("td2.txt")).at("undo_depth"), "3") << "set transfer and two drags";
}

// A report is shown fitted to the controls' width; hovering it shows it at
// its own size (the plots' text is a small bitmap font).
TEST(Studio, HoveringAReportShowsItFullSize) {
  const std::string model = work("wide.cmodel"), folder = model + ".report";
  fs::copy_file(kFire, model, fs::copy_options::overwrite_existing);
  fs::remove_all(folder);
  fs::create_directories(folder);
  candela::Image img;
  img.width = 600;
  img.height = 200;
  img.channels = 3;
  img.pixels.resize(600 * 200 * 3);
  for (size_t p = 0; p < img.pixels.size(); p += 3)
    img.pixels[p] = 40, img.pixels[p + 1] = 200, img.pixels[p + 2] = 120;
  candela::write_png(folder + "/trajectory.png", img);
  auto shown = [](const candela::Image& shot, int* cx = nullptr, int* cy = nullptr) {
    int n = 0;
    long sx = 0, sy = 0;
    for (int y = 0; y < shot.height; ++y)
      for (int x = 0; x < shot.width; ++x)
        if (shot.at(x, y, 0) == 40 && shot.at(x, y, 1) == 200 && shot.at(x, y, 2) == 120)
          ++n, sx += x, sy += y;
    if (cx && n) *cx = static_cast<int>(sx / n), *cy = static_cast<int>(sy / n);
    return n;
  };
  ASSERT_EQ(studio(model, "hover0",
                   "pause\nshow reports\nwait 3\nscreenshot " + work("hv0.png") + "\nquit\n"),
            0)
      << log_text();
  int cx = 0, cy = 0;
  const int fitted = shown(candela::read_png(work("hv0.png"), 3), &cx, &cy);
  ASSERT_GT(fitted, 5000) << "the report, fitted";
  const std::string at = std::to_string(cx) + " " + std::to_string(cy);
  ASSERT_EQ(studio(model, "hover1",
                   "pause\nshow reports\nwait 3\nx-move " + at + "\nwait 3\nscreenshot " +
                       work("hv1.png") + "\nquit\n"),
            0)
      << log_text();
  const auto hovered = candela::read_png(work("hv1.png"), 3);
  const int full = shown(hovered);
  // The widest row of the report's colour: the fitted image is at most the
  // controls' width (360), the full-size one 600.
  int widest = 0;
  for (int y = 0; y < hovered.height; ++y)
    for (int x = 0, run = 0; x < hovered.width; ++x) {
      const bool on =
          hovered.at(x, y, 0) == 40 && hovered.at(x, y, 1) == 200 && hovered.at(x, y, 2) == 120;
      run = on ? run + 1 : 0;
      widest = std::max(widest, run);
    }
  std::printf("report pixels: fitted %d, hovered %d (600x200 = 120000), widest row %d\n", fitted,
              full, widest);
  EXPECT_GE(widest, 600) << "shown at its own size";
  EXPECT_GT(full, fitted + 100000);
}

// ---------------------------------------------------------------------------
// The story timeline: joints edited, segments added, removed and moved, each
// edit re-planned by the runtime's planner; saved stories read back.

const std::string kTour = "builtin:fire builtin:fire-tour";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Studio, AJointsMethodIsSavedAndTheStoryPassesItsSeamCheck) {
  const std::string story = work("edited-story.toml"), scene = work("edited-story-scene.toml");
  ASSERT_EQ(studio(kTour, "joint",
                   "pause\nstory method 1 grow\nstory set 1 theta_min 900\nstory set 3 steps 30\n"
                   "save-story " +
                       story + "\nsave-scene " + scene + "\nquit\n"),
            0)
      << log_text();
  // The story reader reads it back with the chosen methods and parameters.
  const candela::story::StoryDesc d = candela::story::load_story_file(story);
  ASSERT_EQ(d.segments.size(), 4u);
  // (The tour bridges segment 1 in: made a grow, it is saved as one.)
  EXPECT_EQ(d.segments[1].transition.method, candela::story::Method::kGrow);
  EXPECT_FLOAT_EQ(d.segments[1].transition.theta_min, 900);
  EXPECT_EQ(d.segments[3].transition.method, candela::story::Method::kGrow);
  EXPECT_EQ(d.segments[3].transition.steps, 30);
  EXPECT_EQ(d.segments[1].repeat, 2);
  EXPECT_EQ(d.segments[3].kind, candela::story::SegmentKind::kWalk);
  EXPECT_EQ(d.seed, 17u);
  // The tool plans it and every joint passes the seam bound (exit 3 otherwise).
  ASSERT_EQ(run(std::string(CANDELA_TOOL) + " story " + story + " --no-render"), 0) << log_text();
  EXPECT_NE(log_text().find("joint segment[0] -> segment[1]             grow"), std::string::npos)
      << log_text();
  // A scene saved after it plays the saved story, and candela --check accepts it.
  EXPECT_NE(text_of(scene).find("story = \"" + story + "\""), std::string::npos) << text_of(scene);
  ASSERT_EQ(run(std::string(CANDELA_BIN) + " --check --scene " + scene), 0) << log_text();
}

TEST(Studio, AddingDeletingAndMovingSegmentsReplansTheStory) {
  // Every joint a cut: the story is exactly its segments' frames
  // (135 + 2 x 135 + 135 + 6 s of walk at 30 fps = 720).
  const std::string cuts =
      "pause\nstory method 0 cut\nstory method 1 cut\nstory method 2 cut\nstory method 3 cut\n";
  const std::string saved = work("moved-story.toml");
  ASSERT_EQ(studio(kTour, "segments",
                   cuts + "dump " + work("s0.txt") + "\nstory add clip fire-calm 0 60\n" +
                       "story method 4 cut\ndump " + work("s1.txt") + "\nstory delete 3\ndump " +
                       work("s2.txt") + "\nstory move 2 right\ndump " + work("s3.txt") +
                       "\nsave-story " + saved + "\nquit\n"),
            0)
      << log_text();
  auto frames = [](const std::string& f) { return std::stoi(read_dump(work(f)).at("frames")); };
  EXPECT_EQ(frames("s0.txt"), 720);
  EXPECT_EQ(frames("s1.txt"), 780) << "a 60-frame segment added";
  EXPECT_EQ(frames("s2.txt"), 600) << "the 6 s walk (180 frames) deleted";
  EXPECT_EQ(frames("s3.txt"), 600) << "a move keeps the frames";
  EXPECT_EQ(read_dump(work("s3.txt")).at("story_segments"), "4");
  const candela::story::StoryDesc d = candela::story::load_story_file(saved);
  ASSERT_EQ(d.segments.size(), 4u);
  EXPECT_EQ(d.segments[2].to, 60) << "the added segment moved left of the last T1";
  EXPECT_EQ(d.segments[3].to, 135);
  // The tool plans the saved story to the studio's frame count.
  ASSERT_EQ(run(std::string(CANDELA_TOOL) + " story " + saved + " --no-render --max-seam 100"), 0)
      << log_text();
  EXPECT_NE(log_text().find(": 600 frames"), std::string::npos) << log_text();
}

TEST(Studio, PreviewJointPlaysFromJustBeforeTheJoint) {
  ASSERT_EQ(studio(kTour, "preview",
                   "pause\nframe 5\npreview joint 2\ndump " + work("p0.txt") + "\nwait 150\ndump " +
                       work("p1.txt") + "\nquit\n"),
            0)
      << log_text();
  const auto d0 = read_dump(work("p0.txt")), d1 = read_dump(work("p1.txt"));
  const int joint = static_cast<int>(numbers(d0.at("story_joint_frames"))[2]);
  const int at = std::stoi(d0.at("frame"));
  EXPECT_LT(at, joint);
  EXPECT_GE(at, joint - 61) << "about two seconds (30 fps) before it";
  EXPECT_EQ(d0.at("playing"), "1");
  EXPECT_GT(std::stoi(d1.at("frame")), joint) << "and it plays through the joint";
}

TEST(Studio, UndoRestoresThePreviousStory) {
  const std::string saved = work("undone-story.toml");
  ASSERT_EQ(studio(kTour, "story-undo",
                   "pause\ndump " + work("u0.txt") + "\nstory method 1 cut\nstory delete 3\ndump " +
                       work("u1.txt") + "\nundo\nundo\ndump " + work("u2.txt") + "\nsave-story " +
                       saved + "\nquit\n"),
            0)
      << log_text();
  const auto u0 = read_dump(work("u0.txt")), u1 = read_dump(work("u1.txt")),
             u2 = read_dump(work("u2.txt"));
  EXPECT_NE(u1.at("frames"), u0.at("frames"));
  EXPECT_EQ(u1.at("story_segments"), "3");
  EXPECT_EQ(u2.at("frames"), u0.at("frames"));
  EXPECT_EQ(u2.at("story_segments"), "4");
  EXPECT_EQ(u2.at("story_seams"), u0.at("story_seams"));
  const candela::story::StoryDesc d = candela::story::load_story_file(saved);
  EXPECT_EQ(d.segments[1].transition.method, candela::story::Method::kBridge);
}

TEST(Studio, ANewStoryFromTheModelsClipsIsSavedAndPlays) {
  const std::string saved = work("new-story.toml");
  ASSERT_EQ(studio(kFire, "new-story",
                   "pause\ndump " + work("n0.txt") +
                       "\nstory new\nstory add walk 2\nstory method 0 lowpass\ndump " +
                       work("n1.txt") + "\nsave-story " + saved + "\nundo\nundo\nundo\ndump " +
                       work("n2.txt") + "\nquit\n"),
            0)
      << log_text();
  EXPECT_EQ(read_dump(work("n0.txt")).at("story_segments"), "0");
  EXPECT_EQ(read_dump(work("n1.txt")).at("story_segments"), "2");
  const auto n2 = read_dump(work("n2.txt"));
  EXPECT_EQ(n2.at("story_segments"), "0") << "undone back to no story";
  EXPECT_EQ(n2.at("frames"), "300") << "the model's own frames again";
  const candela::story::StoryDesc d = candela::story::load_story_file(saved);
  ASSERT_EQ(d.segments.size(), 2u);
  EXPECT_EQ(d.segments[0].clip, "fire-calm");
  // Low-passed where the loop comes back to the clip's start (the fire's
  // first frames are far from the walk's last, as in builtin:fire-tour).
  EXPECT_EQ(d.segments[0].transition.method, candela::story::Method::kLowpass);
  EXPECT_EQ(d.model, fs::absolute(kFire).lexically_normal().string());
  ASSERT_EQ(run(std::string(CANDELA_TOOL) + " story " + saved + " --no-render"), 0) << log_text();
}

TEST(Studio, TheTimelineShowsSegmentsAsWideAsTheirFrames) {
  // All cuts: 720 frames, segment 0 the first 135, segment 1 the next 270.
  ASSERT_EQ(studio(kTour, "timeline",
                   "pause\nstory method 0 cut\nstory method 1 cut\nstory method 2 cut\n"
                   "story method 3 cut\nframe 540\nwait 2\ndump " +
                       work("tl.txt") + "\nscreenshot " + work("tl.png") + "\nquit\n"),
            0)
      << log_text();
  const auto d = read_dump(work("tl.txt"));
  const auto r = numbers(d.at("timeline"));
  ASSERT_EQ(r.size(), 4u);
  ASSERT_GT(r[2], 300);
  const auto img = candela::read_png(work("tl.png"), 3);
  const int y = static_cast<int>(r[1] + 25);  // inside the blocks, under their labels
  auto colour = [&](double x) {
    const int xi = static_cast<int>(x);
    return std::array<int, 3>{img.at(xi, y, 0), img.at(xi, y, 1), img.at(xi, y, 2)};
  };
  auto at_frame = [&](double f) { return r[0] + r[2] * f / 720; };
  // A block's colour changes where the segment does and not inside it.
  EXPECT_EQ(colour(at_frame(30)), colour(at_frame(100)));
  EXPECT_NE(colour(at_frame(100)), colour(at_frame(200)));
  EXPECT_EQ(colour(at_frame(200)), colour(at_frame(400)));  // both repeats of segment 1
  EXPECT_NE(colour(at_frame(400)), colour(at_frame(470)));
  // The play position: a white line at frame 540 of 720.
  int whitest = -1, best = 0;
  for (int x = static_cast<int>(r[0]); x < static_cast<int>(r[0] + r[2]); ++x) {
    const auto c = colour(x);
    if (c[0] + c[1] + c[2] > best) best = c[0] + c[1] + c[2], whitest = x;
  }
  EXPECT_EQ(best, 3 * 255);
  EXPECT_NEAR(whitest, at_frame(540), 3);
  EXPECT_EQ(d.at("story_selected"), "0");
}

// Script lines that click the tour's walk (segment 3) on the timeline, in
// the middle of its block (between its joint and the loop joint), where a
// first run of the studio dumps the timeline's place.
std::string click_the_walk() {
  if (studio(kTour, "tl-rect", "pause\nwait 2\ndump " + work("tr.txt") + "\nquit\n") != 0) {
    ADD_FAILURE() << log_text();
    return "";
  }
  const auto tr = read_dump(work("tr.txt"));
  const auto r = numbers(tr.at("timeline"));
  const auto joints = numbers(tr.at("story_joint_frames"));
  if (r.size() != 4u || joints.size() < 4u) {
    ADD_FAILURE() << "timeline " << tr.at("timeline") << ", joints " << tr.at("story_joint_frames");
    return "";
  }
  const int frames = std::stoi(tr.at("frames"));
  const double f = (joints[3] + frames) / 2;
  const std::string at = std::to_string(static_cast<int>(r[0] + r[2] * f / frames)) + " " +
                         std::to_string(static_cast<int>(r[1] + 20));
  return "pause\nwait 2\nx-move " + at + "\nwait 1\nx-press " + at + "\nwait 1\nx-release " + at +
         "\nwait 2\n";
}

TEST(Studio, ClickingATimelineBlockSelectsItsSegment) {
  const std::string click = click_the_walk();
  ASSERT_FALSE(click.empty());
  ASSERT_EQ(studio(kTour, "tl-click", click + "dump " + work("tc.txt") + "\nquit\n"), 0)
      << log_text();
  EXPECT_EQ(read_dump(work("tc.txt")).at("story_selected"), "3");
}

TEST(Studio, TypingAJointsStepsIsOneUndoStep) {
  // Segment 3 (the walk) is entered by grow, steps = 20: clicked on the
  // timeline, it is selected and its steps field is shown.
  const std::string select = click_the_walk();
  ASSERT_FALSE(select.empty());
  ASSERT_EQ(studio(kTour, "steps-rect", select + "dump " + work("sr.txt") + "\nquit\n"), 0)
      << log_text();
  EXPECT_EQ(read_dump(work("sr.txt")).at("story_selected"), "3");
  const auto r = numbers(read_dump(work("sr.txt")).at("joint_steps"));
  ASSERT_EQ(r.size(), 4u);
  ASSERT_GT(r[2], 0);
  const std::string field = std::to_string(static_cast<int>(r[0] + 8)) + " " +
                            std::to_string(static_cast<int>(r[1] + r[3] / 2));
  const std::string away = std::to_string(static_cast<int>(r[0])) + " 5";  // the flame pane
  const std::string saved = work("typed-story.toml");
  // Click into the field (it selects its text), type 3 then 7, click away.
  ASSERT_EQ(
      studio(kTour, "steps-type",
             select + "x-move " + field + "\nwait 1\nx-press " + field + "\nwait 1\nx-release " +
                 field + "\nwait 2\nx-key 3\nwait 2\nx-key 7\n" + "wait 2\nx-move " + away +
                 "\nwait 1\nx-press " + away + "\nwait 1\nx-release " + away + "\nwait 2\ndump " +
                 work("st1.txt") + "\nsave-story " + saved + "\nundo\ndump " + work("st2.txt") +
                 "\nsave-story " + work("typed-undone.toml") + "\nquit\n"),
      0)
      << log_text();
  EXPECT_EQ(candela::story::load_story_file(saved).segments[3].transition.steps, 37);
  EXPECT_EQ(read_dump(work("st1.txt")).at("undo_depth"), "1") << "one step for the typing";
  EXPECT_EQ(candela::story::load_story_file(work("typed-undone.toml")).segments[3].transition.steps,
            20)
      << "one undo takes all of it back";
}

TEST(Studio, AStoryEditTheReaderRefusesIsNotMadeAndSaysWhy) {
  // As in the UI (where the message shows under the timeline), the script stops naming it.
  EXPECT_EQ(studio(kTour, "refused", "pause\nstory set 1 steps 500\nquit\n"), 2) << log_text();
  EXPECT_NE(
      log_text().find("refused.script:2: story set: <studio story>: "
                      "segment[1].transition.steps: expected an integer in [0, 200], got 500"),
      std::string::npos)
      << log_text();
}

}  // namespace

namespace {

TEST(Studio, TypedTextIsUnicode) {
  // Click into "Save as scene"'s file field, select all, and type a name with
  // a Greek letter, an e acute (Latin-1) and the euro sign through real X key
  // events: the field holds them (UTF-8, the scene is saved under that name),
  // as a user who names a fire in their own language expects. (Latin-1 only,
  // before: the alpha and the euro sign were dropped.)
  ASSERT_EQ(studio(kFire, "file-rect", "pause\nwait 2\ndump " + work("fr.txt") + "\nquit\n"), 0)
      << log_text();
  const auto r = numbers(read_dump(work("fr.txt")).at("scene_file"));
  ASSERT_EQ(r.size(), 4u);
  ASSERT_GT(r[2], 0);
  const std::string at = std::to_string(static_cast<int>(r[0] + r[2] / 2)) + " " +
                         std::to_string(static_cast<int>(r[1] + r[3] / 2));
  std::string keys;
  for (const char* k : {"U03B1", "eacute", "EuroSign", "period", "t", "o", "m", "l"})
    keys += std::string("x-key ") + k + "\nwait 1\n";
  ASSERT_EQ(studio(kFire, "file-type",
                   "pause\nwait 2\nx-move " + at + "\nwait 1\nx-press " + at +
                       "\nwait 1\nx-release " + at + "\nwait 2\nx-key ctrl+a\nwait 1\n" + keys +
                       "wait 2\ndump " + work("ft.txt") + "\nquit\n"),
            0)
      << log_text();
  const std::string typed = read_dump(work("ft.txt")).at("scene_file_text");
  EXPECT_EQ(typed, "\xce\xb1\xc3\xa9\xe2\x82\xac.toml") << "alpha, e acute, euro sign in UTF-8";
}

}  // namespace
