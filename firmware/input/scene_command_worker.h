// The kiosk commands that load a scene (`scene`, `reload`: a file read, a
// model, a story planned, then a wait for the frame loop to build it, up to
// a minute) run here, on a thread of their own, so the input thread goes on
// serving GPIO and the other control clients meanwhile (issue 34). The
// input thread submits a command with its control-socket ticket, polls fd()
// and hands each finished reply to ControlServer::complete().
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "input/control_channel.h"

namespace candela {

class KioskControl;

class SceneCommandWorker {
 public:
  // Starts the thread; throws RuntimeError when its eventfd cannot be made.
  explicit SceneCommandWorker(KioskControl& kiosk);
  // Joins the thread after the command it runs (the kiosk's stop() ends a
  // wait for the frame loop); commands not started are dropped.
  ~SceneCommandWorker();
  SceneCommandWorker(const SceneCommandWorker&) = delete;
  SceneCommandWorker& operator=(const SceneCommandWorker&) = delete;

  // Whether `c` is one of the commands run here.
  static bool runs(const ControlCommand& c) {
    return c.kind == ControlCommand::Kind::kScene || c.kind == ControlCommand::Kind::kReload;
  }
  // Queues `c`, to be answered as `ticket`. The control socket has at most
  // one waiting line per client, so the queue holds at most kMaxClients.
  void submit(uint64_t ticket, const ControlCommand& c);
  // Readable (POLLIN) while finished replies wait to be taken.
  int fd() const { return fd_; }
  // The finished replies (ticket, reply line), oldest first.
  std::vector<std::pair<uint64_t, std::string>> take();

 private:
  void run();
  KioskControl& kiosk_;
  int fd_ = -1;  // eventfd
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::pair<uint64_t, ControlCommand>> jobs_;
  std::vector<std::pair<uint64_t, std::string>> done_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace candela
