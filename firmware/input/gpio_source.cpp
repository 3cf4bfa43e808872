#include "input/gpio_source.h"

#include <poll.h>

#include <algorithm>
#include <cstdlib>

#include "core/error.h"
#include "core/log.h"

namespace candela {

GpioSource::GpioSource(const InputSpec& spec, uint16_t source, const WindSpec& wind)
    : spec_(spec), logic_(spec, source, wind) {}

void GpioSource::lose(const std::string& why, int64_t now_ns, InputEventSink& sink) {
  LOG_WARN("input \"%s\": %s lost: %s; the wind goes calm for it, retrying every %d s",
           spec_.name.c_str(), line_->description().c_str(), why.c_str(),
           static_cast<int>(kRetryNs / 1'000'000'000));
  line_.reset();
  logic_.lost(now_ns, sink);
  status_ = "lost: " + why;
  last_logged_ = status_;
  next_retry_ns_ = now_ns + kRetryNs;
}

void GpioSource::on_poll(short revents, InputEventSink& sink) {
  if (!line_) return;
  if (revents & POLLIN) {
    GpioEdge edges[16];
    for (;;) {
      const int n = line_->read_edges(edges, 16);
      if (n < 0) {
        lose("reading edge events failed", monotonic_ns(), sink);
        return;
      }
      const int64_t now = monotonic_ns();
      for (int i = 0; i < n; ++i) {
        // Kernels before 5.7 stamp v1 events with CLOCK_REALTIME: fall back to now.
        const int64_t t = std::abs(edges[i].t_ns - now) < 10'000'000'000 ? edges[i].t_ns : now;
        logic_.edge(edges[i].active, t, sink);
      }
      if (n < 16) break;
    }
  } else if (revents & (POLLERR | POLLHUP | POLLNVAL)) {
    lose("the chip went away", monotonic_ns(), sink);
  }
}

int64_t GpioSource::service(int64_t now_ns, InputEventSink& sink) {
  if (!line_ && now_ns >= next_retry_ns_) {
    try {
      line_ = open_gpio_line(spec_, "candela");
      const int v = line_->value();
      logic_.start(v > 0, now_ns);
      status_ = "ok";
      last_logged_.clear();
      next_check_ns_ = now_ns + kHealthCheckNs;
      LOG_INFO("input \"%s\" (%s): %s", spec_.name.c_str(), input_kind_name(spec_.kind),
               line_->description().c_str());
    } catch (const std::exception& e) {
      status_ = e.what();
      if (status_ != last_logged_) {  // once per distinct reason, not every retry
        LOG_WARN("input \"%s\": %s; retrying every %d s", spec_.name.c_str(), e.what(),
                 static_cast<int>(kRetryNs / 1'000'000'000));
        last_logged_ = status_;
      }
      next_retry_ns_ = now_ns + kRetryNs;
    }
  }
  if (line_ && now_ns >= next_check_ns_) {
    // Some kernels do not wake a poller when the chip goes; ask the line.
    if (line_->value() < 0)
      lose("the line no longer answers", now_ns, sink);
    else
      next_check_ns_ = now_ns + kHealthCheckNs;
  }
  int64_t next = line_ ? next_check_ns_ : next_retry_ns_;
  if (line_) {
    const int64_t d = logic_.service(now_ns, sink);
    if (d >= 0) next = std::min(next, d);
  }
  return next;
}

}  // namespace candela
