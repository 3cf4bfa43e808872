// The noise-table command: `candela-tool noise` and `candela-noise` (the
// same command alone, which the build uses to make the runtime's built-in
// tables without building candela-tool). `program` names it in its help and
// its errors.
#pragma once

namespace candela::noise {

int run_noise_command(int argc, char** argv, const char* program);

}  // namespace candela::noise
