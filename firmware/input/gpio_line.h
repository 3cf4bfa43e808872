// One requested GPIO input line with edge events: the only interface the
// rest of the input code sees. libgpiod's v1 (Debian 12, Raspberry Pi OS
// bookworm) and v2 (Debian 13) APIs differ completely; each lives in one file
// (gpio_line_v1.cpp, gpio_line_v2.cpp), and CMake compiles the one that
// matches the installed library.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "scene/input_spec.h"

namespace candela {

struct GpioEdge {
  bool active = false;  // the line's logical level after the edge (active_low applied)
  int64_t t_ns = 0;     // kernel timestamp, CLOCK_MONOTONIC
};

class GpioLine {
 public:
  virtual ~GpioLine() = default;
  // Readable when edges are pending (poll it; reads never block).
  virtual int fd() const = 0;
  // Reads pending edges into out[0..max); returns how many (0: none pending),
  // or -1 when the line is gone (the chip was removed): close and retry.
  virtual int read_edges(GpioEdge* out, int max) = 0;
  // The logical level now: 1 or 0, or -1 when the line is gone.
  virtual int value() = 0;
  // e.g. "gpiochip1 [gpio-sim.0-node0] line 3 (button-left)"
  virtual const std::string& description() const = 0;
};

// Opens the chip (path, name, label or number) and requests the line for
// both-edge events with the spec's bias and active_low. Throws RuntimeError
// saying what is missing (chip, line) or why the request was refused.
std::unique_ptr<GpioLine> open_gpio_line(const InputSpec& spec, const char* consumer);

// "libgpiod 1.6.3 (v1 API)": for logs and --version.
std::string gpio_library_version();

}  // namespace candela
