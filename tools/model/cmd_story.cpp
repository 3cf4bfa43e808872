// candela-tool story STORY --out story.mp4|story.y4m|frames/
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <optional>

#include "colour_flags.h"
#include "core/cli_usage.h"
#include "core/error.h"
#include "core/wxh.h"
#include "display/frame_writer.h"
#include "embedded_models.h"
#include "model/flame_model.h"
#include "named_model.h"
#include "render.h"
#include "story/story_plan.h"
#include "subcommand.h"

namespace {

namespace cm = candela::model;
namespace cs = candela::story;

// A model as the story names it: builtin:NAME from the models embedded in
// candela (the same bytes), else a file; errors name the story's key.
cm::FlameModel open_model(const cs::StoryDesc& story) {
  try {
    return candela::tools::load_named_model(cs::story_model_path(story));
  } catch (const std::exception& e) {
    throw candela::ConfigError(story.file, "model", e.what());
  }
}

int run_story(int argc, char** argv) {
  CLI::App app{
      "Plan and render a story file (segments of a model joined by EigenFires transitions), "
      "printing every joint's seam ratio; fails when one exceeds the bound",
      "candela-tool story"};
  std::string path, out;
  uint64_t seed = 0;
  float max_seam = 0;
  std::string size;
  bool gray = false, no_render = false;
  candela::tools::ColourFlags colour;
  app.add_option("STORY", path, "story file (TOML), or builtin:NAME (firmware/stories/NAME.toml)")
      ->required();
  app.add_option("--out", out, "story.mp4 (ffmpeg), story.y4m, or a folder of PNG frames");
  app.add_option("--seed", seed, "seed of the walks and the ARP (default: the story's, else 1)");
  app.add_option("--max-seam", max_seam,
                 "largest seam ratio allowed at a joint (step across it / the model's median step; "
                 "default: the model's 99th-percentile step, at least 2)")
      ->check(CLI::PositiveNumber);
  app.add_option("--size", size,
                 "frame size WxH (16 to 4096 a side; default: the model's own): the flame scaled "
                 "to fit, centred on black")
      ->check(candela::wxh_range({16, 16}, {4096, 4096}));
  app.add_flag("--gray", gray, "write gray frames instead of coloured ones");
  app.add_flag("--no-render", no_render, "only plan and report the joints");
  colour.add_to(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  if (out.empty() && !no_render) throw std::invalid_argument("--out: say where (or --no-render)");
  std::optional<candela::WxH> frame_size;  // checked by the option's validator
  if (!size.empty()) frame_size = candela::parse_wxh(size, {16, 16}, {4096, 4096});
  const cs::StoryDesc story = cs::open_story(path);
  const cm::FlameModel m = open_model(story);
  if (!seed) seed = story.has_seed ? story.seed : 1;
  const cs::StoryPlan plan = cs::plan_story(story, m, seed);
  if (max_seam <= 0) max_seam = plan.seam_bound();
  std::printf(
      "%s: %d frames (%.1f s at %.0f fps), seed %llu; %zu joints; distances over %d components, "
      "median step %.1f, seam bound %.2f\n",
      story.file.c_str(), plan.frames(), plan.frames() / plan.fps(), plan.fps(),
      static_cast<unsigned long long>(seed), plan.joints().size(), plan.distance_components(),
      plan.median_step(), max_seam);
  for (const auto& p : plan.pieces())
    std::printf("  %-22s frames %5d..%-5d largest step inside %.2f\n", p.key.c_str(), p.first,
                p.first + p.count - 1, p.max_step_ratio);
  int over = 0;
  for (const auto& j : plan.joints()) {
    const bool bad = j.seam_ratio > max_seam;
    over += bad;
    std::printf(
        "  joint %-36s %-7s seam ratio %.2f (a cut: %.2f), %d inserted, frames %d->%d: %s%s\n",
        j.what.c_str(), cs::method_name(j.method), j.seam_ratio, j.cut_ratio, j.inserted, j.alpha,
        j.beta, j.how.c_str(), bad ? "  <-- over the bound" : "");
  }
  if (!no_render) {
    const int mw = m.width(), mh = m.height();
    const int w = frame_size ? frame_size->width : mw, h = frame_size ? frame_size->height : mh;
    auto sink = candela::open_frame_sink(out, w, h, static_cast<int>(std::lround(plan.fps())));
    std::vector<float> img(m.mean.pixels()), fitted;
    std::vector<uint8_t> rgba(static_cast<size_t>(w) * h * 4);
    for (int i = 0; i < plan.frames(); ++i) {
      m.reconstruct({plan.weights_of(i), static_cast<size_t>(plan.components())}, img);
      if (frame_size) fitted = candela::tools::fit_gray(img.data(), mw, mh, w, h);
      const float* frame = frame_size ? fitted.data() : img.data();
      const candela::Image pic =
          gray ? candela::tools::gray_image(frame, w, h) : colour.colourise(frame, w, h, m.colour);
      // The sink takes RGBA rows bottom to top (as glReadPixels gives them).
      for (int y = 0; y < h; ++y) {
        const uint8_t* src = pic.row(y);
        uint8_t* dst = rgba.data() + static_cast<size_t>(h - 1 - y) * w * 4;
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 4; ++c)
            dst[4 * x + c] = c == 3 ? 255 : src[pic.channels == 1 ? x : 3 * x + c];
      }
      sink->write(rgba.data());
    }
    sink->close();
    std::printf("rendered %d frames into %s\n", plan.frames(), out.c_str());
  }
  if (over) {
    std::fflush(stdout);  // the report first, then why it failed
    std::fprintf(stderr,
                 "candela-tool story: %s: %d joint(s) with a seam ratio over %.2f (the step "
                 "across the joint is that many ordinary steps): choose another transition\n",
                 story.file.c_str(), over, max_seam);
    return 3;
  }
  return 0;
}

}  // namespace

int candela::tool::cmd_story(int argc, char** argv) { return run_story(argc, argv); }
