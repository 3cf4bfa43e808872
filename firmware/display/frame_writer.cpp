#include "display/frame_writer.h"

#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/image.h"
#include "core/log.h"

extern char** environ;

namespace candela {
namespace {

bool ends_with(const std::string& s, const char* suffix) {
  const size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

class PngFolderSink final : public FrameSink {
 public:
  PngFolderSink(std::string dir, int w, int h)
      : dir_(std::move(dir)), w_(w), h_(h), flipped_(static_cast<size_t>(w) * h * 4) {
    if (mkdir(dir_.c_str(), 0755) != 0 && errno != EEXIST)
      throw RuntimeError(dir_ + ": cannot create output folder: " + std::strerror(errno));
    struct stat st {};
    if (stat(dir_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw RuntimeError(dir_ + ": expected a folder (or a path ending in .y4m or .mp4)");
  }
  void write(const uint8_t* rgba) override {
    const size_t row = static_cast<size_t>(w_) * 4;
    for (int y = 0; y < h_; ++y) std::memcpy(&flipped_[row * y], rgba + row * (h_ - 1 - y), row);
    // Opaque, as a screen shows it: whatever a blend left in the alpha
    // channel (a dimmed frame's was 191) is no part of the picture.
    for (size_t i = 3; i < flipped_.size(); i += 4) flipped_[i] = 255;
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06d.png", index_++);
    write_png(dir_ + name, w_, h_, 4, flipped_.data());
  }

 private:
  std::string dir_;
  int w_, h_;
  int index_ = 0;
  std::vector<uint8_t> flipped_;
};

// YUV 4:4:4, BT.601 full range: exact enough to check pixels from, and
// played by ffmpeg/mpv/VLC.
class Y4mSink final : public FrameSink {
 public:
  Y4mSink(const std::string& path, int w, int h, int fps)
      : path_(path), w_(w), h_(h), planes_(static_cast<size_t>(w) * h * 3) {
    f_ = std::fopen(path.c_str(), "wb");
    if (!f_) throw RuntimeError(path + ": cannot write: " + std::strerror(errno));
    std::fprintf(f_, "YUV4MPEG2 W%d H%d F%d:1 Ip A1:1 C444 XCOLORRANGE=FULL\n", w, h, fps);
  }
  ~Y4mSink() override {
    if (f_) std::fclose(f_);
  }
  void write(const uint8_t* rgba) override {
    const size_t n = static_cast<size_t>(w_) * h_;
    for (int y = 0; y < h_; ++y) {
      const uint8_t* src = rgba + static_cast<size_t>(h_ - 1 - y) * w_ * 4;
      for (int x = 0; x < w_; ++x, src += 4) {
        const int r = src[0], g = src[1], b = src[2];
        const size_t i = static_cast<size_t>(y) * w_ + x;
        planes_[i] = static_cast<uint8_t>((77 * r + 150 * g + 29 * b + 128) >> 8);
        planes_[n + i] = static_cast<uint8_t>(((-43 * r - 85 * g + 128 * b + 128) >> 8) + 128);
        planes_[2 * n + i] = static_cast<uint8_t>(((128 * r - 107 * g - 21 * b + 128) >> 8) + 128);
      }
    }
    if (std::fputs("FRAME\n", f_) < 0 ||
        std::fwrite(planes_.data(), 1, planes_.size(), f_) != planes_.size())
      throw RuntimeError(path_ + ": write failed: " + std::strerror(errno));
  }
  void close() override {
    if (f_ && std::fclose(f_) != 0) {
      f_ = nullptr;
      throw RuntimeError(path_ + ": write failed: " + std::strerror(errno));
    }
    f_ = nullptr;
  }

 private:
  std::string path_;
  int w_, h_;
  std::vector<uint8_t> planes_;
  FILE* f_ = nullptr;
};

// Starts ffmpeg with `args` (stdin from stdin_fd unless -1; close_fd closed
// in the child unless -1). ffmpeg gets its own process group, so Ctrl-C or a
// SIGHUP to the terminal's group reaches candela only: candela stops, closes
// the pipe and ffmpeg finishes the file (writes the mp4's moov) instead of
// dying half-way. SIGPIPE back to default for ffmpeg (candela ignores it).
// Returns posix_spawnp's status (0: started).
int spawn_ffmpeg(std::vector<std::string>& args, int stdin_fd, int close_fd, pid_t* pid) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (stdin_fd >= 0) posix_spawn_file_actions_adddup2(&fa, stdin_fd, 0);
  if (close_fd >= 0) posix_spawn_file_actions_addclose(&fa, close_fd);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t def;
  sigemptyset(&def);
  sigaddset(&def, SIGPIPE);
  sigaddset(&def, SIGINT);
  sigaddset(&def, SIGTERM);
  sigaddset(&def, SIGHUP);
  posix_spawnattr_setsigdefault(&attr, &def);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
  const int rc = posix_spawnp(pid, "ffmpeg", &fa, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&fa);
  return rc;
}

// Waits for a child; true if it exited with status 0.
// A big-endian number of `n` bytes at `p`.
uint64_t big_endian(const unsigned char* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = v << 8 | p[i];
  return v;
}

}  // namespace

std::string video_file_problem(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return std::string("cannot be read (") + std::strerror(errno) + ")";
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  struct stat st {};
  if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) return "is not a regular file";
  const uint64_t size = static_cast<uint64_t>(st.st_size);
  unsigned char h[16];
  if (ends_with(path, ".mp4")) {
    // ISO BMFF: top-level boxes (32-bit size + type, size 1: a 64-bit size
    // follows) tiling the file, one of them the index (moov) that ffmpeg
    // writes last.
    bool index = false;
    uint64_t at = 0;
    while (at < size) {
      if (fseeko(f, static_cast<off_t>(at), SEEK_SET) != 0 || std::fread(h, 1, 8, f) != 8)
        return "ends inside a box header: the file was cut short";
      uint64_t box = big_endian(h, 4);
      if (box == 1) {
        if (std::fread(h + 8, 1, 8, f) != 8)
          return "ends inside a box header: the file was cut short";
        box = big_endian(h + 8, 8);
      } else if (box == 0) {
        box = size - at;  // to the end of the file
      }
      if (box < 8 || box > size - at) return "ends inside a box: the file was cut short";
      index = index || std::memcmp(h + 4, "moov", 4) == 0;
      at += box;
    }
    if (!index) return "has no index (moov): the writer stopped before finishing it";
    return "";
  }
  if (ends_with(path, ".mkv") || ends_with(path, ".webm")) {
    // Matroska: the EBML header, then the Segment, whose size ffmpeg writes
    // at the end (all ones until then: "unknown").
    auto vint = [&](uint64_t& value, int& length, bool keep_marker) {
      int c = std::fgetc(f);
      if (c <= 0) return false;
      length = 1;
      while (length <= 8 && !(c & (0x80 >> (length - 1)))) ++length;
      if (length > 8) return false;
      value = keep_marker ? static_cast<uint64_t>(c) : static_cast<uint64_t>(c) & (0xFFu >> length);
      for (int i = 1; i < length; ++i) {
        const int b = std::fgetc(f);
        if (b < 0) return false;
        value = value << 8 | static_cast<uint64_t>(b);
      }
      return true;
    };
    uint64_t id = 0, len = 0;
    int n = 0, m = 0;
    if (!vint(id, n, true) || id != 0x1A45DFA3 || !vint(len, m, false) ||
        fseeko(f, static_cast<off_t>(len), SEEK_CUR) != 0)
      return "has no Matroska header: the file was cut short";
    if (!vint(id, n, true) || id != 0x18538067 || !vint(len, m, false))
      return "has no Matroska segment: the file was cut short";
    if (len == (uint64_t{1} << (7 * m)) - 1)
      return "has a segment of unknown size: the writer stopped before finishing it";
    if (static_cast<uint64_t>(ftello(f)) + len > size)
      return "is shorter than its segment: the file was cut short";
    return "";
  }
  return "";
}

namespace {

bool wait_ok(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

class FfmpegSink final : public FrameSink {
 public:
  FfmpegSink(const std::string& path, int w, int h, int fps, const std::string& sound_path)
      : path_(path), sound_path_(sound_path), bytes_(static_cast<size_t>(w) * h * 4) {
    int fds[2];
    if (pipe(fds) != 0) throw RuntimeError(path + ": pipe failed");
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    const std::string rate = std::to_string(fps);
    std::vector<std::string> args = {"ffmpeg",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "rgba",
                                     "-s",
                                     size,
                                     "-r",
                                     rate,
                                     "-i",
                                     "-",
                                     "-vf",
                                     "vflip,pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-c:v"};
    // WebM holds VP8/VP9, not H.264 (a .webm always failed): VP9 at a
    // constant quality, tuned for speed.
    const std::vector<std::string> codec =
        ends_with(path, ".webm")
            ? std::vector<std::string>{"libvpx-vp9", "-crf",     "32",        "-b:v", "0",
                                       "-deadline",  "realtime", "-cpu-used", "8"}
            : std::vector<std::string>{"libx264", "-crf", "18"};
    args.insert(args.end(), codec.begin(), codec.end());
    args.push_back(path);
    const int rc = spawn_ffmpeg(args, fds[0], fds[1], &pid_);
    ::close(fds[0]);
    if (rc != 0) {
      ::close(fds[1]);
      throw RuntimeError(path + ": cannot run ffmpeg (" + std::strerror(rc) +
                         "); install it (apt-get install ffmpeg) or write a .y4m or a PNG folder");
    }
    fd_ = fds[1];
  }
  ~FfmpegSink() override {
    try {
      close();
    } catch (const std::exception& e) {
      LOG_ERROR("%s", e.what());
    }
  }
  void write(const uint8_t* rgba) override {
    size_t done = 0;
    while (done < bytes_) {
      const ssize_t n = ::write(fd_, rgba + done, bytes_ - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)  // EPIPE (SIGPIPE is ignored): ffmpeg exited, its message is above
        throw RuntimeError(path_ + ": ffmpeg stopped accepting frames (" +
                           std::strerror(n < 0 ? errno : EIO) + "); see its message above");
      done += static_cast<size_t>(n);
    }
  }
  void close() override {
    if (fd_ < 0) return;
    ::close(fd_);
    fd_ = -1;
    if (!wait_ok(pid_)) throw RuntimeError(path_ + ": ffmpeg failed to encode the video");
    // ffmpeg exits 0 when the disk fills as it writes the index (issue 34):
    // the file is checked, not its exit status trusted.
    if (const std::string why = video_file_problem(path_); !why.empty())
      throw RuntimeError(path_ + ": the video " + why + " (is the disk full?); it will not play" +
                         (sound_path_.empty() ? "" : "; its sound is " + sound_path_));
    mux_sound();
  }

 private:
  // The finished video + the run's .wav -> the video with sound (see open_frame_sink).
  void mux_sound() {
    struct stat st {};
    if (sound_path_.empty() || stat(sound_path_.c_str(), &st) != 0 || st.st_size <= 44) return;
    const size_t dot = path_.rfind('.');
    const std::string ext = path_.substr(dot);
    const std::string tmp = path_.substr(0, dot) + ".muxing" + ext;
    std::vector<std::string> args = {"ffmpeg",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-i",
                                     path_,
                                     "-i",
                                     sound_path_,
                                     "-map",
                                     "0:v:0",
                                     "-map",
                                     "1:a:0",
                                     "-c:v",
                                     "copy",
                                     "-c:a",
                                     ext == ".webm" ? "libopus" : "aac",
                                     "-b:a",
                                     "160k",
                                     tmp};
    pid_t pid = -1;
    const int rc = spawn_ffmpeg(args, -1, -1, &pid);
    if (rc != 0 || !wait_ok(pid) || !video_file_problem(tmp).empty() ||
        std::rename(tmp.c_str(), path_.c_str()) != 0) {
      unlink(tmp.c_str());
      throw RuntimeError(path_ +
                         ": ffmpeg could not add the sound; the video (silent) is there and "
                         "its sound is " +
                         sound_path_);
    }
    unlink(sound_path_.c_str());
  }

  std::string path_;
  std::string sound_path_;
  size_t bytes_;
  pid_t pid_ = -1;
  int fd_ = -1;
};

}  // namespace

std::string frame_sink_problem(const std::string& path) {
  const char* kExpected =
      "a folder (a name without an extension) or a .y4m, .mp4, .mkv or .webm file";
  if (path.empty()) return kExpected;
  for (const char* ext : {".y4m", ".mp4", ".mkv", ".webm"})
    if (ends_with(path, ext)) return "";
  const size_t slash = path.find_last_of('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.rfind('.');
  struct stat st {};
  if (dot == std::string::npos || dot == 0 || name == ".." || name.empty() ||
      (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)))
    return "";
  return kExpected;
}

std::unique_ptr<FrameSink> open_frame_sink(const std::string& path, int w, int h, int fps,
                                           const std::string& sound_path) {
  if (const std::string why = frame_sink_problem(path); !why.empty())
    throw RuntimeError(path + ": expected " + why);
  if (ends_with(path, ".y4m")) return std::make_unique<Y4mSink>(path, w, h, fps);
  if (ends_with(path, ".mp4") || ends_with(path, ".mkv") || ends_with(path, ".webm"))
    return std::make_unique<FfmpegSink>(path, w, h, fps, sound_path);
  return std::make_unique<PngFolderSink>(path, w, h);
}

AsyncFrameWriter::AsyncFrameWriter(std::unique_ptr<FrameSink> sink, int w, int h, int slots)
    : sink_(std::move(sink)) {
  slots_.resize(static_cast<size_t>(slots), std::vector<uint8_t>(static_cast<size_t>(w) * h * 4));
  thread_ = std::thread([this] { run(); });
}

AsyncFrameWriter::~AsyncFrameWriter() {
  try {
    finish();
  } catch (const std::exception& e) {
    LOG_ERROR("%s", e.what());
  }
}

uint8_t* AsyncFrameWriter::acquire() {
  std::unique_lock lock(mu_);
  cv_.wait(lock, [&] { return count_ < slots_.size() || error_; });
  if (error_) {
    reported_ = true;  // finish() need not throw it a second time
    std::rethrow_exception(error_);
  }
  return slots_[(head_ + count_) % slots_.size()].data();
}

void AsyncFrameWriter::submit() {
  {
    std::lock_guard lock(mu_);
    ++count_;
  }
  cv_.notify_all();
}

void AsyncFrameWriter::run() {
  for (;;) {
    uint8_t* frame = nullptr;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [&] { return count_ > 0 || stop_; });
      if (count_ == 0) break;
      frame = slots_[head_].data();
    }
    try {
      sink_->write(frame);
    } catch (...) {
      std::lock_guard lock(mu_);
      error_ = std::current_exception();
      count_ = 0;
      cv_.notify_all();
      return;
    }
    {
      std::lock_guard lock(mu_);
      head_ = (head_ + 1) % slots_.size();
      --count_;
    }
    cv_.notify_all();
  }
}

void AsyncFrameWriter::finish() {
  if (finished_) return;
  finished_ = true;
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (error_ && !reported_) std::rethrow_exception(error_);
  sink_->close();
}

}  // namespace candela
