// Eigen-flames on the GPU (headless llvmpipe): reconstruction against the
// CPU reference, wind leaning the rendered flame and letting it return, and
// the fallback when a model cannot be loaded; the story driver.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "display/display.h"
#include "elements/eigenflame/eigen_renderer.h"
#include "elements/eigenflame/eigenflame.h"
#include "embedded_scenes.h"
#include "flame_drivers/graph_walker.h"
#include "gl/gles.h"
#include "gl/render_target.h"
#include "model/flame_model.h"
#include "model/model_writer.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "story/story_plan.h"
#include "story/story_player.h"
#include "support/render_harness.h"
#include "support/scene_text.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

std::string default_model_path() {
  return std::string(CANDELA_SOURCE_DIR) + "/firmware/models/default.cmodel";
}

std::unique_ptr<Display> headless(int w, int h) {
  DisplayOptions o;
  o.kind = "headless";
  o.vsync = false;
  o.width = w;
  o.height = h;
  return open_display(o);
}

// The default model with its eigen-images requantised to 16 bits.
model::FlameModel sixteen_bit_copy(const model::FlameModel& m) {
  model::ModelWriter w;
  w.set_info(m.file().info());
  for (const auto& t : m.file().tensors())
    if (t.name.rfind("eigen.", 0) != 0) w.add(t.name, t.dtype, t.shape, {t.data, t.bytes});
  std::vector<float> eig(static_cast<size_t>(m.components()) * m.eigen.pixels());
  for (int k = 0; k < m.components(); ++k)
    for (size_t p = 0; p < m.eigen.pixels(); ++p)
      eig[k * m.eigen.pixels() + p] = m.eigen.value(k, p);
  const auto q =
      model::quantise_images(eig.data(), m.components(), m.eigen.pixels(), model::DType::kU16);
  model::add_quantised(w, "eigen", q, m.components(), m.width(), m.height());
  return model::FlameModel::from(model::ModelFile::from_bytes(w.bytes(), "<16-bit copy>"));
}

struct Diff {
  double mean = 0, max = 0;
};

// GPU reconstruction of stored frames vs FlameModel::reconstruct (clamped to
// 0..255, as an 8-bit target holds it), in gray levels.
Diff compare_reconstruction(const model::FlameModel& m, StackLayout layout) {
  EigenReconstructor r(image_stack_of(m.mean), image_stack_of(m.eigen), layout, m.components());
  const size_t px = m.mean.pixels();
  std::vector<float> cpu(px);
  std::vector<uint8_t> gpu(px * 4);
  double sum = 0, worst = 0;
  size_t n = 0;
  for (int f = 0; f < m.frames(); f += 37) {
    r.reconstruct(m.weights_of(f));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, m.width(), m.height(), GL_RGBA, GL_UNSIGNED_BYTE, gpu.data());
    m.reconstruct(m.weights_of(f), cpu);
    for (size_t p = 0; p < px; ++p) {
      // Framebuffer row 0 holds the image's first (top) row, as the CPU's does.
      const double d = std::abs(gpu[p * 4] - std::clamp(cpu[p], 0.0f, 255.0f));
      sum += d;
      worst = std::max(worst, d);
      ++n;
    }
  }
  return {sum / static_cast<double>(n), worst};
}

TEST(EigenReconstruction, GpuMatchesCpuForStoredFrames) {
  auto display = headless(64, 64);
  const auto m = model::FlameModel::load(default_model_path());
  const auto m16 = sixteen_bit_copy(m);
  for (const auto* model : {&m, &m16})
    for (StackLayout layout : {StackLayout::kPacked, StackLayout::kLayered}) {
      const Diff d = compare_reconstruction(*model, layout);
      std::printf("%s, %s: mean |GPU - CPU| = %.3f, max = %.1f gray levels (of 255)\n",
                  model == &m ? "U8 model" : "U16 model",
                  layout == StackLayout::kPacked ? "packed" : "layered", d.mean, d.max);
      EXPECT_LT(d.mean, 1.0);
      EXPECT_LE(d.max, 2.0);
    }
}

