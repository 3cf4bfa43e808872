// candela-tool: the offline workshop (noise tables, simulation, models).
// Each subcommand lives in its own cmd_*.cpp and reads its own options;
// this lists them (subcommand.h) as CLI11 subcommands and hands each its
// arguments.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/cli_usage.h"
#include "subcommand.h"

namespace {

struct Subcommand {
  const char* name;
  const char* summary;
  int (*run)(int argc, char** argv);
};

namespace ct = candela::tool;
constexpr Subcommand kSubcommands[] = {
    {"build", "dataset -> flame model file (EigenFires, motion graph)", ct::cmd_build},
    {"flame-photo", "procedural flame photograph (PNG) for texturize", ct::cmd_flame_photo},
    {"ingest", "footage -> aligned gray flame dataset", ct::cmd_ingest},
    {"inspect", "print what a model file holds", ct::cmd_inspect},
    {"measure", "realism yardsticks: features, spectra, repeats, --against real", ct::cmd_measure},
    {"noise", "make or analyse 1/f^beta noise tables", ct::cmd_noise},
    {"render-weights", "render a flame from EigenFire weights", ct::cmd_render_weights},
    {"simulate", "2-D fire simulation -> flame clip (PNG + fields)", ct::cmd_simulate},
    {"story", "plan and render a story of clips and transitions", ct::cmd_story},
    {"studio", "the flame studio window: play, edit weights and colour, PCA tracks, save a scene",
     ct::cmd_studio},
    {"synth", "sample and render new flames from a model's ARP", ct::cmd_synth},
    {"texturize", "simulated clip + fire photo -> detailed fire animation", ct::cmd_texturize},
    {"transition", "find a motion transition between two frames", ct::cmd_transition},
};

}  // namespace

int main(int argc, char** argv) {
  // A writer whose reader went away (ffmpeg on a full disk, `| head`) gets
  // EPIPE and says so; the default SIGPIPE ended the tool with no message
  // (issue 34: story --out x.mp4 exited 141).
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App app{
      "The offline workshop: noise tables, simulation, flame models and stories "
      "(candela-tool SUBCOMMAND --help)",
      "candela-tool"};
  app.set_version_flag("--version", "candela-tool 0.1.0");
  app.require_subcommand(1, 1);
  for (const Subcommand& c : kSubcommands) {
    CLI::App* sub = app.add_subcommand(c.name, c.summary);
    // Everything after the name is the subcommand's own (its --help too).
    sub->set_help_flag();
    sub->prefix_command();
    sub->allow_extras();
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; no or an unknown subcommand exits 2.
    return candela::usage_exit(app, e);
  }
  for (const Subcommand& c : kSubcommands) {
    const CLI::App* sub = app.get_subcommand(c.name);
    if (!sub->parsed()) continue;
    std::string name = std::string("candela-tool ") + c.name;
    std::vector<std::string> rest = sub->remaining();
    std::vector<char*> args{name.data()};
    for (std::string& a : rest) args.push_back(a.data());
    args.push_back(nullptr);
    // One place reports what a subcommand throws ("candela-tool NAME: why",
    // status 1); subcommands catch only what they answer differently
    // (a bad value: status 2).
    try {
      return c.run(static_cast<int>(args.size()) - 1, args.data());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
      return 1;
    }
  }
  return 2;
}
