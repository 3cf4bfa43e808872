// candela-tool subcommands register themselves: in cmd_NAME.cpp write
//   static const candela::tool::Registration reg{"noise", "make 1/f^beta noise tables", run_noise};
// where run_noise(int argc, char** argv) gets argv[0] = "candela-tool noise".
// The file must be compiled into the candela-tool executable itself
// (target_sources), not into a static library, or the linker drops it.
#pragma once

#include <string_view>

namespace candela::tool {

using SubcommandFn = int (*)(int argc, char** argv);

struct Subcommand {
  std::string_view name;
  std::string_view summary;
  SubcommandFn run;
};

struct Registration {
  Registration(std::string_view name, std::string_view summary, SubcommandFn run);
};

}  // namespace candela::tool