// The frame cache (a walk's frames kept once drawn): a held frame read back
// from it, and a frame near a jump (its first kBlendComponents low-passed
// with its neighbours': the difference summed over the cached frame), come
// out as the full sum gives them, within a gray level.
TEST(EigenReconstruction, CachedFramesMatchTheFullSum) {
  auto display = headless(64, 64);
  // The built-in fire: 300 frames of 299 components (the candle model's 3600
  // frames would take more layers than a GPU need have; its 80-component
  // sum is cheap anyway).
  const auto m =
      model::FlameModel::load(std::string(CANDELA_SOURCE_DIR) + "/firmware/models/fire.cmodel");
  const size_t px = m.mean.pixels();
  const int w = m.width(), h = m.height(), e = m.components();
  for (StackLayout layout : {StackLayout::kPacked, StackLayout::kLayered}) {
    EigenReconstructor r(image_stack_of(m.mean), image_stack_of(m.eigen), layout, e);
    ASSERT_TRUE(r.enable_cache(m.weights, m.frames(), e));
    RenderTarget out = RenderTarget::checked(w, h, "test");
    std::vector<uint8_t> full(px * 4), cached(px * 4);
    std::vector<float> near(static_cast<size_t>(e));
    double worst_held = 0, worst_near = 0, sum_held = 0;
    size_t n = 0;
    const auto read = [&](std::vector<uint8_t>& to) {
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, to.data());
    };
    for (int f = 1; f + 1 < m.frames(); f += 53) {
      // Held: the frame's own weights.
      r.reconstruct(m.weights_of(f));
      read(full);
      r.cache_frame(f);
      out.bind();
      r.draw_near_frame_at(m.weights_of(f), f, 0, 0);
      read(cached);
      for (size_t p = 0; p < px; ++p) {
        const double d = std::abs(full[p * 4] - cached[p * 4]);
        worst_held = std::max(worst_held, d);
        sum_held += d;
        ++n;
      }
      // Near a jump: as GraphPlayer blends it.
      const auto wp = m.weights_of(f - 1), wf = m.weights_of(f), wn = m.weights_of(f + 1);
      for (int k = 0; k < e; ++k)
        near[static_cast<size_t>(k)] =
            k < GraphWalker::kBlendComponents ? (wp[k] + wf[k] + wn[k]) * (1.0f / 3.0f) : wf[k];
      r.reconstruct(near);
      read(full);
      out.bind();
      r.draw_near_frame_at(near, f, 0, 0);
      read(cached);
      for (size_t p = 0; p < px; ++p)
        worst_near = std::max(worst_near, std::abs(full[p * 4] - cached[p * 4]) + 0.0);
    }
    std::printf("%s: held frames mean |cached - full| = %.4f, max %.0f; near a jump max %.0f\n",
                layout == StackLayout::kPacked ? "packed" : "layered",
                sum_held / static_cast<double>(n), worst_held, worst_near);
    EXPECT_LE(worst_held, 1.0);
    EXPECT_LT(sum_held / static_cast<double>(n), 0.02);
    EXPECT_LE(worst_near, 1.0);
  }
}

