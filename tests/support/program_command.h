#pragma once
// How a C++ test starts a program of the build it tests (e.g. posix_spawn of
// `candela`): program_command(path) is the command to run it, argv[0] first.
// In an arm64 cross build (board/arm64/) ctest sets CANDELA_EMULATOR for
// every test (tests/CMakeLists.txt: CMAKE_CROSSCOMPILING_EMULATOR, e.g.
// /usr/bin/qemu-aarch64-static) and it goes in front, so this machine runs the
// arm64 program through qemu-user without binfmt_misc; elsewhere it is empty.
// The same rule as tests/support/programs.py for the scripts.
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace candela::test {

inline std::vector<std::string> program_command(const std::string& path) {
  std::vector<std::string> cmd;
  if (const char* emulator = std::getenv("CANDELA_EMULATOR")) {
    std::istringstream words(emulator);  // space-separated, like the CMake list it comes from
    for (std::string w; words >> w;) cmd.push_back(w);
  }
  cmd.push_back(path);
  return cmd;
}

}  // namespace candela::test
