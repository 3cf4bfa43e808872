// candela-tool: the offline workshop (noise tables, simulation, models).
// Each subcommand lives in its own cmd_*.cpp and registers itself.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "subcommand.h"

namespace candela::tool {
namespace {
std::vector<Subcommand>& registry() {
  static std::vector<Subcommand> r;
  return r;
}
}  // namespace

Registration::Registration(std::string_view name, std::string_view summary, SubcommandFn run) {
  registry().push_back({name, summary, run});
}

}  // namespace candela::tool

int main(int argc, char** argv) {
  using candela::tool::registry;
  auto& cmds = registry();
  std::sort(cmds.begin(), cmds.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  auto usage = [&](FILE* to) {
    std::fprintf(to,
                 "usage: candela-tool SUBCOMMAND [OPTIONS]   (candela-tool SUBCOMMAND "
                 "--help)\n\nSubcommands:\n");
    for (const auto& c : cmds)
      std::fprintf(to, "  %-16.*s %.*s\n", static_cast<int>(c.name.size()), c.name.data(),
                   static_cast<int>(c.summary.size()), c.summary.data());
  };
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  if (std::string(argv[1]) == "--version") {
    std::printf("candela-tool 0.1.0\n");
    return 0;
  }
  for (const auto& c : cmds) {
    if (c.name == argv[1]) {
      std::string name = std::string("candela-tool ") + argv[1];
      std::vector<char*> args(argv + 1, argv + argc);
      args[0] = name.data();
      // One place reports what a subcommand throws ("candela-tool NAME: why",
      // status 1); subcommands catch only what they answer differently
      // (a bad value: status 2).
      try {
        return c.run(static_cast<int>(args.size()), args.data());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
        return 1;
      }
    }
  }
  std::fprintf(stderr, "candela-tool: unknown subcommand '%s'\n\n", argv[1]);
  usage(stderr);
  return 2;
}