// A fireplace plays one model in several flames: its images go to the GPU,
// and its frames into the cache, once (the built-in fire's stack is 6 MB).
TEST(EigenReconstruction, FlamesOfOneModelShareTheirReconstructor) {
  auto display = headless(64, 64);
  const auto m = model::FlameModel::load(default_model_path());
  const auto m16 = sixteen_bit_copy(m);
  EigenBatch batch;
  const std::vector<float> w(static_cast<size_t>(m.components()), 0.0f);
  const FlameLookSettings look;
  const auto flame = [&](const model::FlameModel& of, StackLayout layout) {
    return std::make_unique<EigenRenderer>(image_stack_of(of.mean), image_stack_of(of.eigen),
                                           layout, of.components(), look, w, &batch);
  };
  auto a = flame(m, StackLayout::kPacked), b = flame(m, StackLayout::kPacked);
  auto other_layout = flame(m, StackLayout::kLayered),
       other_model = flame(m16, StackLayout::kPacked);
  EXPECT_EQ(&a->reconstructor(), &b->reconstructor());
  EXPECT_NE(&a->reconstructor(), &other_layout->reconstructor());
  EXPECT_NE(&a->reconstructor(), &other_model->reconstructor());
  // The last flame of a model gone, a new one uploads its own again.
  const EigenReconstructor* first = &a->reconstructor();
  a.reset();
  EXPECT_EQ(&b->reconstructor(), first);
  b.reset();
  auto c = flame(m, StackLayout::kPacked);
  EXPECT_EQ(c->reconstructor().components(), m.components());
}

// A model of footage keeps an EigenFire per frame (a 20 s clip at 25 fps:
// 500), so that it plays back as filmed: the GPU sums every one of them,
// not only the first 256 (the cap until a model of one's own footage came
// to play back blurred). Here the picture is carried by components past 256
// alone: leaving them out would leave a flat gray.
TEST(EigenReconstruction, GpuSumsEveryComponentOfALongClipsModel) {
  auto display = headless(64, 64);
  constexpr int kW = 24, kH = 20, kCount = model::kMaxPlayedComponents - 12;
  static_assert(kCount > 256);
  constexpr size_t kPx = static_cast<size_t>(kW) * kH;
  std::vector<float> mean(kPx, 40.0f), eig(static_cast<size_t>(kCount) * kPx);
  for (int k = 0; k < kCount; ++k)  // each component a stripe pattern of its own
    for (size_t p = 0; p < kPx; ++p)
      eig[k * kPx + p] = static_cast<float>(std::sin(0.37 * (k + 1) * static_cast<double>(p % kW) +
                                                     0.11 * k * static_cast<double>(p / kW)));
  const auto qm = model::quantise_images(mean.data(), 1, kPx, model::DType::kU16);
  const auto qe = model::quantise_images(eig.data(), kCount, kPx, model::DType::kU16);
  const auto view = [&](const model::QuantisedSet& q, int count) {
    return model::QuantisedImages{q.dtype, count, kW, kH, q.bytes.data(), q.scale, q.offset};
  };
  const model::QuantisedImages mq = view(qm, 1), eq = view(qe, kCount);
  std::vector<float> w(kCount, 0.0f);
  for (int k = 300; k < kCount; k += 17) w[static_cast<size_t>(k)] = 30.0f / (1 + (k % 5));
  for (StackLayout layout : {StackLayout::kPacked, StackLayout::kLayered}) {
    EigenReconstructor r(image_stack_of(mq), image_stack_of(eq), layout, kCount);
    EXPECT_EQ(r.components(), kCount);
    r.reconstruct(w);
    std::vector<uint8_t> gpu(kPx * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kW, kH, GL_RGBA, GL_UNSIGNED_BYTE, gpu.data());
    double worst = 0, spread = 0;
    for (size_t p = 0; p < kPx; ++p) {
      double cpu = mq.value(0, p);
      for (int k = 0; k < kCount; ++k) cpu += w[static_cast<size_t>(k)] * eq.value(k, p);
      cpu = std::clamp(cpu, 0.0, 255.0);
      worst = std::max(worst, std::abs(gpu[p * 4] - cpu));
      spread = std::max(spread, std::abs(cpu - 40.0));
    }
    EXPECT_GT(spread, 20.0) << "the late components must carry a picture";
    EXPECT_LE(worst, 2.0) << (layout == StackLayout::kPacked ? "packed" : "layered");
  }
}

