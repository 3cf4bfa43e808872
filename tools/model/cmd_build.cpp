// candela-tool build DATASET --out MODEL
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "core/cli_usage.h"
#include "model/flame_model.h"
#include "model_build.h"
#include "subcommand.h"

namespace {

int run_build(int argc, char** argv) {
  CLI::App app{"Build a flame model (EigenFires PCA, motion graph) from a dataset made by ingest",
               "candela-tool build"};
  std::string dataset, out, report;
  candela::tools::BuildOptions opt;
  int bits = 16;
  app.add_option("DATASET", dataset, "dataset folder")->required();
  app.add_option("--out", out, "model file to write")->required();
  auto* comp = app.add_option("--components", opt.pca.components, "number of EigenFires E")
                   ->check(CLI::Range(1, candela::model::kMaxPlayedComponents));
  app.add_option("--variance", opt.pca.variance,
                 "else: fewest EigenFires explaining this share of the variance")
      ->check(CLI::Range(0.5, 1.0))
      ->capture_default_str()
      ->excludes(comp);
  app.add_option("--max-components", opt.pca.max_components, "cap for --variance")
      ->check(CLI::Range(1, candela::model::kMaxPlayedComponents))
      ->capture_default_str();
  app.add_option("--holdout", opt.holdout_every,
                 "leave every n-th frame out of the fit to measure PSNR (0: none)")
      ->check(CLI::IsMember({0}) | CLI::Range(2, 1 << 24))
      ->capture_default_str();
  app.add_option("--bits", bits, "eigen-image quantisation: 8 or 16")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  app.add_option("--theta-min", opt.graph.theta_min,
                 "smallest step of the motion graph (default, 0: half the median step)")
      ->check(candela::finite_range(0.0, 1e30));
  app.add_option("--successors", opt.graph.max_successors, "jumps per frame in the motion graph")
      ->check(CLI::Range(1, candela::model::kMaxSuccessors - 1))
      ->capture_default_str();
  app.add_option("--min-jump", opt.graph.min_jump, "a jump lands at least this many frames away")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  app.add_option("--hue", opt.colour.hue, "default colour: hue (degrees)")
      ->check(candela::finite_range(0.0, 360.0))
      ->capture_default_str();
  app.add_option("--saturation", opt.colour.saturation, "default colour: saturation")
      ->check(candela::finite_range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--glow-strength", opt.colour.glow_strength,
                 "default glow: strength (an additive blurred copy; real fire footage has "
                 "little, and any glow fills the dark gaps between tongues)")
      ->check(candela::finite_range(0.0, 4.0))
      ->capture_default_str();
  app.add_option("--glow-radius", opt.colour.glow_radius,
                 "default glow: radius, fraction of the image height")
      ->check(candela::finite_range(0.0, 1.0))
      ->capture_default_str();
  bool no_flames = false;
  app.add_flag("--no-learning-flames", no_flames,
               "EigenFires and motion graph only (no shape model, no ARP)");
  app.add_option("--np", opt.flames.shape.np, "Learning Flames: path samples")
      ->capture_default_str();
  app.add_option("--nw", opt.flames.shape.nw, "Learning Flames: width samples")
      ->capture_default_str();
  app.add_option("--ne", opt.flames.ne, "Learning Flames: eigenflames")->capture_default_str();
  app.add_option("--particles", opt.flames.arp.particles, "ARP learning: condensation particles Nc")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--order", opt.flames.arp.order, "ARP order K")
      ->check(CLI::Range(1, candela::model::kMaxArpOrder))
      ->capture_default_str();
  app.add_option("--report", report, "folder for the reports (default: MODEL.report)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  opt.learning_flames = !no_flames;
  // Before the dataset is read: options whose model the runtime would refuse.
  try {
    candela::tools::check_build_options(opt);
  } catch (const candela::tools::BuildOptionError& e) {
    std::fprintf(stderr, "candela-tool build: %s\n", e.what());
    return 2;
  }
  auto d = candela::tools::load_dataset(dataset);
  opt.eigen_dtype = bits == 8 ? candela::model::DType::kU8 : candela::model::DType::kU16;
  opt.progress = [](const std::string& s) { std::fprintf(stderr, "build: %s\n", s.c_str()); };
  opt.provenance_options = {{"dataset", dataset},
                            {"components", opt.pca.components},
                            {"variance", opt.pca.variance},
                            {"max_components", opt.pca.max_components},
                            {"holdout", opt.holdout_every},
                            {"bits", bits},
                            {"theta_min", opt.graph.theta_min},
                            {"successors", opt.graph.max_successors},
                            {"min_jump", opt.graph.min_jump},
                            {"learning_flames", !no_flames},
                            {"np", opt.flames.shape.np},
                            {"nw", opt.flames.shape.nw},
                            {"ne", opt.flames.ne},
                            {"particles", opt.flames.arp.particles},
                            {"order", opt.flames.arp.order}};
  auto m = candela::tools::build_model(d, opt);
  m.writer.write(out);
  if (report.empty()) report = out + ".report";
  candela::tools::write_reports(d, m, report);
  std::printf("%s: %d EigenFires of %dx%d over %d frames (%.2f%% of the variance)\n", out.c_str(),
              m.pca.components(), d.width, d.height, d.frames(),
              100.0 * m.pca.variance.head(m.pca.components()).sum() / m.pca.total_variance);
  std::printf("black level %.1f (the reconstruction's haze over the background)\n", m.black_level);
  std::printf("   E   train dB  held-out dB\n");
  for (const auto& r : m.psnr)
    std::printf("%4d   %7.2f   %7.2f\n", r.components, r.train_db, r.holdout_db);
  if (m.has_flames)
    std::printf(
        "Learning Flames: %zu single-plume frames, ARP after %d EM iterations; held-out PSNR at "
        "%d "
        "parameters/frame: EigenFires %.2f dB, Learning Flames %.2f dB\n",
        m.flames.frames.size(), m.flames.dynamics.iterations, m.equal_params, m.plain_equal_db,
        m.flames_equal_db);
  std::printf("motion graph: %zu edges, theta_min %.1f; reports in %s\n", m.graph.successors.size(),
              m.graph.theta_min, report.c_str());
  return 0;
}

}  // namespace

int candela::tool::cmd_build(int argc, char** argv) { return run_build(argc, argv); }
