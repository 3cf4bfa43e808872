// The capture loop: takes frames from the camera, converts each into a free
// writer slot (gray or RGB) and queues it, notes the driver's sequence gaps
// and the frames the writers could not take as dropped, and decides why the
// recording ends (limit reached, signal or preview, camera gone or silent,
// a write failure). It never waits for the writers or the preview.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "input/video_capture.h"
#include "output_error.h"
#include "png_writer_pool.h"
#include "recorder.h"

namespace candela::record {

// Why the recording ended.
struct LoopEnd {
  std::string reason;
  int exit_code = kExitOk;
  bool complete = false;                   // ended as asked (limit, signal, the preview closed)
  OutputFault fault = OutputFault::kNone;  // what the output folder did, if it failed
};

class CaptureLoop {
 public:
  // Called about once a second (the manifest is rewritten there); a LoopEnd
  // ends the recording.
  using Tick = std::function<std::optional<LoopEnd>()>;

  CaptureLoop(VideoCapture& camera, PngWriterPool& writers, const RecordOptions& options,
              FrameObserver* preview);

  LoopEnd run(const std::atomic<bool>& stop, const Tick& each_second);
  // Sequence numbers of the frames lost so far (by the driver or because the
  // writers were behind), in the order noticed; at most about 100000.
  const std::vector<uint32_t>& dropped() const { return dropped_; }

 private:
  std::optional<LoopEnd> should_end(const std::atomic<bool>& stop, double elapsed_s) const;
  void take(const VideoFrame& frame);

  VideoCapture& camera_;
  PngWriterPool& writers_;
  const RecordOptions& options_;
  FrameObserver* preview_;
  VideoFormat format_;
  std::vector<uint32_t> dropped_;
  bool have_sequence_ = false;
  uint32_t next_sequence_ = 0;
  uint64_t queued_ = 0;
};

}  // namespace candela::record
