// A model as candela-tool's subcommands name it: "builtin:candle" and
// "builtin:fire" (the bytes embedded in candela, as scenes and stories name
// them), else a model file's path.
#pragma once

#include <string>

#include "model/flame_model.h"

namespace candela::tools {

// Throws ConfigError("<built-in models>", NAME, ...) for an unknown built-in
// name (listing the built-in ones) and ModelError for a file that does not load.
model::FlameModel load_named_model(const std::string& name_or_path);

}  // namespace candela::tools