// Intensity-weighted centroid x of a frame read back from the GL framebuffer.
double centroid_x(const std::vector<uint8_t>& rgba, int w, int h) {
  double s0 = 0, s1 = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* p = &rgba[(static_cast<size_t>(y) * w + x) * 4];
      const double l = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
      s0 += l;
      s1 += l * x;
    }
  return s0 > 0 ? s1 / s0 : w / 2.0;
}

// Runs a scene step by step (60 steps/s), drawing and reading back every
// frame, so that the wind can change in the middle of a run.
class SteppedScene {
 public:
  SteppedScene(const std::string& toml, int w, int h)
      : desc_(load_scene_text(toml, "<test scene>")),
        display_(headless(w, h)),
        scene_(desc_),
        w_(w),
        h_(h),
        pixels_(static_cast<size_t>(w) * h * 4) {}
  // Mean lean (centroid x, pixels) over `frames` frames.
  double run(int frames) {
    double sum = 0;
    for (int i = 0; i < frames; ++i) {
      StepContext st;
      st.step = step_;
      st.dt = Fixed::from_ratio(1, 60);
      st.time = Fixed::from_ratio(static_cast<int64_t>(step_), 60);
      scene_.update(st);
      FrameContext fc;
      fc.width = w_;
      fc.height = h_;
      fc.frame = fc.step = step_++;
      display_->begin_frame();
      scene_.draw(fc);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, pixels_.data());
      sum += centroid_x(pixels_, w_, h_);
      display_->present();
    }
    return sum / frames;
  }
  Scene& scene() { return scene_; }

 private:
  SceneDesc desc_;
  std::unique_ptr<Display> display_;
  Scene scene_;
  int w_, h_;
  uint64_t step_ = 0;
  std::vector<uint8_t> pixels_;
};

const std::string kWindScene =
    "seed = 4\n" + test::black_room(0.0, 0.3, 1.2, 0.0, 0.3, 0.0, 40) + R"(
[[element]]
kind = "eigenflame"
position = [0.0, 0.0, 0.0]
height = 0.6
components = 24
glow_strength = 0
driver = "DRIVER"
)";

void check_wind_leans_and_returns(const std::string& driver) {
  std::string toml = kWindScene;
  toml.replace(toml.find("DRIVER"), 6, driver);
  SteppedScene s(toml, 320, 240);
  s.run(60);
  const double calm = s.run(480);
  // A steady wind from the left (blowing to +x).
  s.scene().wind().push({WindEvent::Type::kSteady, Fixed::from_int(3), Fixed{}});
  s.run(150);  // it travels from plane S and the flame follows
  const double windy = s.run(480);
  s.scene().wind().push({WindEvent::Type::kSteady, Fixed{}, Fixed{}});
  s.run(240);
  const double after = s.run(480);
  std::printf(
      "%s: mean lean (centroid x, px of 320): calm %.2f, wind from the left %.2f, after %.2f\n",
      driver.c_str(), calm, windy, after);
  // The default model's breeze frames lean ~0.045 image widths (~2.5 px here);
  // the arp flame bends by `bend` = 0.15 heights per m/s at its tip.
  EXPECT_GT(windy - calm, 2.0);
  EXPECT_LT(std::abs(after - calm), 0.35 * (windy - calm));
}

TEST(EigenWind, GraphWalkLeansWithTheWindAndReturns) { check_wind_leans_and_returns("graph"); }
TEST(EigenWind, ArpFlameBendsWithTheWindAndReturns) { check_wind_leans_and_returns("arp"); }

