// candela-tool's subcommands: each cmd_NAME.cpp reads its own options with a
// CLI::App of its own (argv[0] is "candela-tool NAME") and defines its entry
// point here; main.cpp lists them all for CLI11's add_subcommand. A new
// subcommand is declared here and listed there (nothing registers itself, so
// nothing can be dropped by the linker).
#pragma once

namespace candela::tool {

int cmd_build(int argc, char** argv);
int cmd_flame_photo(int argc, char** argv);
int cmd_ingest(int argc, char** argv);
int cmd_inspect(int argc, char** argv);
int cmd_measure(int argc, char** argv);
int cmd_noise(int argc, char** argv);
int cmd_render_weights(int argc, char** argv);
int cmd_simulate(int argc, char** argv);
int cmd_story(int argc, char** argv);
int cmd_studio(int argc, char** argv);
int cmd_synth(int argc, char** argv);
int cmd_texturize(int argc, char** argv);
int cmd_transition(int argc, char** argv);

}  // namespace candela::tool
