// libgpiod 2.x (v2 API, Debian 13). The v1 counterpart is gpio_line_v1.cpp.
// CMake picks the file by version. On Debian 12 (libgpiod 1.6) tests/run-all.sh
// still builds it, against trixie's libgpiod (board/libgpiod2/build.sh), and
// runs the gpio virtual-board tests on it.
#include <dirent.h>
#include <fcntl.h>
#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "input/gpio_line.h"

namespace candela {
namespace {

// What gpiod_chip_info says about a chip, copied out (the info is freed here).
struct ChipInfo {
  std::string name;   // gpiochipN
  std::string label;  // e.g. "pinctrl-rp1", "vboard-gpio"
  size_t num_lines = 0;
};

ChipInfo chip_info(gpiod_chip* chip) {
  ChipInfo out;
  gpiod_chip_info* info = gpiod_chip_get_info(chip);
  if (!info) return out;
  out.name = gpiod_chip_info_get_name(info);
  out.label = gpiod_chip_info_get_label(info);
  out.num_lines = gpiod_chip_info_get_num_lines(info);
  gpiod_chip_info_free(info);
  return out;
}

// v2 opens chips by path only; like v1's gpiod_chip_open_lookup, accept a
// path, a name (gpiochipN), a number or a label.
gpiod_chip* open_chip(const std::string& what) {
  if (what.empty()) {
    errno = ENOENT;
    return nullptr;
  }
  if (what[0] == '/') return gpiod_chip_open(what.c_str());
  if (what.find_first_not_of("0123456789") == std::string::npos)
    return gpiod_chip_open(("/dev/gpiochip" + what).c_str());
  if (what.rfind("gpiochip", 0) == 0)
    if (gpiod_chip* c = gpiod_chip_open(("/dev/" + what).c_str())) return c;
  DIR* dir = opendir("/dev");
  if (!dir) return nullptr;
  gpiod_chip* found = nullptr;
  while (dirent* e = readdir(dir)) {
    if (std::strncmp(e->d_name, "gpiochip", 8) != 0) continue;
    gpiod_chip* c = gpiod_chip_open((std::string("/dev/") + e->d_name).c_str());
    if (!c) continue;
    if (chip_info(c).label == what) {
      found = c;
      break;
    }
    gpiod_chip_close(c);
  }
  closedir(dir);
  if (!found) errno = ENOENT;
  return found;
}

class GpioLineV2 final : public GpioLine {
 public:
  GpioLineV2(gpiod_chip* chip, gpiod_line_request* req, unsigned offset, std::string description)
      : chip_(chip), req_(req), offset_(offset), description_(std::move(description)) {
    buffer_ = gpiod_edge_event_buffer_new(16);
    fd_ = gpiod_line_request_get_fd(req_);
    const int flags = fcntl(fd_, F_GETFL);
    if (flags >= 0) fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  }
  ~GpioLineV2() override {
    gpiod_edge_event_buffer_free(buffer_);
    gpiod_line_request_release(req_);
    gpiod_chip_close(chip_);
  }
  int fd() const override { return fd_; }
  int read_edges(GpioEdge* out, int max) override {
    if (max > 16) max = 16;
    const int n = gpiod_line_request_read_edge_events(req_, buffer_, static_cast<size_t>(max));
    if (n < 0) return errno == EAGAIN || errno == EINTR ? 0 : -1;
    for (int i = 0; i < n; ++i) {
      gpiod_edge_event* ev =
          gpiod_edge_event_buffer_get_event(buffer_, static_cast<unsigned long>(i));
      out[i].active = gpiod_edge_event_get_event_type(ev) == GPIOD_EDGE_EVENT_RISING_EDGE;
      out[i].t_ns = static_cast<int64_t>(gpiod_edge_event_get_timestamp_ns(ev));
    }
    return n;
  }
  int value() override {
    const int v = static_cast<int>(gpiod_line_request_get_value(req_, offset_));
    return v < 0 ? -1 : (v == GPIOD_LINE_VALUE_ACTIVE ? 1 : 0);
  }
  const std::string& description() const override { return description_; }

