// candela-tool inspect MODEL
#include <CLI/CLI.hpp>
#include <cstdio>

#include "core/cli_usage.h"
#include "core/error.h"
#include "model/flame_model.h"
#include "named_model.h"
#include "subcommand.h"

namespace {

int run_inspect(int argc, char** argv) {
  CLI::App app{"Print what a model file holds and how big it is; exits 1 if it does not load",
               "candela-tool inspect"};
  std::string path;
  bool json = false;
  app.add_option("MODEL", path, "model file, or builtin:candle / builtin:fire")->required();
  app.add_flag("--json", json, "print the whole metadata as JSON");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return candela::usage_exit(app, e);
  }
  namespace cm = candela::model;
  try {
    cm::FlameModel m = candela::tools::load_named_model(path);
    const cm::ModelFile& f = m.file();
    std::printf("%s: candela-model version %d, %zu bytes (header %zu), crc32 %08x\n", path.c_str(),
                f.version(), f.file_size(), f.header_bytes(), f.checksum());
    std::printf("EigenFires: %d components of %dx%d, %d frames, eigen-images %s\n", m.components(),
                m.width(), m.height(), m.frames(), cm::dtype_name(m.eigen.dtype));
    double explained = 0;
    for (float v : m.variance) explained += v;
    std::printf("explained variance: %.2f%% (first: %.2f%%)\n",
                100.0 * explained / m.total_variance, 100.0 * m.variance[0] / m.total_variance);
    std::printf("motion graph: %zu edges (%.2f per frame), theta_min %.2f\n",
                m.graph.successors.size(),
                static_cast<double>(m.graph.successors.size()) / m.frames(), m.graph.theta_min);
    std::printf("colour: hue %.0f, saturation %.2f, glow radius %.3f strength %.2f\n", m.colour.hue,
                m.colour.saturation, m.colour.glow_radius, m.colour.glow_strength);
    for (const auto& c : m.clips) {
      std::printf("clip %s: frames %d..%d at %.2f fps from %s\n", c.name.c_str(), c.first,
                  c.first + c.count - 1, c.fps, c.source.c_str());
      for (const auto& l : c.labels)
        std::printf("  label %s: frames %d..%d\n", l.label.c_str(), l.from, l.to - 1);
    }
    if (m.has_learning_flames)
      std::printf(
          "Learning Flames: np %d nw %d ne %d (%d parameters), normalised %dx%d, ARP order %d, %d "
          "training frames\n",
          m.flames.np, m.flames.nw, m.flames.ne, m.flames.dim, m.flames.width, m.flames.height,
          m.flames.order, m.flames.frames);
    else
      std::printf("Learning Flames: not in this model\n");
    if (f.info().contains("provenance"))
      std::printf("provenance: %s\n", f.info()["provenance"].dump().c_str());
    std::printf("tensors:\n");
    for (const auto& t : f.tensors()) {
      std::string shape;
      for (auto s : t.shape) shape += (shape.empty() ? "" : "x") + std::to_string(s);
      std::printf("  %-18s %-4s %-16s %10zu bytes\n", t.name.c_str(), cm::dtype_name(t.dtype),
                  shape.c_str(), t.bytes);
    }
    if (json) std::printf("%s\n", f.info().dump(2).c_str());
    return 0;
  } catch (const cm::ModelError& e) {
    std::fprintf(stderr, "candela-tool inspect: %s [%s]\n", e.what(), cm::to_string(e.kind()));
    return 1;
  } catch (const candela::ConfigError& e) {  // builtin:NAME that is none
    std::fprintf(stderr, "candela-tool inspect: %s\n", e.what());
    return 1;
  }
}

}  // namespace

int candela::tool::cmd_inspect(int argc, char** argv) { return run_inspect(argc, argv); }
