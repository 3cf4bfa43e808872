// JSON helpers without a JSON library (candela_core has none): a string as
// a JSON string literal, and numbers rounded as a report shows them before
// nlohmann_json (firmware/input, app/, the recorder) writes them.
#pragma once

#include <string>
#include <string_view>

namespace candela {

// "text" with ", \ and control characters escaped (\u00XX).
std::string json_quote(std::string_view text);

// `v` rounded to `decimals` places as printf's "%.*f" rounds it (so 0.5 is
// written 0.5, not 0.500000000001); NaN and infinities stay (JSON: null).
double json_decimals(double v, int decimals);
// `v` rounded to `digits` significant digits as printf's "%.*g" rounds it.
double json_digits(double v, int digits);

}  // namespace candela