TEST(EigenFallback, CorruptModelIsReportedAndTheDefaultPlays) {
  const std::string dir = std::string(CANDELA_SOURCE_DIR) + "/tests/elements/eigenflame/data";
  const SceneDesc desc = load_scene_file(dir + "/bad-model.toml");
  ASSERT_EQ(desc.elements.size(), 1u);
  const auto* spec = dynamic_cast<const EigenFlameSpec*>(desc.elements[0].spec.get());
  ASSERT_NE(spec, nullptr);
  // The reason names the key, the file and what is wrong with it.
  EXPECT_NE(spec->model_error.find("element[0].model"), std::string::npos) << spec->model_error;
  EXPECT_NE(spec->model_error.find("corrupt.cmodel"), std::string::npos) << spec->model_error;
  EXPECT_EQ(spec->model->source, "<built-in default>");
  // And the display is not dark: the default flame burns.
  test::RenderHarness h(load_scene_file(dir + "/bad-model.toml"), 160, 120);
  h.run(30);
  const test::Frame f = h.read();
  double brightest = 0;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) brightest = std::max(brightest, f.luma(x, y));
  EXPECT_GT(brightest, 80);
}

TEST(EigenFallback, MissingModelFallsBackToo) {
  const SceneDesc desc = load_scene_text(
      "[[element]]\nkind = \"eigenflame\"\nmodel = \"/nonexistent/flame.cmodel\"\n", "<test>");
  const auto* spec = dynamic_cast<const EigenFlameSpec*>(desc.elements[0].spec.get());
  ASSERT_NE(spec, nullptr);
  EXPECT_NE(spec->model_error.find("/nonexistent/flame.cmodel"), std::string::npos);
  EXPECT_EQ(spec->model->source, "<built-in default>");
}

// "builtin:NAME" plays a model embedded in the runtime; an unknown name is
// reported (naming what is built in) and the default plays.
TEST(EigenBuiltinModels, SceneNamesTheCandleOrTheFireModel) {
  auto source_of = [](const std::string& name, std::string* error = nullptr) {
    const SceneDesc desc = load_scene_text(
        "[[element]]\nkind = \"eigenflame\"\nmodel = \"builtin:" + name + "\"\n", "<test>");
    const auto* spec = dynamic_cast<const EigenFlameSpec*>(desc.elements[0].spec.get());
    if (!spec) return std::string("(no eigenflame spec)");
    if (error) *error = spec->model_error;
    return spec->model->source;
  };
  EXPECT_EQ(source_of("fire"), "<built-in fire>");
  EXPECT_EQ(source_of("candle"), "<built-in default>");
  std::string error;
  EXPECT_EQ(source_of("nosuch", &error), "<built-in default>");
  EXPECT_NE(error.find("no such built-in model"), std::string::npos) << error;
  // Two different models, not one under two names.
  const auto fire = builtin_eigen_model("fire"), candle = builtin_eigen_model("candle");
  EXPECT_NE(fire->model.get(), candle->model.get());
  // The shipped scenes use them.
  for (const auto& [scene, want] :
       {std::pair<const char*, const char*>{"eigen-fireplace", "<built-in fire>"},
        {"eigen-candle", "<built-in default>"}}) {
    const SceneDesc d = load_builtin_scene(scene);
    int eigen = 0;
    for (const auto& e : d.elements)
      if (const auto* spec = dynamic_cast<const EigenFlameSpec*>(e.spec.get())) {
        ++eigen;
        EXPECT_EQ(spec->model->source, want) << scene;
        EXPECT_TRUE(spec->model_error.empty()) << scene << ": " << spec->model_error;
      }
    EXPECT_GE(eigen, 1) << scene;
  }
}

