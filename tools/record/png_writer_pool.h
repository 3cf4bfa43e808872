// The PNG writers: a fixed set of frame slots (allocated once), a queue the
// capture loop fills without ever waiting, and writer threads that turn each
// slot into frames/NNNNNNNN.png (named by the driver's sequence number). The
// pool owns the slots and the threads; the capture loop borrows a slot,
// fills it and hands it back through submit().
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "output_error.h"

namespace candela::record {

struct WrittenFrame {
  uint32_t sequence = 0;
  int64_t timestamp_ns = 0;
};

// The first write that failed: the message and its typed fault.
struct WriteFailure {
  std::string message;
  OutputFault fault = OutputFault::kNone;
  explicit operator bool() const { return fault != OutputFault::kNone; }
};

struct FrameSlot {
  std::vector<uint8_t> pixels;  // width x height x channels
  uint32_t sequence = 0;
  int64_t timestamp_ns = 0;
};

class PngWriterPool {
 public:
  // Writes one slot to `path` (a PNG by default); throws on failure: an
  // OutputError carries its errno, anything else is classified from the
  // filesystem holding `frames_dir` (libpng reports no errno).
  using WriteFn = std::function<void(const std::string& path, const FrameSlot& slot)>;

  PngWriterPool(std::string frames_dir, int width, int height, int channels, int slots, int threads,
                WriteFn write = {});
  ~PngWriterPool();
  PngWriterPool(const PngWriterPool&) = delete;
  PngWriterPool& operator=(const PngWriterPool&) = delete;

  // A free slot, or nullptr when every slot is queued or being written (the
  // writers are behind). Never waits.
  FrameSlot* acquire();
  // Back unused (the frame was damaged).
  void give_back(FrameSlot* slot);
  // Queues the filled slot for writing.
  void submit(FrameSlot* slot);
  // Writes what is queued, then stops the threads. Idempotent.
  void close();

  // Frames written so far, in sequence order.
  std::vector<WrittenFrame> written() const;
  size_t written_count() const;
  // The rate the camera delivered, from the written frames' timestamps
  // (sequence gaps count as frame periods); 0 until 10 frames.
  double measured_fps() const;
  // The first failure; after one, nothing more is written.
  WriteFailure failure() const;

  // frames/NNNNNNNN.png's name for a sequence number.
  static std::string file_name(uint32_t sequence);

 private:
  void run();
  WriteFailure classify(const std::exception& e, size_t frame_bytes) const;

  const std::string frames_dir_;
  WriteFn write_;
  std::vector<FrameSlot> slots_;
  mutable std::mutex mutex_;
  std::condition_variable work_;
  std::deque<FrameSlot*> pending_;
  std::vector<FrameSlot*> free_;
  std::map<uint32_t, WrittenFrame> written_;  // by sequence
  WriteFailure failure_;
  bool closing_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace candela::record
