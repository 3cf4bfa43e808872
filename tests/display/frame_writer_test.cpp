// Headless output: PNG folders and .y4m video hold the frames that were drawn.
#include "display/frame_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const char* name) {
  fs::path p = fs::temp_directory_path() /
               (std::string("candela-test-") + name + "-" + std::to_string(getpid()));
  fs::remove_all(p);
  return p;
}

// A w x h RGBA frame, bottom-up, whose pixel (x, y-from-top) encodes x, y and the frame index.
std::vector<uint8_t> pattern(int w, int h, int index) {
  std::vector<uint8_t> f(static_cast<size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = &f[(static_cast<size_t>(h - 1 - y) * w + x) * 4];
      p[0] = static_cast<uint8_t>(x * 10);
      p[1] = static_cast<uint8_t>(y * 10);
      p[2] = static_cast<uint8_t>(index * 40);
      p[3] = 255;
    }
  return f;
}

TEST(FrameWriter, PngFolderHoldsEveryFrameTopDown) {
  const fs::path dir = temp_dir("png");
  {
    AsyncFrameWriter w(open_frame_sink(dir.string(), 8, 6, 30), 8, 6);
    for (int i = 0; i < 5; ++i) {
      const auto f = pattern(8, 6, i);
      std::copy(f.begin(), f.end(), w.acquire());
      w.submit();
    }
    w.finish();
  }
  for (int i = 0; i < 5; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", i);
    const Image img = read_png((dir / name).string(), 4);
    ASSERT_EQ(img.width, 8);
    ASSERT_EQ(img.height, 6);
    EXPECT_EQ(img.at(3, 0, 0), 30);
    EXPECT_EQ(img.at(3, 0, 1), 0) << "row 0 is the top";
    EXPECT_EQ(img.at(3, 5, 1), 50);
    EXPECT_EQ(img.at(0, 0, 2), i * 40);
  }
  EXPECT_FALSE(fs::exists(dir / "frame_000005.png"));
  fs::remove_all(dir);
}

TEST(FrameWriter, Y4mHasHeaderAndFrames) {
  const fs::path dir = temp_dir("y4m");
  fs::create_directories(dir);
  const std::string path = (dir / "out.y4m").string();
  {
    AsyncFrameWriter w(open_frame_sink(path, 4, 2, 25), 4, 2);
    for (int i = 0; i < 3; ++i) {
      const auto f = pattern(4, 2, i);
      std::copy(f.begin(), f.end(), w.acquire());
      w.submit();
    }
    w.finish();
  }
  std::ifstream in(path, std::ios::binary);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("YUV4MPEG2 W4 H2 F25:1", 0), 0u) << header;
  int frames = 0;
  std::string tag;
  while (std::getline(in, tag)) {
    ASSERT_EQ(tag, "FRAME");
    std::vector<char> planes(4 * 2 * 3);
    in.read(planes.data(), static_cast<std::streamsize>(planes.size()));
    ASSERT_EQ(in.gcount(), static_cast<std::streamsize>(planes.size()));
    // Top-left pixel is (0, 0, 40*i): luma of pure blue 40*i.
    EXPECT_NEAR(static_cast<uint8_t>(planes[0]), (29 * 40 * frames + 128) >> 8, 1);
    ++frames;
  }
  EXPECT_EQ(frames, 3);
  fs::remove_all(dir);
}

TEST(FrameWriter, UnwritablePlaceIsAClearError) {
  try {
    open_frame_sink("/proc/candela-cannot-exist/frames", 4, 4, 30);
    FAIL();
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/candela-cannot-exist/frames"), std::string::npos)
        << e.what();
  }
}

// Issue 34: ffmpeg exits 0 when the disk fills as it writes the video's
// index, so the writer checks the file itself. A whole .mp4/.mkv passes;
// the same cut short, or with its index or segment size missing, does not.
std::vector<char> read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
void write_all(const fs::path& p, const std::vector<char>& b, size_t n) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(b.data(), static_cast<std::streamsize>(std::min(n, b.size())));
}

TEST(FrameWriter, VideoCheckFindsAVideoCutShort) {
  const fs::path dir = temp_dir("videocheck");
  fs::create_directories(dir);
  for (const char* ext : {".mp4", ".mkv"}) {
    SCOPED_TRACE(ext);
    const fs::path whole = dir / (std::string("whole") + ext);
    auto sink = open_frame_sink(whole.string(), 32, 24, 30);  // ffmpeg: install-deps.sh
    for (int i = 0; i < 30; ++i) sink->write(pattern(32, 24, i).data());
    sink->close();
    EXPECT_EQ(video_file_problem(whole.string()), "") << "the finished video";
    const std::vector<char> bytes = read_all(whole);
    ASSERT_GT(bytes.size(), 1000u);
    const fs::path cut = dir / (std::string("cut") + ext);
    for (size_t n : {size_t{0}, size_t{20}, bytes.size() / 2, bytes.size() - 9}) {
      write_all(cut, bytes, n);
      EXPECT_NE(video_file_problem(cut.string()), "") << "cut to " << n << " bytes";
    }
  }
  // The index (moov) renamed away: boxes tile the file but nothing indexes it.
  std::vector<char> mp4 = read_all(dir / "whole.mp4");
  const std::string moov = "moov";
  auto at = std::search(mp4.begin(), mp4.end(), moov.begin(), moov.end());
  ASSERT_NE(at, mp4.end());
  std::copy_n("free", 4, at);
  write_all(dir / "noindex.mp4", mp4, mp4.size());
  EXPECT_EQ(video_file_problem((dir / "noindex.mp4").string()),
            "has no index (moov): the writer stopped before finishing it");
  // The Matroska segment's size left unknown (8-byte vint of all ones), as a
  // writer that never reached its trailer leaves it.
  std::vector<char> mkv = read_all(dir / "whole.mkv");
  const char segment_id[] = {'\x18', '\x53', '\x80', '\x67'};
  auto seg = std::search(mkv.begin(), mkv.end(), segment_id, segment_id + 4);
  ASSERT_NE(seg, mkv.end());
  ASSERT_EQ(static_cast<unsigned char>(seg[4]), 0x01) << "ffmpeg writes an 8-byte size";
  std::fill_n(seg + 5, 7, '\xff');
  write_all(dir / "unknown.mkv", mkv, mkv.size());
  EXPECT_EQ(video_file_problem((dir / "unknown.mkv").string()),
            "has a segment of unknown size: the writer stopped before finishing it");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace candela