// foot_fade hides the foot of the model's image (the built-in fire's own bed
// and logs, where a hearth draws its own) and leaves the flame above it as it was.
TEST(EigenLook, FootFadeHidesTheImagesFootAndLeavesTheFlameAboveIt) {
  // The fire model's image, 0.1 high from y = 0, framed whole (as
  // tests/realism/scenes/eigen_fire.toml): the frame spans y -0.0082..0.1082.
  const auto scene = [](const std::string& extra) {
    return test::black_room(0.0, 0.05, 0.16, 0.0, 0.05, 0.0, 40) +
           "[[element]]\nkind = \"eigenflame\"\nmodel = \"builtin:fire\"\nposition = [0.0, 0.0, "
           "0.0]\nheight = 0.1\ncrossfade = 0.0\nglow_strength = 0.0\n" +
           extra;
  };
  constexpr int w = 96, h = 96;
  test::RenderHarness plain(scene(""), w, h, 3);
  test::RenderHarness faded(scene("foot_fade = [0.3, 0.5]\n"), w, h, 3);
  plain.run(20);
  faded.run(20);
  const test::Frame a = plain.read(), b = faded.read();
  // The screen row of a height in the image (0 its bottom, 1 its top).
  const auto row = [&](double at) { return static_cast<int>((0.1082 - 0.1 * at) / 0.1164 * h); };
  const auto mean = [&](const test::Frame& f, int y0, int y1) { return f.mean_luma(0, y0, w, y1); };
  // Below 0.3 of its height (the bed and the front log: lit, unfaded) nothing.
  const int foot0 = row(0.28), foot1 = row(0.02);
  EXPECT_GT(mean(a, foot0, foot1), 15.0);
  EXPECT_LT(mean(b, foot0, foot1), 0.5);
  // Above 0.5 the same picture (within a gray level: the billboard's sampling).
  double worst = 0;
  for (int y = row(0.95); y < row(0.52); ++y)
    for (int x = 0; x < w; ++x) worst = std::max(worst, std::abs(a.luma(x, y) - b.luma(x, y)));
  EXPECT_GT(mean(a, row(0.95), row(0.52)), 15.0);
  EXPECT_LE(worst, 1.0);
  // Heights out of order or not two are an error naming the key.
  for (const char* bad :
       {"foot_fade = [0.5, 0.3]", "foot_fade = [0.4]", "foot_fade = [0.2, 1.5]"}) {
    try {
      load_scene_text(scene(std::string(bad) + "\n"), "<test>");
      ADD_FAILURE() << bad << ": no error";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("foot_fade"), std::string::npos) << e.what();
    }
  }
}

TEST(EigenLook, InFrontDrawsTheFlameOverAHearthsFrontLog) {
  // A hearth's front log (drawn after the flames) across the foot of a fire
  // model's flame: behind it, the flame's foot is hidden; in_front = true
  // draws the flame after the log, licking up over it, as in footage.
  const auto scene = [](const std::string& extra) {
    return test::black_room(0.0, 0.05, 0.3, 0.0, 0.05, 0.0, 40) +
           "[[element]]\nkind = \"hearth\"\nwidth = 0.3\ndepth = 0.2\nembers = 0\n"
           "light_strength = 0.3\n[[element.log]]\nfrom = [-0.15, 0.03, 0.08]\n"
           "to = [0.15, 0.03, 0.08]\nradius = 0.03\n\n" +
           extra;
  };
  const std::string flame =
      "[[element]]\nkind = \"eigenflame\"\nmodel = \"builtin:fire\"\nposition = [0.0, 0.0, "
      "0.0]\nheight = 0.1\ncrossfade = 0.0\nglow_strength = 0.0\n";
  constexpr int w = 96, h = 96;
  test::RenderHarness logs(scene(""), w, h, 3);
  test::RenderHarness behind(scene(flame), w, h, 3);
  test::RenderHarness in_front(scene(flame + "in_front = true\n"), w, h, 3);
  logs.run(20);
  behind.run(20);
  in_front.run(20);
  // The log's middle band (y 0.015..0.045 seen from 0.22 m), the middle columns.
  const auto mean = [&](const test::Frame& f) {
    return f.mean_luma(w * 3 / 10, h * 56 / 100, w * 7 / 10, h * 68 / 100);
  };
  const double log = mean(logs.read()), hidden = mean(behind.read()), over = mean(in_front.read());
  EXPECT_LT(std::abs(hidden - log), 1.0) << "behind the log: the log alone shows";
  EXPECT_GT(over, log + 20.0) << "in front: the flame's foot over the log";
  try {
    load_scene_text(scene(flame + "in_front = \"yes\"\n"), "<test>");
    ADD_FAILURE() << "in_front = \"yes\": no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("in_front"), std::string::npos) << e.what();
  }
}

