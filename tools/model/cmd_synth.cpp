// candela-tool synth MODEL --frames N --out DIR
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/cli_usage.h"
#include "core/image.h"
#include "learning_flames.h"
#include "model/flame_model.h"
#include "render.h"
#include "subcommand.h"

namespace {

int run_synth(int argc, char** argv) {
  CLI::App app{
      "Sample new flame parameter sequences from a model's learned ARP (Learning Flames) and "
      "render them",
      "candela-tool synth"};
  std::string path, out;
  int frames = 120, start = -1;
  uint64_t seed = 1;
  bool gray = false;
  double lean = 0;
  app.add_option("MODEL", path, "model file with a Learning Flames part")->required();
  app.add_option("--out", out, "folder for params.csv and the PNG frames")->required();
  app.add_option("--frames", frames, "frames to synthesise")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  app.add_option("--seed", seed, "noise seed")->capture_default_str();
  app.add_option("--start", start,
                 "training frame whose history starts the process (default: the first possible)")
      ->capture_default_str();
  app.add_option("--lean", lean,
                 "offset added to the path, growing to the tip (pixels): a bent flame, as wind");
  app.add_flag("--gray", gray, "write gray frames instead of coloured ones");
  bool no_png = false;
  app.add_flag("--no-png", no_png, "write only params.csv");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  namespace ct = candela::tools;
  candela::model::FlameModel fm = candela::model::FlameModel::load(path);
  ct::LearningFlamesModel lf = ct::flames_from_model(fm);
  const int K = lf.dynamics.arp.order;
  if (start < 0) start = K - 1;
  if (start < K - 1 || start >= lf.params.rows())
    throw std::invalid_argument("--start must be a training frame >= order-1");
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd x =
      ct::sample_arp(lf.dynamics.arp, lf.params.middleRows(start - K + 1, K), frames, rng);
  std::filesystem::create_directories(out);
  std::ofstream csv(out + "/params.csv");
  for (int i = 0; i < lf.dim(); ++i) {
    const char* kind = i < lf.shape.np                  ? "path"
                       : i < lf.shape.np + lf.shape.nw  ? "width"
                       : i == lf.shape.np + lf.shape.nw ? "height"
                                                        : "appearance";
    csv << (i ? "," : "") << kind << i;
  }
  csv << "\n";
  std::vector<float> img(static_cast<size_t>(fm.width()) * fm.height());
  for (int t = 0; t < frames; ++t) {
    Eigen::VectorXd v = x.row(t).transpose();
    for (int i = 0; i < lf.shape.np; ++i) v[i] += lean * ct::sample_height(i, lf.shape.np);
    for (int i = 0; i < v.size(); ++i) csv << (i ? "," : "") << v[i];
    csv << "\n";
    if (no_png) continue;
    lf.render(v, fm.width(), fm.height(), img.data());
    char name[32];
    std::snprintf(name, sizeof name, "/%05d.png", t);
    candela::write_png(out + name,
                       gray ? ct::gray_image(img.data(), fm.width(), fm.height())
                            : ct::colourise(img.data(), fm.width(), fm.height(), fm.colour.hue,
                                            fm.colour.saturation, fm.colour.glow_radius,
                                            fm.colour.glow_strength, fm.colour.black_level));
    if ((t + 1) % 100 == 0) std::fprintf(stderr, "synth: %d/%d frames\n", t + 1, frames);
  }
  std::printf("%s: %d frames synthesised (seed %llu)\n", out.c_str(), frames,
              static_cast<unsigned long long>(seed));
  return 0;
}

}  // namespace

int candela::tool::cmd_synth(int argc, char** argv) { return run_synth(argc, argv); }
