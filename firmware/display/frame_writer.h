// Where headless frames go: a PNG folder, a .y4m video, or an .mp4 through
// ffmpeg. Writing happens on its own thread into preallocated slots, so the
// render thread does no file I/O; it waits only if the disk falls behind.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace candela {

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // One RGBA frame, rows bottom to top (as glReadPixels returns them).
  virtual void write(const uint8_t* rgba_bottom_up) = 0;
  virtual void close() {}
};

// Chooses by path: "*.y4m", "*.mp4", "*.mkv" (H.264), "*.webm" (VP9; these
// need ffmpeg on PATH), else a folder of
// frame_000000.png ... Throws RuntimeError naming the path and the problem.
// `sound_path` (ffmpeg videos only): a .wav that close() muxes into the
// finished video (a second ffmpeg run, video stream copied, AAC or Opus
// audio, into a temporary file renamed over the video; the .wav is then
// removed). Skipped when the .wav is missing or holds no samples.
std::unique_ptr<FrameSink> open_frame_sink(const std::string& path, int width, int height, int fps,
                                           const std::string& sound_path = {});
// Empty when `path` names an output open_frame_sink writes: *.y4m, *.mp4,
// *.mkv, *.webm, or a folder (a name without an extension, or a folder that
// exists); else what is expected instead ("a folder (...) or a .y4m ... file"). "frames.avi" no
// longer silently became a folder of PNGs.
std::string frame_sink_problem(const std::string& path);
// Empty when the video at `path` is whole: an .mp4's boxes tile the file and
// hold its index (moov); an .mkv's or .webm's segment has its size, within
// the file. Else what is wrong ("has no index (moov): ..."). Other names: "".
// ffmpeg exits 0 when the disk fills as it writes the trailer.
std::string video_file_problem(const std::string& path);

class AsyncFrameWriter {
 public:
  AsyncFrameWriter(std::unique_ptr<FrameSink> sink, int width, int height, int slots = 3);
  ~AsyncFrameWriter();
  // A slot to read the frame into; waits while every slot is still queued.
  uint8_t* acquire();
  void submit();
  // Waits for every queued frame, closes the sink; rethrows a write error.
  void finish();

 private:
  void run();
  std::unique_ptr<FrameSink> sink_;
  std::vector<std::vector<uint8_t>> slots_;
  std::mutex mu_;
  std::condition_variable cv_;
  size_t head_ = 0, count_ = 0;  // queued slots: [head_, head_ + count_)
  bool stop_ = false;
  bool finished_ = false;
  bool reported_ = false;  // acquire() has thrown error_ already
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace candela