// The eigen fireplace is a fire that fills the picture (issue 35: at least 12%
// of the pixels above 0.25 gray and 45% of the frame's height, at 1280x720 and
// 1920x1080), its flames' feet faded where the hearth's logs are: without its
// firebox (the lit bricks are not fire), over four frames a third of a second apart.
class EigenFireplaceFill : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(EigenFireplaceFill, FillsThePicture) {
  const auto [w, h] = GetParam();
  const std::string toml =
      test::without_table(std::string(scenes::find("eigen-fireplace.toml")), "[element.firebox]");
  ASSERT_FALSE(toml.empty());
  test::RenderHarness r(load_scene_text(toml, "eigen-fireplace.toml (no firebox)"), w, h);
  double lit_share = 0;
  constexpr int kFrames = 4;
  for (int k = 0; k < kFrames; ++k) {
    r.run(20);
    const test::Frame::Lit lit = r.read().lit_above(0.25 * 255);
    lit_share += static_cast<double>(lit.count) / (w * h);
    EXPECT_GE(lit.bottom - lit.top + 1, 0.45 * h) << "frame " << k;
  }
  EXPECT_GE(lit_share / kFrames, 0.12);
}

INSTANTIATE_TEST_SUITE_P(EigenFire, EigenFireplaceFill,
                         ::testing::Values(std::make_pair(1280, 720), std::make_pair(1920, 1080)),
                         [](const auto& info) {
                           return std::to_string(info.param.first) + "x" +
                                  std::to_string(info.param.second);
                         });

TEST(EigenScenes, ShippedScenesLoad) {
  for (const char* name : {"eigen-fireplace", "eigen-candle", "eigen-bench-f1-e8",
                           "eigen-bench-f4-e32", "eigen-bench-f8-e64"}) {
    SCOPED_TRACE(name);
    const SceneDesc d = load_builtin_scene(name);
    EXPECT_GE(d.elements.size(), 1u);
  }
}

// The story driver's frames on the GPU are the frames `candela-tool story`
// writes: the built-in tour planned, played by the driver's StoryPlayer
// (held frames), reconstructed by the renderer's EigenReconstructor and
// compared with the tool's CPU reconstruction of the plan, every 50th frame
// (clip frames, a grown path, the low-passed joint's blends, the walk, the
// ARP, and across the loop).
TEST(EigenStory, GpuFramesMatchTheToolsReconstruction) {
  auto display = headless(64, 64);
  const auto fire = builtin_eigen_model("fire");
  const model::FlameModel& m = *fire->model;
  const story::StoryDesc desc = story::open_story("builtin:fire-tour");
  const story::StoryPlan plan = story::plan_story(desc, m, desc.seed, true);
  story::StoryPlayer player(plan, m.components(), Fixed::from_int(1));
  player.set_crossfade(Fixed{});
  EigenReconstructor r(image_stack_of(m.mean), image_stack_of(m.eigen), StackLayout::kPacked,
                       m.components());
  const size_t px = m.mean.pixels();
  std::vector<float> cpu(px);
  std::vector<uint8_t> gpu(px * 4);
  double sum = 0, worst = 0;
  size_t n = 0;
  int blended = 0, first_blend = -1;
  for (int k = 0; k < plan.frames() && first_blend < 0; ++k)
    if (plan.model_frame(k) < 0) first_blend = k;  // a low-passed frame
  for (int step = 1; step <= plan.frames() + 60; ++step) {
    player.step();
    if (step % 50 != 0 && player.frame() != first_blend) continue;
    const int k = player.frame();
    ASSERT_EQ(k, step % plan.frames());
    blended += plan.model_frame(k) < 0;
    r.reconstruct(player.weights());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, m.width(), m.height(), GL_RGBA, GL_UNSIGNED_BYTE, gpu.data());
    m.reconstruct({plan.weights_of(k), static_cast<size_t>(plan.components())}, cpu);
    for (size_t p = 0; p < px; ++p) {
      const double d = std::abs(gpu[p * 4] - std::clamp(cpu[p], 0.0f, 255.0f));
      sum += d;
      worst = std::max(worst, d);
      ++n;
    }
  }
  std::printf("story frames: mean |GPU - tool| = %.3f, max = %.1f gray levels\n",
              sum / static_cast<double>(n), worst);
  EXPECT_GE(blended, 1) << "a low-passed frame was compared";
  EXPECT_LT(sum / static_cast<double>(n), 1.0);
  EXPECT_LE(worst, 2.0);
}

