// candela-tool render-weights MODEL --frame N | --weights w0,w1,... --out PNG
#include <CLI/CLI.hpp>
#include <cstdio>

#include "colour_flags.h"
#include "core/cli_usage.h"
#include "core/image.h"
#include "model/flame_model.h"
#include "named_model.h"
#include "render.h"
#include "subcommand.h"

namespace {

int run_render_weights(int argc, char** argv) {
  CLI::App app{
      "Render a flame from EigenFire weights (a stored frame's, or given, or edited), with "
      "synthetic HLS colour and glow",
      "candela-tool render-weights"};
  std::string path, out;
  int frame = -1;
  std::vector<float> weights;
  std::vector<std::string> sets;
  bool gray = false, zero = false;
  candela::tools::ColourFlags colour;
  app.add_option("MODEL", path, "model file, or builtin:candle / builtin:fire")->required();
  app.add_option("--out", out, "PNG to write")->required();
  auto* fr = app.add_option("--frame", frame, "start from this stored frame's weights");
  app.add_option("--weights", weights,
                 "start from these weights (comma separated, first components)")
      ->delimiter(',')
      ->excludes(fr);
  app.add_flag("--zero", zero, "start from all-zero weights (the mean image)");
  app.add_option("--set", sets, "edit one weight: K=VALUE (component K, 0-based); repeatable");
  app.add_flag("--gray", gray, "write the gray (sRGB-encoded) image instead of the coloured one");
  colour.add_to(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  namespace cm = candela::model;
  cm::FlameModel m = candela::tools::load_named_model(path);
  std::vector<float> w(m.components(), 0.0f);
  if (frame >= 0) {
    if (frame >= m.frames())
      throw std::invalid_argument("--frame: the model has " + std::to_string(m.frames()) +
                                  " frames");
    auto s = m.weights_of(frame);
    w.assign(s.begin(), s.end());
  } else if (!weights.empty()) {
    if (weights.size() > w.size())
      throw std::invalid_argument("--weights: more values than the model's " +
                                  std::to_string(w.size()) + " components");
    std::copy(weights.begin(), weights.end(), w.begin());
  } else if (!zero && sets.empty()) {
    throw std::invalid_argument("say which weights: --frame N, --weights ..., --zero or --set K=V");
  }
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--set " + s + ": expected K=VALUE");
    const int k = std::stoi(s.substr(0, eq));
    if (k < 0 || k >= m.components())
      throw std::invalid_argument("--set " + s + ": component out of range");
    w[k] = std::stof(s.substr(eq + 1));
  }
  std::vector<float> img(m.mean.pixels());
  m.reconstruct(w, img);
  if (gray) {
    candela::write_png(out, candela::tools::gray_image(img.data(), m.width(), m.height()));
  } else {
    candela::write_png(out, colour.colourise(img.data(), m.width(), m.height(), m.colour));
  }
  std::printf("%s: %dx%d\n", out.c_str(), m.width(), m.height());
  return 0;
}

}  // namespace

int candela::tool::cmd_render_weights(int argc, char** argv) {
  return run_render_weights(argc, argv);
}
