#include "core/json.h"

#include <cstdio>
#include <cstdlib>

namespace candela {

double json_decimals(double v, int decimals) {
  char buf[400];  // %f of the largest double: 309 digits
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return std::strtod(buf, nullptr);
}

double json_digits(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return std::strtod(buf, nullptr);
}

}  // namespace candela
