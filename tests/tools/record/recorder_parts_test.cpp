// candela-record's parts (tools/record): typed output errors (a full disk is
// "disk full" because of ENOSPC, not because of a message's wording), the
// folder checks, the manifest read back by a JSON reader, the PNG writer
// pool's frame order and failure handling, and the capture loop's endings.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/videodev2.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>

#include "capture_loop.h"
#include "core/image.h"
#include "manifest.h"
#include "output_folder.h"
#include "png_writer_pool.h"

namespace cr = candela::record;
namespace fs = std::filesystem;
using cr::OutputFault;

namespace {

// A fresh empty folder under the build tree's temp dir, removed afterwards.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string templ = (fs::temp_directory_path() / "candela-record-test-XXXXXX").string();
    path = mkdtemp(templ.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string read_text(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// Writes to /dev/full, which fails every write with ENOSPC like a full disk.
void write_to_dev_full(const std::string& as) {
  const int fd = open("/dev/full", O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(std::string("/dev/full: ") + std::strerror(errno));
  try {
    cr::write_all(fd, std::string(4096, 'x'), as);
  } catch (...) {
    close(fd);
    throw;
  }
  close(fd);
}

}  // namespace

TEST(RecordOutput, FullDiskIsReportedAsDiskFullFromEnospc) {
  try {
    write_to_dev_full("clip/manifest.json");
    FAIL() << "writing to /dev/full succeeded";
  } catch (const cr::OutputError& e) {
    EXPECT_EQ(e.error_number(), ENOSPC);
    EXPECT_EQ(e.fault(), OutputFault::kDiskFull);
    EXPECT_STREQ(cr::fault_prefix(e.fault()), "output disk full; ");
    EXPECT_EQ(std::string(e.what()), "clip/manifest.json: write failed: No space left on device");
  }
}

TEST(RecordOutput, FaultsComeFromErrnoNotText) {
  EXPECT_EQ(cr::fault_from_errno(0), OutputFault::kNone);
  EXPECT_EQ(cr::fault_from_errno(ENOSPC), OutputFault::kDiskFull);
  EXPECT_EQ(cr::fault_from_errno(EDQUOT), OutputFault::kDiskFull);
  EXPECT_EQ(cr::fault_from_errno(EROFS), OutputFault::kReadOnly);
  EXPECT_EQ(cr::fault_from_errno(EACCES), OutputFault::kOther);
  EXPECT_STREQ(cr::fault_prefix(OutputFault::kReadOnly), "output folder read-only; ");
  EXPECT_STREQ(cr::fault_prefix(OutputFault::kOther), "");
  // A message that merely mentions "No space" is no full disk.
  const cr::OutputError e("clip/No space/manifest.json: cannot write: Permission denied", EACCES);
  EXPECT_EQ(e.fault(), OutputFault::kOther);
  EXPECT_EQ(cr::fault_of(e), OutputFault::kOther);
  EXPECT_EQ(cr::fault_of(std::runtime_error("x: No space left on device")), OutputFault::kNone);
  EXPECT_EQ(cr::fault_of(cr::OutputError("x", EROFS)), OutputFault::kReadOnly);
}

TEST(RecordOutput, AtomicWriteLeavesTheWholeFileAndNoTemporary) {
  TempDir d;
  const std::string path = (d.path / "info.txt").string();
  cr::write_atomic(path, "first\n");
  cr::write_atomic(path, "second, longer\n");
  EXPECT_EQ(read_text(path), "second, longer\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  try {
    cr::write_atomic((d.path / "missing" / "info.txt").string(), "x");
    FAIL() << "writing into a missing folder succeeded";
  } catch (const cr::OutputError& e) {
    EXPECT_EQ(e.error_number(), ENOENT);
    EXPECT_NE(std::string(e.what()).find("missing/info.txt: cannot write: No such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(RecordOutput, FolderHoldingARecordingIsRefused) {
  TempDir d;
  const cr::OutputFolder folder((d.path / "clip").string());
  EXPECT_EQ(folder.check_unused(), "");
  EXPECT_EQ(folder.create(), "");
  EXPECT_TRUE(fs::is_directory(d.path / "clip" / "frames"));
  EXPECT_EQ(folder.name(), "clip");
  cr::write_atomic(folder.manifest_path(), "{}\n");
  EXPECT_EQ(folder.check_unused(),
            folder.path() + " already holds a recording (manifest.json); choose another folder");
}

TEST(RecordOutput, ReserveHoldsRoomUntilReleased) {
  TempDir d;
  const std::string path = (d.path / ".manifest-reserve").string();
  {
    cr::ManifestReserve reserve(path);
    ASSERT_TRUE(reserve.grow(65536));
    EXPECT_GE(fs::file_size(path), 65536u);
    EXPECT_FALSE(reserve.grow(size_t{1} << 62));  // more than any disk
    reserve.release();
    EXPECT_FALSE(fs::exists(path));
    ASSERT_TRUE(reserve.grow(4096));
  }
  EXPECT_FALSE(fs::exists(path)) << "the reserve outlived the recording";
}

namespace {

cr::RecordingInfo sample_info() {
  cr::RecordingInfo info;
  info.clip = "breeze \"two\"\n\xc3\xa9t\xc3\xa9";  // quotes, a newline, UTF-8
  info.backend = "v4l2";
  info.device = "/dev/video0";
  info.card = "vivid";
  info.driver = "vivid";
  info.started = "2026-12-02T12:00:00Z";
  info.width = 320;
  info.height = 180;
  info.pixel_format = "YUYV";
  info.fps = 29.97;
  info.requested_fps = 30;
  info.controls = {{9963776, "brightness", "128", "128"}, {1, "exposure", "null", "true"}};
  info.locked = {{"gain_automatic", "off"}, {"exposure_auto", "not offered"}};
  return info;
}

}  // namespace

TEST(RecordManifest, RoundTripsThroughAJsonReader) {
  cr::RecordingState s;
  s.frames = {{7, 1000}, {8, 34000}, {10, 100000}};
  s.dropped = {9};
  s.measured_fps = 29.987654;
  s.preview_json = R"({"mode":"headless","shown":3})";
  s.final_write = true;
  s.complete = true;
  s.end_reason = "frame count reached";
  const std::string text = cr::manifest_text(sample_info(), s);
  ASSERT_EQ(text.back(), '\n');
  const auto m = nlohmann::json::parse(text);
  EXPECT_EQ(m["format"], "candela-recording");
  EXPECT_EQ(m["version"], 1);
  EXPECT_EQ(m["clip"], sample_info().clip);
  EXPECT_EQ(m["backend"], "v4l2");
  EXPECT_EQ(m["device"], "/dev/video0");
  EXPECT_EQ(m["started"], "2026-12-02T12:00:00Z");
  EXPECT_EQ(m["width"], 320);
  EXPECT_EQ(m["height"], 180);
  EXPECT_EQ(m["pixel_format"], "YUYV");
  EXPECT_EQ(m["png"], "gray8");
  EXPECT_DOUBLE_EQ(m["fps"].get<double>(), 29.97);
  EXPECT_EQ(m["requested_fps"], 30);
  EXPECT_DOUBLE_EQ(m["measured_fps"].get<double>(), 29.988);  // three decimals
  EXPECT_EQ(m["locked"]["gain_automatic"], "off");
  EXPECT_EQ(m["locked"]["exposure_auto"], "not offered");
  EXPECT_EQ(m["controls"]["brightness"]["id"], 9963776);
  EXPECT_EQ(m["controls"]["brightness"]["value"], 128);
  EXPECT_TRUE(m["controls"]["exposure"]["value"].is_null());
  EXPECT_EQ(m["controls"]["exposure"]["default"], true);
  EXPECT_EQ(m["frame_count"], 3);
  ASSERT_EQ(m["frames"].size(), 3u);
  EXPECT_EQ(m["frames"][2]["file"], "frames/00000010.png");
  EXPECT_EQ(m["frames"][2]["sequence"], 10);
  EXPECT_EQ(m["frames"][2]["timestamp_ns"], 100000);
  EXPECT_EQ(m["dropped"]["count"], 1);
  EXPECT_EQ(m["dropped"]["sequences"], nlohmann::json::array({9}));
  EXPECT_EQ(m["preview"]["mode"], "headless");
  EXPECT_EQ(m["preview"]["shown"], 3);
  EXPECT_EQ(m["complete"], true);
  EXPECT_EQ(m["end_reason"], "frame count reached");
  // The keys in the documented order (format first, end_reason last).
  EXPECT_EQ(text.rfind("{\"format\":\"candela-recording\"", 0), 0u) << text.substr(0, 80);
  EXPECT_NE(text.find("\"end_reason\":\"frame count reached\"}\n"), std::string::npos) << text;
}

TEST(RecordManifest, WhileRecordingItIsNeitherCompleteNorEnded) {
  cr::RecordingState s;
  s.complete = true;  // only the final write may say so
  s.end_reason = "frame count reached";
  cr::RecordingInfo info = sample_info();
  info.fps = 30;
  info.color = true;
  const auto m = nlohmann::json::parse(cr::manifest_text(info, s));
  EXPECT_EQ(m["complete"], false);
  EXPECT_EQ(m["end_reason"], "recording");
  EXPECT_EQ(m["preview"], nlohmann::json({{"mode", "off"}}));
  EXPECT_EQ(m["frame_count"], 0);
  EXPECT_TRUE(m["frames"].is_array() && m["frames"].empty());
  EXPECT_EQ(m["png"], "rgb8");
  EXPECT_TRUE(m["fps"].is_number_integer()) << "30 fps is written as 30, as before";
}

// Frame 0 is written last (its writer waits for all the others), yet the pool
// lists the frames, and the manifest the files, in sequence order.
TEST(RecordWriterPool, KeepsFrameOrderWhateverOrderTheWritersFinish) {
  TempDir d;
  constexpr int kFrames = 8;
  std::mutex m;
  std::condition_variable cv;
  int others_done = 0;
  bool waited_too_long = false;
  auto write = [&](const std::string& path, const cr::FrameSlot& s) {
    if (s.sequence == 100) {
      std::unique_lock<std::mutex> lock(m);
      if (!cv.wait_for(lock, std::chrono::seconds(20), [&] { return others_done == kFrames - 1; }))
        waited_too_long = true;
    }
    candela::write_png(path, 4, 2, 1, s.pixels.data());
    if (s.sequence != 100) {
      std::lock_guard<std::mutex> lock(m);
      ++others_done;
      cv.notify_all();
    }
  };
  {
    cr::PngWriterPool pool(d.path.string(), 4, 2, 1, kFrames, 2, write);
    for (int i = 0; i < kFrames; ++i) {
      cr::FrameSlot* s = pool.acquire();
      ASSERT_NE(s, nullptr);
      ASSERT_EQ(s->pixels.size(), 8u);
      std::fill(s->pixels.begin(), s->pixels.end(), static_cast<uint8_t>(i * 10));
      s->sequence = 100 + i;
      s->timestamp_ns = 1000 * i;
      pool.submit(s);
    }
    pool.close();
    EXPECT_FALSE(waited_too_long) << "the other writer never wrote frames 101..107";
    const auto written = pool.written();
    ASSERT_EQ(written.size(), static_cast<size_t>(kFrames));
    for (int i = 0; i < kFrames; ++i) {
      EXPECT_EQ(written[i].sequence, 100u + i);
      EXPECT_EQ(written[i].timestamp_ns, 1000 * i);
      const auto img = candela::read_png((d.path / cr::PngWriterPool::file_name(100 + i)).string());
      EXPECT_EQ(img.pixels.at(0), i * 10) << "frame " << 100 + i << " holds another's pixels";
    }
    EXPECT_FALSE(pool.failure());
  }
}

TEST(RecordWriterPool, NeverWaitsForASlot) {
  TempDir d;
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 2, 1);
  cr::FrameSlot* a = pool.acquire();
  cr::FrameSlot* b = pool.acquire();
  ASSERT_TRUE(a && b);
  EXPECT_EQ(pool.acquire(), nullptr) << "all slots are busy: the frame is dropped, not waited for";
  pool.give_back(a);
  EXPECT_EQ(pool.acquire(), a);
}

// One writer; frame 3 hits a full disk (/dev/full): it is reported as "disk
// full" from ENOSPC and nothing after it is written.
TEST(RecordWriterPool, FullDiskStopsWritingAndIsTyped) {
  TempDir d;
  auto write = [](const std::string& path, const cr::FrameSlot& s) {
    if (s.sequence >= 3) write_to_dev_full(path);
    candela::write_png(path, 4, 2, 1, s.pixels.data());
  };
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 8, 1, write);
  for (uint32_t i = 0; i < 6; ++i) {
    cr::FrameSlot* s = pool.acquire();
    ASSERT_NE(s, nullptr);
    s->sequence = i;
    pool.submit(s);
  }
  pool.close();
  const cr::WriteFailure f = pool.failure();
  ASSERT_TRUE(f);
  EXPECT_EQ(f.fault, OutputFault::kDiskFull);
  EXPECT_EQ(f.message,
            (d.path / "00000003.png").string() + ": write failed: No space left on device");
  ASSERT_EQ(pool.written_count(), 3u);
  EXPECT_EQ(pool.written().back().sequence, 2u);
  EXPECT_FALSE(fs::exists(d.path / "00000004.png"));
}

namespace {

// A camera that plays a script of frames, then times out or goes away.
class ScriptedCamera : public candela::VideoCapture {
 public:
  std::vector<uint32_t> sequences;
  bool gone_at_end = true;
  size_t next_index = 0, released = 0;
  std::function<void(size_t)> before_frame;  // called with the frame's index

  ScriptedCamera() {
    format_.fourcc = V4L2_PIX_FMT_GREY;
    format_.width = 4;
    format_.height = 2;
    format_.bytesperline = 4;
    format_.sizeimage = 8;
    format_.fps = 30;
  }
  Result next(candela::VideoFrame& frame, int, int) override {
    if (next_index >= sequences.size()) {
      error_ = "unplugged";
      return gone_at_end ? Result::kGone : Result::kTimeout;
    }
    if (before_frame) before_frame(next_index);
    frame.data = pixels_;
    frame.bytes = sizeof pixels_;
    frame.sequence = sequences[next_index];
    frame.timestamp_ns = int64_t{33333333} * sequences[next_index];
    frame.index = static_cast<int>(next_index++);
    return Result::kFrame;
  }
  void release(const candela::VideoFrame&) override { ++released; }
  const candela::VideoFormat& format() const override { return format_; }
  const std::string& error() const override { return error_; }
  const char* backend() const override { return "v4l2"; }
  const std::string& device() const override { return name_; }
  const std::string& card() const override { return name_; }
  const std::string& driver() const override { return name_; }
  std::vector<candela::CaptureControl> controls() override { return {}; }
  std::vector<candela::LockedControl> lock_auto(const candela::AutoLockRequest&) override {
    return {};
  }

 private:
  candela::VideoFormat format_;
  std::string error_, name_ = "scripted";
  uint8_t pixels_[8] = {1, 2, 3, 4, 5, 6, 7, 8};
};

}  // namespace

TEST(RecordCaptureLoop, StopsAtTheFrameCountAndListsSequenceGaps) {
  TempDir d;
  ScriptedCamera cam;
  cam.sequences = {5, 6, 9, 10, 11, 12};
  cr::RecordOptions o;
  o.frames = 4;
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 8, 1);
  cr::CaptureLoop loop(cam, pool, o, nullptr);
  const std::atomic<bool> stop{false};
  const cr::LoopEnd end = loop.run(stop, {});
  pool.close();
  EXPECT_EQ(end.reason, "frame count reached");
  EXPECT_EQ(end.exit_code, cr::kExitOk);
  EXPECT_TRUE(end.complete);
  EXPECT_EQ(loop.dropped(), (std::vector<uint32_t>{7, 8}));
  EXPECT_EQ(cam.released, 4u) << "every frame taken is handed back to the camera";
  const auto written = pool.written();
  ASSERT_EQ(written.size(), 4u);
  EXPECT_EQ(written[2].sequence, 9u);
  const auto img = candela::read_png((d.path / "00000010.png").string());
  EXPECT_EQ(img.pixels, (std::vector<uint8_t>{1, 2, 3, 4, 5, 6, 7, 8}));
}

TEST(RecordCaptureLoop, ACameraThatGoesAwayEndsWithExit5) {
  TempDir d;
  ScriptedCamera cam;
  cam.sequences = {0, 1, 2};
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 8, 1);
  cr::RecordOptions o;
  cr::CaptureLoop loop(cam, pool, o, nullptr);
  const std::atomic<bool> stop{false};
  const cr::LoopEnd end = loop.run(stop, {});
  EXPECT_EQ(end.reason, "the camera went away: unplugged");
  EXPECT_EQ(end.exit_code, cr::kExitCameraLost);
  EXPECT_FALSE(end.complete);
  EXPECT_EQ(end.fault, OutputFault::kNone);
}

TEST(RecordCaptureLoop, AStopRequestEndsItCompleteBeforeAnyFrame) {
  TempDir d;
  ScriptedCamera cam;
  cam.sequences = {0, 1, 2};
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 8, 1);
  cr::RecordOptions o;
  cr::CaptureLoop loop(cam, pool, o, nullptr);
  const std::atomic<bool> stop{true};
  const cr::LoopEnd end = loop.run(stop, {});
  EXPECT_EQ(end.reason, "stopped by a signal");
  EXPECT_TRUE(end.complete);
  EXPECT_EQ(cam.next_index, 0u);
}

TEST(RecordCaptureLoop, AWriterOnAFullDiskEndsItAsDiskFull) {
  TempDir d;
  ScriptedCamera cam;
  cam.sequences = {0, 1, 2, 3};
  auto write = [](const std::string& path, const cr::FrameSlot&) { write_to_dev_full(path); };
  cr::PngWriterPool pool(d.path.string(), 4, 2, 1, 4, 1, write);
  // Before the second frame, let the writer finish the first (and fail).
  cam.before_frame = [&](size_t i) {
    if (i == 1) pool.close();
  };
  cr::RecordOptions o;
  cr::CaptureLoop loop(cam, pool, o, nullptr);
  const std::atomic<bool> stop{false};
  const cr::LoopEnd end = loop.run(stop, {});
  // Frame 0's failure is known by the time frame 1 is taken at the latest:
  // the loop asks for no frame after that.
  EXPECT_LE(cam.next_index, 2u) << "the loop goes on recording after a failed write";
  EXPECT_EQ(end.exit_code, cr::kExitOutput);
  EXPECT_EQ(end.fault, OutputFault::kDiskFull);
  EXPECT_EQ(end.reason.rfind("writing frames failed: ", 0), 0u) << end.reason;
  EXPECT_NE(end.reason.find("No space left on device"), std::string::npos) << end.reason;
}
