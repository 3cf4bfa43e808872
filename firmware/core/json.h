// A string as a JSON string literal, quotes included: the manifests, the
// state query and the recorder's metadata all write JSON by hand (small,
// fixed shapes), and this is the one place that escapes text for them.
#pragma once

#include <string>
#include <string_view>

namespace candela {

// "text" with ", \ and control characters escaped (\u00XX).
std::string json_quote(std::string_view text);

}  // namespace candela
