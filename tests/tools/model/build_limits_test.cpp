// Issue 15: `candela-tool build` never hands back a model the runtime
// refuses. Options past the players' limits stop before any work, naming the
// option; whatever else would fail the runtime's validation (the same
// FlameModel::from) stops the build instead of being written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "model/colour_ramp.h"
#include "model/flame_model.h"
#include "model_build.h"
#include "render.h"

namespace ct = candela::tools;
namespace cm = candela::model;

namespace {

// A dot drifting round a 12x12 frame, one clip at `fps`.
ct::Dataset drifting_dot(int frames, double fps) {
  ct::Dataset d;
  d.width = 12;
  d.height = 12;
  d.pixels.resize(d.frame_pixels() * frames);
  d.multi_plume.assign(frames, 0);
  for (int f = 0; f < frames; ++f) {
    const double cx = 6 + 3 * std::cos(0.3 * f), cy = 6 + 3 * std::sin(0.3 * f);
    for (int y = 0; y < d.height; ++y)
      for (int x = 0; x < d.width; ++x) {
        const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
        d.pixels[d.frame_pixels() * f + y * d.width + x] =
            static_cast<uint8_t>(std::lround(250 * std::exp(-r2 / 4)));
      }
  }
  d.clips.push_back({"dot", "synthetic", 0, frames, fps, {}});
  return d;
}

// The message build_model stops with (empty if it builds).
std::string build_error(const ct::Dataset& d, const ct::BuildOptions& o) {
  try {
    ct::build_model(d, o);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

ct::BuildOptions small_options() {
  ct::BuildOptions o;
  o.pca.components = 4;
  o.learning_flames = false;
  return o;
}

}  // namespace

TEST(BuildLimits, OptionsPastThePlayersLimitsStopNamingTheOption) {
  const ct::Dataset d = drifting_dot(40, 30);
  ct::BuildOptions o = small_options();
  o.learning_flames = true;
  o.flames.shape.np = 40;
  o.flames.shape.nw = 40;
  // 40 + 40 + 1 + 5 = 86 parameters: the ARP player holds 64.
  EXPECT_EQ(build_error(d, o),
            "Learning Flames --np 40, --nw 40, --ne 5: np + nw + 1 + ne = 86; the ARP player "
            "takes a state of at most 64 (lower --np, --nw or --ne, or build with "
            "--no-learning-flames)");
  EXPECT_THROW(ct::check_build_options(o), ct::BuildOptionError);
  // What the runtime's reader says about the same sizes, word for word.
  const auto runtime = cm::learning_flames_size_problem(40, 40, 5, 2);
  ASSERT_TRUE(runtime);
  EXPECT_NE(build_error(d, o).find(runtime->problem), std::string::npos);
  o.flames.shape.np = o.flames.shape.nw = 10;
  o.flames.arp.order = 5;
  EXPECT_EQ(build_error(d, o),
            "Learning Flames --order: expected an integer in [1, 4] (change --order, or build "
            "with --no-learning-flames)");
  // Without Learning Flames its sizes do not matter.
  o.learning_flames = false;
  EXPECT_EQ(build_error(d, o), "");
  o.graph.max_successors = cm::kMaxSuccessors;  // + the next frame: one too many
  EXPECT_EQ(build_error(d, o),
            "--successors 1024: the graph player takes at most 1024 successors of a frame, the "
            "next frame and 1023 jumps");
  o.graph.max_successors = cm::kMaxSuccessors - 1;
  EXPECT_NO_THROW(ct::check_build_options(o));
}

TEST(BuildLimits, AModelTheRuntimeWouldRefuseIsNotHandedBack) {
  // A clip at 5000 fps overflows the runtime's Q16.16 frame rate (issue 15,
  // finding 5): build used to write it, and the element dropped the model.
  EXPECT_NE(
      build_error(drifting_dot(40, 5000), small_options())
          .find(
              "the model built: model.clips[0].fps: expected a number in [0.100000, 1000.000000]"),
      std::string::npos)
      << build_error(drifting_dot(40, 5000), small_options());
  // Within the limits the model built is one the runtime loads.
  const ct::BuiltModel m = ct::build_model(drifting_dot(40, 30), small_options());
  const cm::FlameModel loaded =
      cm::FlameModel::from(cm::ModelFile::from_bytes(m.writer.bytes(), "m"));
  EXPECT_EQ(loaded.frames(), 40);
  EXPECT_EQ(loaded.components(), 4);
  EXPECT_DOUBLE_EQ(loaded.clips[0].fps, 30);
}

// The tools colour a frame as the kiosk does (story --out, render-weights):
// every gray through the runtime's own HLS ramp, with hue_top when asked.
TEST(ToolColour, TheToolsColourEveryGrayAsTheRuntimesRamp) {
  std::vector<float> gray(256);
  for (int i = 0; i < 256; ++i) gray[static_cast<size_t>(i)] = static_cast<float>(i);
  for (const float hue_top : {std::numeric_limits<float>::quiet_NaN(), 56.0f}) {
    const candela::Image img =
        candela::tools::colourise(gray.data(), 256, 1, 16.0f, 0.95f, 0.0f, 0.0f, 12.0f, hue_top);
    const auto ramp = candela::hls_ramp(16.0f, 0.95f, 12.0f, hue_top);
    for (size_t i = 0; i < 256; ++i)
      for (size_t c = 0; c < 3; ++c)
        ASSERT_EQ(img.pixels[3 * i + c], ramp[4 * i + c]) << "gray " << i << " channel " << c;
  }
  // hue_top turns the bright body yellow (blue falls away from green; one hue
  // goes pinkish white there) and keeps the dim edge's deep orange.
  const candela::Image one =
      candela::tools::colourise(gray.data(), 256, 1, 16.0f, 0.95f, 0.0f, 0.0f, 0.0f);
  const candela::Image two =
      candela::tools::colourise(gray.data(), 256, 1, 16.0f, 0.95f, 0.0f, 0.0f, 0.0f, 56.0f);
  const auto green_over_blue = [](const candela::Image& im, size_t i) {
    return im.pixels[3 * i + 1] - im.pixels[3 * i + 2];
  };
  for (size_t i : {200u, 230u}) EXPECT_GT(green_over_blue(two, i), green_over_blue(one, i) + 30);
  for (size_t c = 0; c < 3; ++c) EXPECT_EQ(two.pixels[3 * 40 + c], one.pixels[3 * 40 + c]);
}
