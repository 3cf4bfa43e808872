// record(): the output folder, the camera, the writers, the manifest and the
// capture loop, each its own object (output_folder.h, png_writer_pool.h,
// manifest.h, capture_loop.h); this file only puts them together in order.
#include "recorder.h"

#include <linux/videodev2.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "capture_loop.h"
#include "core/log.h"
#include "input/v4l2_capture.h"
#include "input/video_capture.h"
#include "manifest.h"
#include "output_folder.h"
#include "png_writer_pool.h"

namespace candela::record {
namespace {

RecordResult failed(int exit_code, std::string message) {
  RecordResult r;
  r.exit_code = exit_code;
  r.message = std::move(message);
  return r;
}

// The camera as asked for; nullptr with `error` set (usage or camera) when
// it cannot be had.
std::unique_ptr<VideoCapture> open_camera(const RecordOptions& o, RecordResult& error) {
  CaptureSettings s;
  s.device = o.device;
  s.width = o.width;
  s.height = o.height;
  s.fps = o.fps;
  s.buffers = 8;
  if (!o.pixel_format.empty()) {
    s.fourcc = fourcc_from_name(o.pixel_format);
    if (!s.fourcc || !is_supported_format(s.fourcc)) {
      error = failed(kExitUsage,
                     "--format " + o.pixel_format + ": expected GREY, YUYV, UYVY, RGB3 or BGR3");
      return nullptr;
    }
  }
  try {
    return open_video_capture(o.backend, s);
  } catch (const std::exception& e) {
    error = failed(kExitCamera, e.what());
    return nullptr;
  }
}

std::string format_g(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// info.txt: what ingest reads the frame rate from ("NN fps"). `how` follows
// the rate (why it differs from what the camera reported, or nothing).
std::string info_text(const RecordingInfo& info, double rate, const std::string& how) {
  return info.clip + ": recorded by candela-record from " + info.device + " (" + info.card + "), " +
         std::to_string(info.width) + "x" + std::to_string(info.height) + " " + info.pixel_format +
         " at " + format_g(rate) + " fps" + how + "; " + (info.color ? "RGB" : "gray") +
         " PNG frames in frames/; details in manifest.json\n";
}

// What the manifest says of the camera and the format; locks the camera's
// auto controls on the way (what lock_auto did is part of it).
RecordingInfo describe(VideoCapture& cap, const RecordOptions& o, const OutputFolder& folder) {
  AutoLockRequest lock_request;
  lock_request.keep_auto = o.keep_auto;
  lock_request.exposure = o.exposure;
  lock_request.gain = o.gain;
  lock_request.white_balance = o.white_balance;
  const VideoFormat& f = cap.format();
  RecordingInfo info;
  info.locked = cap.lock_auto(lock_request);
  info.controls = cap.controls();
  info.clip = !o.clip.empty() ? o.clip : folder.name();
  info.backend = cap.backend();
  info.device = cap.device();
  info.card = cap.card();
  info.driver = cap.driver();
  info.width = f.width;
  info.height = f.height;
  info.pixel_format = fourcc_name(f.fourcc);
  info.color = o.color;
  info.fps = f.fps > 0 ? f.fps : o.fps;
  info.requested_fps = o.fps;
  return info;
}

// When the camera's timestamps disagree with the rate it reported by over
// 5%, info.txt gets the measured rate (ingest would play the clip too fast
// or slow otherwise).
void correct_info_rate(const OutputFolder& folder, const RecordingInfo& info, double measured) {
  if (!(measured > 0) || std::abs(measured - info.fps) <= 0.05 * info.fps) return;
  const std::string how =
      " (measured from the camera's timestamps; it reported " + format_g(info.fps) + ")";
  try {
    write_atomic(folder.info_path(), info_text(info, std::round(measured * 100) / 100, how));
    LOG_WARN("%s: the camera delivered %.2f fps, not the %g it reported; info.txt says %.2f",
             folder.path().c_str(), measured, info.fps, measured);
  } catch (const std::exception& e) {
    LOG_WARN("%s: info.txt keeps %g fps (%s)", folder.path().c_str(), info.fps, e.what());
  }
}

// Rewrites manifest.json from the writers' and the loop's state, keeping the
// reserve on disk grown with it.
class ManifestWriter {
 public:
  ManifestWriter(const OutputFolder& folder, const RecordingInfo& info,
                 const PngWriterPool& writers, FrameObserver* preview)
      : folder_(folder),
        info_(info),
        writers_(writers),
        preview_(preview),
        reserve_(folder.reserve_path()) {}

  // False when not even 64 KiB can be kept for the final manifest.
  bool reserve_initial() { return reserve_.grow(65536); }

  // While recording: the manifest so far. Throws OutputError.
  void write_progress(const std::vector<uint32_t>& dropped) {
    write(state(dropped, false, false, ""));
  }
  // Twice the manifest (old + new while it is replaced) and room for more frames.
  bool grow_reserve() { return reserve_.grow(2 * bytes_ + 65536); }
  // The last one, with the ending; frees the reserve first. Returns the
  // number of frames listed. Throws OutputError.
  uint64_t write_final(const std::vector<uint32_t>& dropped, const LoopEnd& end) {
    RecordingState s = state(dropped, true, end.complete, end.reason);
    reserve_.release();
    write(s);
    return s.frames.size();
  }

 private:
  RecordingState state(const std::vector<uint32_t>& dropped, bool final_write, bool complete,
                       const std::string& reason) const {
    RecordingState s;
    s.frames = writers_.written();
    s.dropped = dropped;
    s.measured_fps = writers_.measured_fps();
    s.preview_json = preview_ ? preview_->manifest_json() : "";
    s.final_write = final_write;
    s.complete = complete;
    s.end_reason = reason;
    return s;
  }
  void write(const RecordingState& s) {
    const std::string text = manifest_text(info_, s);
    write_atomic(folder_.manifest_path(), text);
    bytes_ = text.size();
  }

  const OutputFolder& folder_;
  const RecordingInfo& info_;
  const PngWriterPool& writers_;
  FrameObserver* preview_;
  ManifestReserve reserve_;
  size_t bytes_ = 0;
};

}  // namespace

RecordResult record(const RecordOptions& o, const std::atomic<bool>& stop, FrameObserver* preview) {
  using Clock = std::chrono::steady_clock;
  // --- the output folder, checked before the camera is opened ---------------------
  const OutputFolder folder(o.out);
  if (std::string why = folder.check_unused(); !why.empty()) return failed(kExitOutput, why);

  // --- the camera -----------------------------------------------------------------
  RecordResult res;
  std::unique_ptr<VideoCapture> cap = open_camera(o, res);
  if (!cap) return res;
  // Only now, so a missing camera leaves no empty folder behind.
  if (std::string why = folder.create(); !why.empty()) return failed(kExitOutput, why);
  const V4l2Format f = cap->format();
  if (o.color && (f.fourcc == V4L2_PIX_FMT_NV12 || f.fourcc == V4L2_PIX_FMT_YUV420))
    return failed(kExitCamera,
                  "--color: " + fourcc_name(f.fourcc) + " frames are recorded gray only");
  RecordingInfo info = describe(*cap, o, folder);
  // Rewritten at the end when the camera's timestamps disagree with the rate it reported.
  try {
    write_atomic(folder.info_path(), info_text(info, info.fps, ""));
  } catch (const std::exception& e) {
    return failed(kExitOutput, std::string("output folder not writable: ") + e.what());
  }

  // --- the writers and the manifest ------------------------------------------------
  const int channels = o.color ? 3 : 1;
  PngWriterPool writers(folder.frames_dir(), f.width, f.height, channels, o.queue, o.writers);
  if (preview) preview->start(f.width, f.height, channels);
  info.started = utc_now();
  ManifestWriter manifest(folder, info, writers, preview);
  if (!manifest.reserve_initial()) {
    cap.reset();
    writers.close();
    return failed(kExitOutput, "output disk full: not even 64 KiB free in " + o.out);
  }

  // --- the capture loop ------------------------------------------------------------
  const auto t0 = Clock::now();
  CaptureLoop loop(*cap, writers, o, preview);
  LoopEnd end = loop.run(stop, [&]() -> std::optional<LoopEnd> {
    try {
      manifest.write_progress(loop.dropped());
    } catch (const std::exception& e) {
      return LoopEnd{std::string("writing the manifest failed: ") + e.what(), kExitOutput, false,
                     fault_of(e)};
    }
    if (!manifest.grow_reserve())  // already says "disk full": no fault prefix
      return LoopEnd{"output disk full; No space left on device to keep recording safely",
                     kExitOutput};
    return std::nullopt;
  });
  cap.reset();  // stop streaming before the (possibly long) writer drain
  if (preview) preview->stop();
  writers.close();
  if (const WriteFailure wf = writers.failure(); wf && end.exit_code == kExitOk)
    end = LoopEnd{"writing frames failed: " + wf.message, kExitOutput, false, wf.fault};
  if (end.exit_code != kExitOk) end.complete = false;
  // The failed frame's temporary file is gone (write_png removes it), which
  // frees room for the final manifest even on a full disk.
  try {
    res.written = manifest.write_final(loop.dropped(), end);
  } catch (const std::exception& e) {
    res.written = writers.written_count();
    end.reason += std::string("; the final manifest could not be written (") + e.what() +
                  "), the one from the last second stands";
    if (end.exit_code == kExitOk) end.exit_code = kExitOutput;
    if (end.fault == OutputFault::kNone) end.fault = fault_of(e);
  }
  correct_info_rate(folder, info, writers.measured_fps());
  res.exit_code = end.exit_code;
  res.dropped = loop.dropped().size();
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  res.fps = res.seconds > 0 ? static_cast<double>(res.written) / res.seconds : 0;
  res.message = fault_prefix(end.fault) + end.reason;
  return res;
}

}  // namespace candela::record
