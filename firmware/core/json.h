// Numbers rounded as a report shows them, before nlohmann_json (firmware/
// input, app/, the recorder) writes them: JSON text itself is always
// nlohmann_json's (strings escaped by it).
#pragma once

namespace candela {

// `v` rounded to `decimals` places as printf's "%.*f" rounds it (so 0.5 is
// written 0.5, not 0.500000000001); NaN and infinities stay (JSON: null).
double json_decimals(double v, int decimals);
// `v` rounded to `digits` significant digits as printf's "%.*g" rounds it.
double json_digits(double v, int digits);

}  // namespace candela
