// candela-tool noise: the noise-table command (noise/noise_cli.h).
#include "candela-tool/subcommand.h"
#include "noise/noise_cli.h"

namespace candela::tool {
namespace {

int run_noise(int argc, char** argv) {
  return noise::run_noise_command(argc, argv, "candela-tool noise");
}

}  // namespace
}  // namespace candela::tool

int candela::tool::cmd_noise(int argc, char** argv) { return run_noise(argc, argv); }