 private:
  gpiod_chip* chip_;
  gpiod_line_request* req_;
  unsigned offset_;
  std::string description_;
  gpiod_edge_event_buffer* buffer_ = nullptr;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<GpioLine> open_gpio_line(const InputSpec& spec, const char* consumer) {
  gpiod_chip* chip = open_chip(spec.chip);
  if (!chip)
    throw RuntimeError("GPIO chip \"" + spec.chip + "\" not found (" + std::strerror(errno) + ")");
  // Described as v1 describes it: "gpiochip0 [vboard-gpio]".
  const ChipInfo ci = chip_info(chip);
  const std::string chip_desc = ci.name + " [" + ci.label + "]";
  int offset = spec.line_offset;
  if (!spec.line_name.empty())
    offset = gpiod_chip_get_line_offset_from_name(chip, spec.line_name.c_str());
  gpiod_line_info* info =
      offset >= 0 ? gpiod_chip_get_line_info(chip, static_cast<unsigned>(offset)) : nullptr;
  if (!info) {
    const std::string what = spec.line_name.empty() ? "offset " + std::to_string(spec.line_offset)
                                                    : "named \"" + spec.line_name + "\"";
    gpiod_chip_close(chip);
    throw RuntimeError("GPIO " + chip_desc + " has no line " + what + " (it has " +
                       std::to_string(ci.num_lines) + " lines)");
  }
  const char* name = gpiod_line_info_get_name(info);
  const std::string desc = chip_desc + " line " + std::to_string(offset) +
                           (name ? std::string(" (") + name + ")" : std::string());
  gpiod_line_info_free(info);

  gpiod_line_settings* settings = gpiod_line_settings_new();
  gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_INPUT);
  gpiod_line_settings_set_edge_detection(settings, GPIOD_LINE_EDGE_BOTH);
  gpiod_line_settings_set_event_clock(settings, GPIOD_LINE_CLOCK_MONOTONIC);
  gpiod_line_settings_set_active_low(settings, spec.active_low);
  switch (spec.bias) {
    case InputSpec::Bias::kAsIs:
      gpiod_line_settings_set_bias(settings, GPIOD_LINE_BIAS_AS_IS);
      break;
    case InputSpec::Bias::kDisabled:
      gpiod_line_settings_set_bias(settings, GPIOD_LINE_BIAS_DISABLED);
      break;
    case InputSpec::Bias::kPullUp:
      gpiod_line_settings_set_bias(settings, GPIOD_LINE_BIAS_PULL_UP);
      break;
    case InputSpec::Bias::kPullDown:
      gpiod_line_settings_set_bias(settings, GPIOD_LINE_BIAS_PULL_DOWN);
      break;
  }
  // No kernel debounce (debounce_period_us): v1 has none, and sensor_logic's
  // debouncer needs the raw edges to date a press from its first edge; both
  // together would also make a press wait twice. So v1 and v2 boards agree.
  gpiod_line_config* line_cfg = gpiod_line_config_new();
  const unsigned off = static_cast<unsigned>(offset);
  gpiod_line_config_add_line_settings(line_cfg, &off, 1, settings);
  gpiod_request_config* req_cfg = gpiod_request_config_new();
  gpiod_request_config_set_consumer(req_cfg, consumer);
  gpiod_line_request* req = gpiod_chip_request_lines(chip, req_cfg, line_cfg);
  const int err = errno;
  gpiod_request_config_free(req_cfg);
  gpiod_line_config_free(line_cfg);
  gpiod_line_settings_free(settings);
  if (!req) {
    // Name who holds the line, as v1 does, when that is why.
    std::string user;
    if (gpiod_line_info* now = gpiod_chip_get_line_info(chip, off)) {
      if (const char* c = gpiod_line_info_get_consumer(now); c && gpiod_line_info_is_used(now))
        user = std::string(" (in use by \"") + c + "\")";
      gpiod_line_info_free(now);
    }
    gpiod_chip_close(chip);
    throw RuntimeError("GPIO " + desc + ": request refused: " + std::strerror(err) + user);
  }
  return std::make_unique<GpioLineV2>(chip, req, off, desc);
}

std::string gpio_library_version() {
  return std::string("libgpiod ") + gpiod_api_version() + " (v2 API)";
}

}  // namespace candela
