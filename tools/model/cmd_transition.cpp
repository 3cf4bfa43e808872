// candela-tool transition MODEL --from A --to B
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "core/cli_usage.h"
#include "core/image.h"
#include "model_views.h"
#include "render.h"
#include "subcommand.h"

namespace {

int run_transition(int argc, char** argv) {
  CLI::App app{
      "Find a transition between two frames of a model (End Growing Connection, Direct "
      "Bridging or low-pass blending), print it, optionally render it",
      "candela-tool transition"};
  std::string path, method = "grow", kernel = "third", render_dir;
  int alpha = -1, beta = -1, components = 0;
  candela::tools::TransitionOptions opt;
  opt.theta_min = -1;
  app.add_option("MODEL", path, "model file")->required();
  app.add_option("--from", alpha, "alpha: the last frame of T1")->required();
  app.add_option("--to", beta, "beta: the first frame of T2")->required();
  app.add_option("--method", method,
                 "grow (End Growing Connection), bridge (Direct Bridging), lowpass")
      ->check(CLI::IsMember({"grow", "bridge", "lowpass"}))
      ->capture_default_str();
  app.add_option("--steps", opt.steps, "N: inserted frames (bridge) or the most steps (grow)")
      ->capture_default_str();
  app.add_option("--theta-min", opt.theta_min,
                 "smallest step (default: the model's motion-graph theta_min)");
  app.add_option("--reject-tail", opt.reject_tail, "frames before alpha / after beta never used")
      ->capture_default_str();
  app.add_option("--components", components, "EigenFires used for distances (default: all)");
  app.add_option("--kernel", kernel, "lowpass kernel: third [1/3,1/3,1/3] or fifth [1/5,1/5,3/5]")
      ->check(CLI::IsMember({"third", "fifth"}))
      ->capture_default_str();
  app.add_option("--render", render_dir,
                 "write the frames of the transition as PNGs into this folder");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  namespace cm = candela::model;
  namespace ct = candela::tools;
  cm::FlameModel m = cm::FlameModel::load(path);
  if (alpha < 0 || beta < 0 || alpha >= m.frames() || beta >= m.frames())
    throw std::invalid_argument("--from/--to must be frames 0.." + std::to_string(m.frames() - 1));
  if (opt.theta_min < 0) opt.theta_min = m.graph.theta_min;
  std::vector<std::vector<float>> frames;  // weights of each frame to render
  if (method == "lowpass") {
    const std::vector<float> k = kernel == "third" ? std::vector<float>{1 / 3.f, 1 / 3.f, 1 / 3.f}
                                                   : std::vector<float>{0.2f, 0.2f, 0.6f};
    const int c = m.clips[m.clip_of(alpha)].first, c2 = m.clips[m.clip_of(beta)].first;
    std::vector<int> t1, t2;
    for (int f = std::max(c, alpha - 2); f <= alpha; ++f) t1.push_back(f);
    for (int f = beta; f < std::min(beta + 3, c2 + m.clips[m.clip_of(beta)].count); ++f)
      t2.push_back(f);
    Eigen::MatrixXf w =
        ct::lowpass_transition(ct::model_weights(m), t1, t2, k, components > 0 ? components : 50);
    std::printf("low-pass: replaces frames %d %d | %d %d with blended weights\n", t1[t1.size() - 2],
                t1.back(), t2[0], t2[1]);
    for (int r = 0; r < 4; ++r) frames.emplace_back(w.row(r).data(), w.row(r).data() + w.cols());
  } else {
    ct::WeightSpace s = ct::model_space(m, components);
    ct::Transition t = method == "grow" ? ct::end_growing(s, alpha, beta, opt)
                                        : ct::direct_bridging(s, alpha, beta, opt);
    std::printf("%s %s: %s, theta_min %.2f, distance alpha-beta %.2f\npath:", method.c_str(),
                t.found ? "found" : "failed", t.how.c_str(), opt.theta_min,
                s.distance(alpha, beta));
    for (int f : t.path) std::printf(" %d", f);
    std::printf("\nsteps:");
    for (size_t i = 0; i + 1 < t.path.size(); ++i)
      std::printf(" %.1f", s.distance(t.path[i], t.path[i + 1]));
    std::printf("\n");
    for (int f : t.path) {
      auto w = m.weights_of(f);
      frames.emplace_back(w.begin(), w.end());
    }
    if (!t.found && render_dir.empty()) return 3;
  }
  if (!render_dir.empty()) {
    std::filesystem::create_directories(render_dir);
    std::vector<float> gray(m.mean.pixels());
    for (size_t i = 0; i < frames.size(); ++i) {
      m.reconstruct(frames[i], gray);
      char name[32];
      std::snprintf(name, sizeof name, "/%04zu.png", i);
      candela::write_png(
          render_dir + name,
          ct::colourise(gray.data(), m.width(), m.height(), m.colour.hue, m.colour.saturation,
                        m.colour.glow_radius, m.colour.glow_strength, m.colour.black_level));
    }
    std::printf("rendered %zu frames into %s\n", frames.size(), render_dir.c_str());
  }
  return 0;
}

}  // namespace

int candela::tool::cmd_transition(int argc, char** argv) { return run_transition(argc, argv); }