// The story scene renders a burning flame, the same pixels for the same seed.
TEST(EigenStory, SceneRendersTheSameFramesForTheSameSeed) {
  const SceneDesc d = load_builtin_scene("eigen-story");
  const EigenFlameSpec* spec = nullptr;
  for (const auto& e : d.elements)
    if (const auto* s = dynamic_cast<const EigenFlameSpec*>(e.spec.get())) spec = s;
  ASSERT_NE(spec, nullptr);
  EXPECT_TRUE(spec->story_error.empty()) << spec->story_error;
  ASSERT_NE(spec->story, nullptr);
  EXPECT_EQ(spec->settings.driver, EigenDriver::kStory);
  EXPECT_EQ(spec->model->source, "<built-in fire>");
  std::vector<test::Frame> runs;
  for (int i = 0; i < 2; ++i) {
    test::RenderHarness h(load_builtin_scene("eigen-story"), 96, 72);
    h.run(40);
    runs.push_back(h.read());
  }
  EXPECT_EQ(runs[0].rgba, runs[1].rgba);
  double brightest = 0;
  for (int y = 0; y < runs[0].height; ++y)
    for (int x = 0; x < runs[0].width; ++x) brightest = std::max(brightest, runs[0].luma(x, y));
  EXPECT_GT(brightest, 80);
}

// A story that cannot be planned is reported (scene key, story file, story
// key) and the element walks the story model's graph instead: still burning.
TEST(EigenStory, BrokenStoryIsReportedAndTheGraphWalkPlays) {
  const std::string dir = std::string(CANDELA_SOURCE_DIR) + "/tests/elements/eigenflame/data";
  const SceneDesc desc = load_scene_file(dir + "/bad-story.toml");
  const auto* spec = dynamic_cast<const EigenFlameSpec*>(desc.elements[0].spec.get());
  ASSERT_NE(spec, nullptr);
  EXPECT_NE(spec->story_error.find("element[0].story"), std::string::npos) << spec->story_error;
  EXPECT_NE(spec->story_error.find("bad-clip.story.toml: segment[1].clip"), std::string::npos)
      << spec->story_error;
  EXPECT_EQ(spec->settings.driver, EigenDriver::kGraph);
  EXPECT_EQ(spec->model->source, "<built-in fire>");
  EXPECT_FALSE(scene_problems(desc).empty());  // --check fails on it
  test::RenderHarness h(load_scene_file(dir + "/bad-story.toml"), 160, 120);
  h.run(30);
  const test::Frame f = h.read();
  double brightest = 0;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) brightest = std::max(brightest, f.luma(x, y));
  EXPECT_GT(brightest, 60);
  // Keys that contradict a story are refused outright.
  for (const auto& [text, key] :
       {std::pair<const char*, const char*>{"story = \"builtin:fire-tour\"\ndriver = \"arp\"\n",
                                            "element[0].driver"},
        {"story = \"builtin:fire-tour\"\nmodel = \"builtin:fire\"\n", "element[0].model"},
        {"driver = \"story\"\n", "element[0].story"}}) {
    try {
      load_scene_text(std::string("[[element]]\nkind = \"eigenflame\"\n") + text, "<s>");
      ADD_FAILURE() << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("<s>: ") + key), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace candela
