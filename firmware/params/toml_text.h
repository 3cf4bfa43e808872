// TOML text (a scene, the kiosk's config, a story) parsed by toml++ after a
// nesting check; a syntax error is ConfigError(name, "line L, column C", ...).
#pragma once

#include <toml++/toml.h>

#include <string>
#include <string_view>

namespace candela {

// Deeper TOML nesting would overflow toml++'s stack (README: "Limits").
inline constexpr int kMaxSceneNesting = 32;

toml::table parse_toml_text(std::string_view text, const std::string& name);

}  // namespace candela
