// One configured GPIO sensor on the input thread: its line (when the chip is
// there), its sensor logic, and the retry/health-check timers. A missing or
// vanished chip is logged once and retried; it never stops anything else.
#pragma once

#include <memory>
#include <string>

#include "input/gpio_line.h"
#include "input/sensor_logic.h"

namespace candela {

class GpioSource {
 public:
  GpioSource(const InputSpec& spec, uint16_t source, const WindSpec& wind);

  const InputSpec& spec() const { return spec_; }
  int fd() const { return line_ ? line_->fd() : -1; }
  // poll() reported `revents` on fd().
  void on_poll(short revents, InputEventSink& sink);
  // Opens/retries, checks the line is still there, settles debounced edges.
  // Returns the next time it needs to run (CLOCK_MONOTONIC ns).
  int64_t service(int64_t now_ns, InputEventSink& sink);

  bool connected() const { return line_ != nullptr; }
  const std::string& status() const { return status_; }  // "ok" or why not
  std::string line_description() const { return line_ ? line_->description() : std::string(); }
  const SensorLogic& logic() const { return logic_; }

  static constexpr int64_t kRetryNs = 2'000'000'000;
  static constexpr int64_t kHealthCheckNs = 1'000'000'000;

 private:
  void lose(const std::string& why, int64_t now_ns, InputEventSink& sink);

  InputSpec spec_;
  SensorLogic logic_;
  std::unique_ptr<GpioLine> line_;
  int64_t next_retry_ns_ = 0;
  int64_t next_check_ns_ = 0;
  std::string status_ = "not opened yet";
  std::string last_logged_;
};

}  // namespace candela
