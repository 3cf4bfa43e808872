// Headless output: PNG folders and .y4m video hold the frames that were drawn.
#include "display/frame_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
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

}  // namespace
}  // namespace candela
