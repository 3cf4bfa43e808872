#include "recorder.h"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "core/image.h"
#include "core/json.h"
#include "core/log.h"
#include "input/v4l2_capture.h"
#include "input/video_capture.h"

namespace candela::record {
namespace {

namespace fs = std::filesystem;

// Writes `text` to path atomically; throws RuntimeError naming the file and errno.
void write_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  const int fd = open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw RuntimeError(path + ": cannot write: " + std::strerror(errno));
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      close(fd);
      unlink(tmp.c_str());
      throw RuntimeError(path + ": write failed: " + std::strerror(err));
    }
    done += static_cast<size_t>(n);
  }
  if (close(fd) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    throw RuntimeError(path + ": write failed: " + std::strerror(err));
  }
  if (rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    unlink(tmp.c_str());
    throw RuntimeError(path + ": cannot rename into place: " + std::strerror(err));
  }
}

// Room kept for the final manifest: a full disk must not cost the list of
// frames already written. Grown with the manifest; freed just before the
// final write. False when the disk cannot give that much any more.
bool grow_reserve(const std::string& path, size_t bytes) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  const int r = posix_fallocate(fd, 0, static_cast<off_t>(bytes));
  close(fd);
  return r == 0;
}

std::string utc_now() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

struct Slot {
  std::vector<uint8_t> pixels;
  uint32_t sequence = 0;
  int64_t timestamp_ns = 0;
};

struct WrittenFrame {
  uint32_t sequence;
  int64_t timestamp_ns;
};

// Shared between the capture loop and the PNG writers.
struct Pipeline {
  std::mutex mutex;
  std::condition_variable work, space;
  std::deque<Slot*> pending;
  std::vector<Slot*> free_slots;
  std::map<uint32_t, WrittenFrame> written;  // by sequence
  std::string write_error;
  bool closing = false;
};

}  // namespace

