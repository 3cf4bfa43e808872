// One way every Candela program reports a bad command line (CLI11): on
// stderr "PROGRAM: error: WHAT" and where to find --help, and exit status 2,
// as the POSIX utilities do; --help and --version print and exit 0. (CLI11's
// own exit statuses were 105, 106, 109... depending on the error.)
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "core/wxh.h"

namespace candela {

inline constexpr int kUsageExitStatus = 2;

// A number in [lo, hi], NaN and infinities refused: CLI::Range lets NaN
// through (every comparison with it is false).
inline CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < lo || v > hi)
          return "expected a number in [" + CLI::detail::to_string(lo) + ", " +
                 CLI::detail::to_string(hi) + "], got " + text;
        return "";
      },
      "FLOAT in [" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]");
}

// A size "WxH" within [min, max] a side (core/wxh.h), e.g. for --size.
inline CLI::Validator wxh_range(WxH min, WxH max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        if (parse_wxh(text, min, max)) return "";
        return "expected WxH, the width " + std::to_string(min.width) + " to " +
               std::to_string(max.width) + " and the height " + std::to_string(min.height) +
               " to " + std::to_string(max.height) + ", got " + text;
      },
      "WxH");
}

// `app`'s name is the program as the user typed it ("candela-tool build").
inline int usage_exit(CLI::App& app, const CLI::ParseError& e) {
  const std::string program = app.get_name();
  app.failure_message([program](const CLI::App*, const CLI::Error& error) {
    return program + ": error: " + error.what() + "\nRun '" + program +
           " --help' for the options.\n";
  });
  return app.exit(e) == 0 ? 0 : kUsageExitStatus;
}

}  // namespace candela
