#include "capture_loop.h"

#include <chrono>

#include "input/v4l2_capture.h"

namespace candela::record {

CaptureLoop::CaptureLoop(VideoCapture& camera, PngWriterPool& writers, const RecordOptions& options,
                         FrameObserver* preview)
    : camera_(camera),
      writers_(writers),
      options_(options),
      preview_(preview),
      format_(camera.format()) {}

std::optional<LoopEnd> CaptureLoop::should_end(const std::atomic<bool>& stop,
                                               double elapsed_s) const {
  if (stop.load())
    return LoopEnd{
        preview_ && preview_->quit_requested() ? "stopped from the preview" : "stopped by a signal",
        kExitOk, true};
  if (const WriteFailure f = writers_.failure())
    return LoopEnd{"writing frames failed: " + f.message, kExitOutput, false, f.fault};
  if (options_.frames && queued_ >= options_.frames)
    return LoopEnd{"frame count reached", kExitOk, true};
  if (options_.seconds > 0 && elapsed_s >= options_.seconds)
    return LoopEnd{"duration reached", kExitOk, true};
  return std::nullopt;
}

void CaptureLoop::take(const VideoFrame& frame) {
  // Sequence gaps: the driver dropped frames before we saw them.
  if (have_sequence_ && frame.sequence > next_sequence_)
    for (uint32_t s = next_sequence_; s < frame.sequence && dropped_.size() < 100000; ++s)
      dropped_.push_back(s);
  have_sequence_ = true;
  next_sequence_ = frame.sequence + 1;
  FrameSlot* slot = writers_.acquire();
  const bool ok =
      slot && frame.bytes &&
      (options_.color ? frame_to_rgb(format_, frame.data, frame.bytes, slot->pixels.data())
                      : frame_to_gray(format_, frame.data, frame.bytes, slot->pixels.data()));
  camera_.release(frame);
  if (!ok) {
    dropped_.push_back(frame.sequence);  // writers behind, or a damaged frame
    if (slot) writers_.give_back(slot);
    return;
  }
  slot->sequence = frame.sequence;
  slot->timestamp_ns = frame.timestamp_ns;
  if (preview_) preview_->push(slot->pixels.data(), frame.sequence);
  writers_.submit(slot);
  ++queued_;
}

LoopEnd CaptureLoop::run(const std::atomic<bool>& stop, const Tick& each_second) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto last_tick = t0;
  int silent = 0;
  for (;;) {
    if (auto end = should_end(stop, std::chrono::duration<double>(Clock::now() - t0).count()))
      return *end;
    VideoFrame frame;
    const auto r = camera_.next(frame, 2000);
    if (r == VideoCapture::Result::kGone)
      return LoopEnd{"the camera went away: " + camera_.error(), kExitCameraLost};
    if (r == VideoCapture::Result::kTimeout) {
      if (++silent >= 3)  // 6 s without a frame: the camera is as good as gone
        return LoopEnd{"the camera delivered no frame for 6 s", kExitCameraLost};
      continue;
    }
    silent = 0;
    take(frame);
    if (Clock::now() - last_tick > std::chrono::seconds(1)) {
      last_tick = Clock::now();
      if (each_second)
        if (auto end = each_second()) return *end;
    }
  }
}

}  // namespace candela::record
