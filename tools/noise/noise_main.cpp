// candela-noise: the noise-table command alone (noise/noise_cli.h), so the
// build can make the runtime's built-in tables without candela-tool.
#include "noise/noise_cli.h"

int main(int argc, char** argv) {
  return candela::noise::run_noise_command(argc, argv, "candela-noise");
}
