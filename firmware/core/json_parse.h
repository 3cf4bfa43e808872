// The one way Candela reads JSON text (model headers, dataset manifests, MQTT
// messages, recorder reports): the nesting depth is bounded before any tree
// is built. nlohmann_json parses iteratively, but dump(), copies and
// comparisons recurse, so a few hundred kilobytes of "[[[[..." would
// overflow the stack in whatever touches the tree next (found by a hostile
// model whose checksum re-serialises its header).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace candela {

// Deeper than any file Candela writes (a model header nests 4 levels) and
// shallow enough for every recursive walk in nlohmann_json.
inline constexpr int kMaxJsonDepth = 32;

namespace json_detail {
// Empty when `text` is JSON nested at most `max_depth` arrays/objects deep,
// else what is wrong with it ("nested deeper than 32 levels at byte 33").
std::string check_depth(std::string_view text, int max_depth);
}  // namespace json_detail

// `text` parsed, or std::nullopt with `*error` saying why (not JSON, or
// nested deeper than `max_depth`).
template <class Json = nlohmann::json>
std::optional<Json> try_parse_json(std::string_view text, std::string* error,
                                   int max_depth = kMaxJsonDepth) {
  std::string why = json_detail::check_depth(text, max_depth);
  if (!why.empty()) {
    if (error) *error = std::move(why);
    return std::nullopt;
  }
  Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) {  // check_depth parsed it already: not reached
    if (error) *error = "not valid JSON";
    return std::nullopt;
  }
  return j;
}

// `text` parsed; a ConfigError naming `file` (and `key`, where the text is a
// part of a file) otherwise.
nlohmann::json parse_json(std::string_view text, const std::string& file,
                          const std::string& key = "", int max_depth = kMaxJsonDepth);

}  // namespace candela