RecordResult record(const RecordOptions& o, const std::atomic<bool>& stop, FrameObserver* preview) {
  RecordResult res;
  using Clock = std::chrono::steady_clock;
  // --- the output folder --------------------------------------------------------
  const fs::path out(o.out);
  const std::string frames_dir = (out / "frames").string();
  const std::string manifest_path = (out / "manifest.json").string();
  std::error_code exists_error;
  const bool exists = fs::exists(manifest_path, exists_error);
  if (exists_error) {  // e.g. a parent folder this user may not enter
    res.exit_code = kExitOutput;
    res.message = "cannot use " + o.out + ": " + exists_error.message();
    return res;
  }
  if (exists) {
    res.exit_code = kExitOutput;
    res.message = o.out + " already holds a recording (manifest.json); choose another folder";
    return res;
  }
  const std::string clip =
      !o.clip.empty() ? o.clip : fs::absolute(out).lexically_normal().filename().string();

  // --- the camera -----------------------------------------------------------------
  std::unique_ptr<VideoCapture> cap;
  try {
    CaptureSettings s;
    s.device = o.device;
    s.width = o.width;
    s.height = o.height;
    s.fps = o.fps;
    s.buffers = 8;
    if (!o.pixel_format.empty()) {
      s.fourcc = fourcc_from_name(o.pixel_format);
      if (!s.fourcc || !is_supported_format(s.fourcc)) {
        res.exit_code = kExitUsage;
        res.message = "--format " + o.pixel_format + ": expected GREY, YUYV, UYVY, RGB3 or BGR3";
        return res;
      }
    }
    cap = open_video_capture(o.backend, s);
  } catch (const std::exception& e) {
    res.exit_code = kExitCamera;
    res.message = e.what();
    return res;
  }
  // Only now, so a missing camera leaves no empty folder behind.
  std::error_code ec;
  fs::create_directories(frames_dir, ec);
  if (ec) {
    res.exit_code = kExitOutput;
    res.message = "cannot create " + frames_dir + ": " + ec.message();
    return res;
  }
  const V4l2Format f = cap->format();
  if (o.color && (f.fourcc == V4L2_PIX_FMT_NV12 || f.fourcc == V4L2_PIX_FMT_YUV420)) {
    res.exit_code = kExitCamera;
    res.message = "--color: " + fourcc_name(f.fourcc) + " frames are recorded gray only";
    return res;
  }
  AutoLockRequest lock_request;
  lock_request.keep_auto = o.keep_auto;
  lock_request.exposure = o.exposure;
  lock_request.gain = o.gain;
  lock_request.white_balance = o.white_balance;
  const std::vector<LockedControl> locked = cap->lock_auto(lock_request);
  const std::vector<CaptureControl> controls = cap->controls();
  const std::string card = cap->card(), driver = cap->driver(), device = cap->device();
  const std::string backend = cap->backend();
  const int channels = o.color ? 3 : 1;
  const double fps = f.fps > 0 ? f.fps : o.fps;

  // info.txt: what ingest reads the frame rate from ("NN fps"). Rewritten at
  // the end when the camera's timestamps disagree with the rate it reported.
  auto write_info = [&](double rate, const char* how) {
    char info[640];
    std::snprintf(info, sizeof info,
                  "%s: recorded by candela-record from %s (%s), %dx%d %s at %g fps%s; %s PNG "
                  "frames in frames/; details in manifest.json\n",
                  clip.c_str(), device.c_str(), card.c_str(), f.width, f.height,
                  fourcc_name(f.fourcc).c_str(), rate, how, o.color ? "RGB" : "gray");
    write_atomic((out / "info.txt").string(), info);
  };
  try {
    write_info(fps, "");
  } catch (const std::exception& e) {
    res.exit_code = kExitOutput;
    res.message = std::string("output folder not writable: ") + e.what();
    return res;
  }

  // --- writers ----------------------------------------------------------------------
  Pipeline p;
  std::vector<Slot> slots(static_cast<size_t>(std::max(2, o.queue)));
  for (auto& s : slots) {
    s.pixels.resize(static_cast<size_t>(f.width) * f.height * channels);
    p.free_slots.push_back(&s);
  }
  std::vector<std::thread> writers;
  for (int i = 0; i < std::max(1, o.writers); ++i)
    writers.emplace_back([&] {
      std::unique_lock<std::mutex> lock(p.mutex);
      for (;;) {
        p.work.wait(lock, [&] { return p.closing || !p.pending.empty(); });
        if (p.pending.empty()) return;
        Slot* s = p.pending.front();
        p.pending.pop_front();
        const bool skip = !p.write_error.empty();  // after a failure, write nothing more
        lock.unlock();
        char name[32];
        std::snprintf(name, sizeof name, "%08u.png", s->sequence);
        std::string error;
        if (!skip) {
          try {
            write_png(frames_dir + "/" + name, f.width, f.height, channels, s->pixels.data());
          } catch (const std::exception& e) {
            error = e.what();
            // libpng reports a failed fwrite as "Write Error" without errno: ask the filesystem.
            struct statvfs vfs {};
            if (statvfs(frames_dir.c_str(), &vfs) == 0 &&
                static_cast<double>(vfs.f_bavail) * vfs.f_bsize < 2.0 * s->pixels.size() + 65536)
              error = "No space left on device (" +
                      std::to_string(static_cast<unsigned long long>(vfs.f_bavail) * vfs.f_bsize /
                                     1024) +
                      " KiB free): " + error;
          }
        }
        lock.lock();
        if (!skip && error.empty()) p.written[s->sequence] = {s->sequence, s->timestamp_ns};
        if (!error.empty() && p.write_error.empty()) p.write_error = error;
        p.free_slots.push_back(s);
        p.space.notify_all();
      }
    });

  if (preview) preview->start(f.width, f.height, channels);

  std::vector<uint32_t> dropped;  // capture thread only
  std::string end_reason;
  bool complete = false;
  const std::string started = utc_now();
  const std::string reserve_path = (out / ".manifest-reserve").string();
  size_t manifest_bytes = 0;
  // The rate the camera really delivered, from its own timestamps (sequence
  // gaps count as frame periods): some drivers ignore the rate asked for and
  // report none (vimc runs at about 50 fps whatever is asked). 0 until 10 frames.
  auto measured_fps = [&]() -> double {
    std::lock_guard<std::mutex> lock(p.mutex);
    if (p.written.size() < 10) return 0;
    const auto& first = p.written.begin()->second;
    const auto& last = p.written.rbegin()->second;
    const double span = static_cast<double>(last.timestamp_ns - first.timestamp_ns) * 1e-9;
    const double periods = static_cast<double>(last.sequence - first.sequence);
    return span > 0 ? periods / span : 0;
  };
  auto manifest = [&](bool final_write) {
    std::string frames_json, controls_json, locked_json, dropped_json;
    uint64_t n = 0;
    {
      std::lock_guard<std::mutex> lock(p.mutex);
      for (const auto& [seq, w] : p.written) {
        char b[128];
        std::snprintf(
            b, sizeof b,
            "%s\n    {\"file\":\"frames/%08u.png\",\"sequence\":%u,\"timestamp_ns\":%lld}",
            n ? "," : "", seq, seq, static_cast<long long>(w.timestamp_ns));
        frames_json += b;
        ++n;
      }
    }
    const double measured = measured_fps();
    for (const auto& c : controls)
      controls_json += (controls_json.empty() ? "\n    " : ",\n    ") + json_quote(c.name) +
                       ":{\"id\":" + std::to_string(c.id) + ",\"value\":" + c.value_json +
                       ",\"default\":" + c.default_json + "}";
    for (const auto& l : locked)
      locked_json +=
          (locked_json.empty() ? "" : ",") + json_quote(l.name) + ":" + json_quote(l.outcome);
    for (uint32_t d : dropped)
      dropped_json += (dropped_json.empty() ? "" : ",") + std::to_string(d);
    char head[2048];
    std::snprintf(head, sizeof head,
                  "{\n  \"format\": \"candela-recording\",\n  \"version\": 1,\n  \"clip\": %s,\n"
                  "  \"backend\": \"%s\",\n  \"device\": %s,\n  \"card\": %s,\n  \"driver\": %s,\n"
                  "  \"started\": \"%s\",\n"
                  "  \"width\": %d,\n  \"height\": %d,\n  \"pixel_format\": \"%s\",\n"
                  "  \"png\": \"%s\",\n  \"fps\": %g,\n  \"requested_fps\": %d,\n"
                  "  \"measured_fps\": %.3f,\n",
                  json_quote(clip).c_str(), backend.c_str(), json_quote(device).c_str(),
                  json_quote(card).c_str(), json_quote(driver).c_str(), started.c_str(), f.width,
                  f.height, fourcc_name(f.fourcc).c_str(), o.color ? "rgb8" : "gray8", fps, o.fps,
                  measured);
    const std::string text =
        std::string(head) + "  \"locked\": {" + locked_json + "},\n  \"controls\": {" +
        controls_json + "\n  },\n  \"frame_count\": " + std::to_string(n) + ",\n  \"frames\": [" +
        frames_json + "\n  ],\n  \"dropped\": {\"count\": " + std::to_string(dropped.size()) +
        ", \"sequences\": [" + dropped_json +
        "]},\n  \"preview\": " + (preview ? preview->manifest_json() : "{\"mode\":\"off\"}") +
        ",\n  \"complete\": " + (final_write && complete ? "true" : "false") +
        ",\n  \"end_reason\": " + json_quote(final_write ? end_reason : "recording") + "\n}\n";
    if (final_write) unlink(reserve_path.c_str());
    write_atomic(manifest_path, text);
    manifest_bytes = text.size();
    return n;
  };

  // --- capture loop -----------------------------------------------------------------
  if (!grow_reserve(reserve_path, 65536)) {
    res.exit_code = kExitOutput;
    res.message = "output disk full: not even 64 KiB free in " + o.out;
    cap.reset();
    {
      std::lock_guard<std::mutex> lock(p.mutex);
      p.closing = true;
      p.work.notify_all();
    }
    for (auto& t : writers) t.join();
    return res;
  }
  const auto t0 = Clock::now();
  auto last_manifest = t0;
  bool have_seq = false;
  uint32_t next_seq = 0;
  uint64_t queued = 0;
  int silent = 0;
  for (;;) {
    if (stop.load()) {
      end_reason =
          preview && preview->quit_requested() ? "stopped from the preview" : "stopped by a signal";
      complete = true;
      break;
    }
    {
      std::lock_guard<std::mutex> lock(p.mutex);
      if (!p.write_error.empty()) {
        end_reason = "writing frames failed: " + p.write_error;
        res.exit_code = kExitOutput;
        break;
      }
    }
    if (o.frames && queued >= o.frames) {
      end_reason = "frame count reached";
      complete = true;
      break;
    }
    if (o.seconds > 0 && std::chrono::duration<double>(Clock::now() - t0).count() >= o.seconds) {
      end_reason = "duration reached";
      complete = true;
      break;
    }
    VideoFrame frame;
    const auto r = cap->next(frame, 2000);
    if (r == VideoCapture::Result::kGone) {
      end_reason = "the camera went away: " + cap->error();
      res.exit_code = kExitCameraLost;
      break;
    }
    if (r == VideoCapture::Result::kTimeout) {
      if (++silent >= 3) {  // 6 s without a frame: the camera is as good as gone
        end_reason = "the camera delivered no frame for 6 s";
        res.exit_code = kExitCameraLost;
        break;
      }
      continue;
    }
    silent = 0;
    // Sequence gaps: the driver dropped frames before we saw them.
    if (have_seq && frame.sequence > next_seq)
      for (uint32_t s = next_seq; s < frame.sequence && dropped.size() < 100000; ++s)
        dropped.push_back(s);
    have_seq = true;
    next_seq = frame.sequence + 1;
    Slot* slot = nullptr;
    {
      std::lock_guard<std::mutex> lock(p.mutex);
      if (!p.free_slots.empty()) {
        slot = p.free_slots.back();
        p.free_slots.pop_back();
      }
    }
    const bool ok = slot && frame.bytes &&
                    (o.color ? frame_to_rgb(f, frame.data, frame.bytes, slot->pixels.data())
                             : frame_to_gray(f, frame.data, frame.bytes, slot->pixels.data()));
    cap->release(frame);
    if (!ok) {
      dropped.push_back(frame.sequence);  // writers behind, or a damaged frame
      if (slot) {
        std::lock_guard<std::mutex> lock(p.mutex);
        p.free_slots.push_back(slot);
      }
    } else {
      slot->sequence = frame.sequence;
      slot->timestamp_ns = frame.timestamp_ns;
      if (preview) preview->push(slot->pixels.data(), frame.sequence);
      std::lock_guard<std::mutex> lock(p.mutex);
      p.pending.push_back(slot);
      p.work.notify_one();
      ++queued;
    }
    if (Clock::now() - last_manifest > std::chrono::seconds(1)) {
      last_manifest = Clock::now();
      try {
        manifest(false);
        // Twice the manifest (old + new while it is replaced) and room for more frames.
        if (!grow_reserve(reserve_path, 2 * manifest_bytes + 65536)) {
          end_reason = "output disk full; No space left on device to keep recording safely";
          res.exit_code = kExitOutput;
          break;
        }
      } catch (const std::exception& e) {
        end_reason = std::string("writing the manifest failed: ") + e.what();
        res.exit_code = kExitOutput;
        break;
      }
    }
  }
  cap.reset();  // stop streaming before the (possibly long) writer drain
  if (preview) preview->stop();
  {
    std::lock_guard<std::mutex> lock(p.mutex);
    p.closing = true;
    p.work.notify_all();
  }
  for (auto& t : writers) t.join();
  if (!p.write_error.empty() && res.exit_code == 0) {
    end_reason = "writing frames failed: " + p.write_error;
    res.exit_code = kExitOutput;
    complete = false;
  }
  if (res.exit_code != 0) complete = false;
  // The failed frame's temporary file is gone (write_png removes it), which
  // frees room for the final manifest even on a full disk.
  try {
    res.written = manifest(true);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(p.mutex);
    res.written = p.written.size();
    end_reason += std::string("; the final manifest could not be written (") + e.what() +
                  "), the one from the last second stands";
    if (res.exit_code == 0) res.exit_code = kExitOutput;
  }
  unlink(reserve_path.c_str());
  if (const double measured = measured_fps();
      measured > 0 && std::abs(measured - fps) > 0.05 * fps) {
    char how[96];
    std::snprintf(how, sizeof how, " (measured from the camera's timestamps; it reported %g)", fps);
    try {
      write_info(std::round(measured * 100) / 100, how);
      LOG_WARN("%s: the camera delivered %.2f fps, not the %g it reported; info.txt says %.2f",
               o.out.c_str(), measured, fps, measured);
    } catch (const std::exception& e) {
      LOG_WARN("%s: info.txt keeps %g fps (%s)", o.out.c_str(), fps, e.what());
    }
  }
  res.dropped = dropped.size();
  res.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  res.fps = res.seconds > 0 ? static_cast<double>(res.written) / res.seconds : 0;
  if (end_reason.find("failed") != std::string::npos &&
      (end_reason.find("No space") != std::string::npos ||
       end_reason.find("Read-only") != std::string::npos))
    end_reason = (end_reason.find("No space") != std::string::npos ? "output disk full; "
                                                                   : "output folder read-only; ") +
                 end_reason;
  res.message = end_reason;
  return res;
}

}  // namespace candela::record
