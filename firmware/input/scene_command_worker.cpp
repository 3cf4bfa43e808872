#include "input/scene_command_worker.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "input/kiosk_control.h"

namespace candela {

SceneCommandWorker::SceneCommandWorker(KioskControl& kiosk) : kiosk_(kiosk) {
  fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (fd_ < 0) throw RuntimeError(std::string("scene commands: eventfd: ") + std::strerror(errno));
  thread_ = std::thread([this] { run(); });
}

SceneCommandWorker::~SceneCommandWorker() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
    jobs_.clear();
  }
  cv_.notify_all();
  thread_.join();
  close(fd_);
}

void SceneCommandWorker::submit(uint64_t ticket, const ControlCommand& c) {
  {
    std::lock_guard lock(mu_);
    jobs_.emplace_back(ticket, c);
  }
  cv_.notify_one();
}

std::vector<std::pair<uint64_t, std::string>> SceneCommandWorker::take() {
  uint64_t n = 0;
  (void)!read(fd_, &n, sizeof n);  // clears it (EAGAIN when already clear)
  std::lock_guard lock(mu_);
  return std::exchange(done_, {});
}

void SceneCommandWorker::run() {
  std::unique_lock lock(mu_);
  for (;;) {
    cv_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    auto [ticket, command] = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    std::string reply = kiosk_.command(command);
    lock.lock();
    done_.emplace_back(ticket, std::move(reply));
    const uint64_t one = 1;
    (void)!write(fd_, &one, sizeof one);
  }
}

}  // namespace candela
