#include "params/toml_text.h"

#include <sstream>

#include "core/error.h"

namespace candela {
namespace {

// toml++ recurses once per part of a dotted key or table header (and per
// nested array or inline table): a 100 KB line of `a.a.a...` overflows the
// stack inside parse(). Refuse deep nesting before toml++ sees it. A cheap
// scan: strings and comments skipped, dots counted since the last = , [ ] { }
// or newline (so `a . a` counts too; a float's one dot stays well below).
void check_nesting(std::string_view t, const std::string& name) {
  int line = 1, dots = 0, brackets = 0;
  auto fail = [&](const std::string& what) {
    throw ConfigError(
        name, "line " + std::to_string(line),
        what + " (more than " + std::to_string(kMaxSceneNesting) + " levels; a scene needs a few)");
  };
  const size_t n = t.size();
  for (size_t i = 0; i < n; ++i) {
    const char c = t[i];
    if (c == '\n') {
      ++line;
      dots = 0;
    } else if (c == '#') {
      while (i + 1 < n && t[i + 1] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const bool multi = i + 2 < n && t[i + 1] == c && t[i + 2] == c;
      i += multi ? 3 : 1;
      for (; i < n; ++i) {
        if (t[i] == '\n') {
          if (!multi) break;  // toml++ reports the unterminated string
          ++line;
        } else if (c == '"' && t[i] == '\\') {
          if (i + 1 < n && t[i + 1] == '\n') ++line;
          ++i;
        } else if (t[i] == c && (!multi || (i + 2 < n && t[i + 1] == c && t[i + 2] == c))) {
          if (multi) i += 2;
          // TOML allows up to two more quotes just before a closing delimiter.
          while (multi && i + 1 < n && t[i + 1] == c) ++i;
          break;
        }
      }
      if (i < n && t[i] == '\n') --i;  // counted by the loop
    } else if (c == '.') {
      if (++dots >= kMaxSceneNesting) fail("a dotted key or table header nests too deep");
    } else if (c == '[' || c == '{') {
      dots = 0;
      if (++brackets > kMaxSceneNesting) fail("arrays or inline tables nest too deep");
    } else if (c == ']' || c == '}') {
      dots = 0;
      if (brackets > 0) --brackets;
    } else if (c == '=' || c == ',') {
      dots = 0;
    }
  }
}

}  // namespace

toml::table parse_toml_text(std::string_view text, const std::string& name) {
  check_nesting(text, name);
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << ", column " << e.source().begin.column;
    throw ConfigError(name, where.str(), "TOML syntax error: " + std::string(e.description()));
  }
}

}  // namespace candela
