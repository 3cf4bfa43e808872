// libgpiod 1.x (v1 API). The v2 counterpart is gpio_line_v2.cpp.
#include <fcntl.h>
#include <gpiod.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "input/gpio_line.h"

namespace candela {
namespace {

class GpioLineV1 final : public GpioLine {
 public:
  GpioLineV1(gpiod_chip* chip, gpiod_line* line, std::string description)
      : chip_(chip), line_(line), description_(std::move(description)) {
    fd_ = gpiod_line_event_get_fd(line_);
    // Reads must never block the input thread, whatever poll() said.
    const int flags = fcntl(fd_, F_GETFL);
    if (flags >= 0) fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  }
  ~GpioLineV1() override {
    gpiod_line_release(line_);
    gpiod_chip_close(chip_);
  }
  int fd() const override { return fd_; }
  int read_edges(GpioEdge* out, int max) override {
    gpiod_line_event events[16];
    if (max > 16) max = 16;
    const int n = gpiod_line_event_read_fd_multiple(fd_, events, static_cast<unsigned>(max));
    if (n < 0) return errno == EAGAIN || errno == EINTR ? 0 : -1;
    for (int i = 0; i < n; ++i) {
      out[i].active = events[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
      out[i].t_ns =
          static_cast<int64_t>(events[i].ts.tv_sec) * 1'000'000'000 + events[i].ts.tv_nsec;
    }
    return n;
  }
  int value() override {
    const int v = gpiod_line_get_value(line_);
    return v < 0 ? -1 : v;
  }
  const std::string& description() const override { return description_; }

 private:
  gpiod_chip* chip_;
  gpiod_line* line_;
  std::string description_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<GpioLine> open_gpio_line(const InputSpec& spec, const char* consumer) {
  // open_lookup accepts a path, a name, a label or a number.
  gpiod_chip* chip = gpiod_chip_open_lookup(spec.chip.c_str());
  if (!chip)
    throw RuntimeError("GPIO chip \"" + spec.chip + "\" not found (" + std::strerror(errno) + ")");
  gpiod_line* line = spec.line_name.empty()
                         ? gpiod_chip_get_line(chip, static_cast<unsigned>(spec.line_offset))
                         : gpiod_chip_find_line(chip, spec.line_name.c_str());
  const std::string chip_desc =
      std::string(gpiod_chip_name(chip)) + " [" + gpiod_chip_label(chip) + "]";
  if (!line) {
    const std::string what = spec.line_name.empty() ? "offset " + std::to_string(spec.line_offset)
                                                    : "named \"" + spec.line_name + "\"";
    const std::string lines = std::to_string(gpiod_chip_num_lines(chip));
    gpiod_chip_close(chip);
    throw RuntimeError("GPIO " + chip_desc + " has no line " + what + " (it has " + lines +
                       " lines)");
  }
  gpiod_line_request_config cfg{};
  cfg.consumer = consumer;
  cfg.request_type = GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES;
  switch (spec.bias) {
    case InputSpec::Bias::kAsIs:
      break;
    case InputSpec::Bias::kDisabled:
      cfg.flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
      break;
    case InputSpec::Bias::kPullUp:
      cfg.flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
      break;
    case InputSpec::Bias::kPullDown:
      cfg.flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
      break;
  }
  if (spec.active_low) cfg.flags |= GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW;
  const std::string desc =
      chip_desc + " line " + std::to_string(gpiod_line_offset(line)) +
      (gpiod_line_name(line) ? std::string(" (") + gpiod_line_name(line) + ")" : std::string());
  if (gpiod_line_request(line, &cfg, 0) < 0) {
    const int err = errno;
    const char* user = gpiod_line_consumer(line);
    gpiod_chip_close(chip);
    throw RuntimeError("GPIO " + desc + ": request refused: " + std::strerror(err) +
                       (user ? std::string(" (in use by \"") + user + "\")" : std::string()));
  }
  return std::make_unique<GpioLineV1>(chip, line, desc);
}

std::string gpio_library_version() {
  return std::string("libgpiod ") + gpiod_version_string() + " (v1 API)";
}

}  // namespace candela
