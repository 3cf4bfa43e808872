// candela-tool studio MODEL [STORY]: runs candela-studio, which lies beside
// candela-tool (the studio links the runtime, and the runtime's noise tables
// are made by candela-tool, so the studio is a program of its own).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "subcommand.h"

namespace {

int run_studio(int argc, char** argv) {
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string studio =
      (ec ? std::filesystem::path(".") : self.parent_path()) / "candela-studio";
  std::vector<char*> args(argv, argv + argc);
  args.push_back(nullptr);
  execv(studio.c_str(), args.data());
  std::fprintf(stderr,
               "candela-tool studio: cannot run %s (%s): the studio is built only with Dear ImGui "
               "and X11 (apt-get install libimgui-dev libx11-dev, then rebuild)\n",
               studio.c_str(), std::strerror(errno));
  return 1;
}

}  // namespace

int candela::tool::cmd_studio(int argc, char** argv) { return run_studio(argc, argv); }
