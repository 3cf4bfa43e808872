// Reading [[input]] tables from a scene's TOML (only scene_file.cpp needs it).
#pragma once

#include <toml++/toml.h>

#include <string>
#include <vector>

#include "scene/input_spec.h"

namespace candela {

// Parses the top-level `input` array of a scene ([[input]] tables). Null: no
// inputs. Throws ConfigError naming the file and key (input[2].line, ...).
std::vector<InputSpec> parse_inputs(const toml::node* node, const std::string& file);

}  // namespace candela
