// The bounded file reader behind every file Candela opens (scene, model, PNG,
// noise/gust table): special files are refused at once with a message that
// says what they are, and sizes are checked before anything is read.
#include "core/file_read.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "model/noise_table.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class FileRead : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string t = (fs::temp_directory_path() / "candela-fileread-XXXXXX").string();
    ASSERT_NE(mkdtemp(t.data()), nullptr);
    dir_ = t;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string dir_;
};

// The message of the ConfigError `f` throws (empty, and a failure, if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEST_F(FileRead, AFifoIsRefusedWithoutWaitingForAWriter) {
  const std::string fifo = path("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto t0 = Clock::now();
  // Each reader the runtime uses: before, every one of them blocked in open() for ever.
  for (FileKind k : {FileKind::kScene, FileKind::kModel, FileKind::kImage, FileKind::kNoiseTable}) {
    const std::string e = error_of([&] { read_bounded_file(fifo, k); });
    EXPECT_EQ(e, fifo + ": not a regular file (a FIFO)");
  }
  EXPECT_TRUE(contains(error_of([&] { read_png(fifo); }), "not a regular file (a FIFO)"));
  EXPECT_TRUE(contains(error_of([&] { NoiseTable::load(fifo); }), "not a regular file (a FIFO)"));
  EXPECT_EQ(regular_file_problem(fifo), "not a regular file (a FIFO)");
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(5));
}

TEST_F(FileRead, DevicesDirectoriesAndLinkLoopsSayWhatTheyAre) {
  EXPECT_EQ(error_of([&] { read_bounded_file("/dev/zero", FileKind::kScene); }),
            "/dev/zero: not a regular file (a character device)");
  // Before: the noise reader said "got 0 bytes (truncated?)" for a directory.
  EXPECT_EQ(error_of([&] { NoiseTable::load(dir_); }), dir_ + ": not a regular file (a directory)");
  const std::string a = path("a"), b = path("b");
  fs::create_symlink(b, a);
  fs::create_symlink(a, b);
  EXPECT_EQ(error_of([&] { read_bounded_file(a, FileKind::kScene); }),
            a + ": cannot open: Too many levels of symbolic links");
  EXPECT_EQ(error_of([&] { read_bounded_file(path("none"), FileKind::kScene); }),
            path("none") + ": cannot open: No such file or directory");
  EXPECT_EQ(regular_file_problem(dir_), "not a regular file (a directory)");
}

TEST_F(FileRead, SizeIsCheckedBeforeReading) {
  // A sparse 1.2 GB file: refused from its size alone, nothing allocated or read.
  const std::string big = path("big.cmodel");
  const int fd = ::open(big.c_str(), O_CREAT | O_WRONLY, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(ftruncate(fd, static_cast<off_t>(1.2 * (1 << 30))), 0);
  ::close(fd);
  EXPECT_EQ(error_of([&] { BoundedFile::open(big, FileKind::kModel); }),
            big + ": 1.2 GB, larger than the 256 MB limit for a model");
  EXPECT_EQ(error_of([&] { read_bounded_file(big, FileKind::kScene); }),
            big + ": 1.2 GB, larger than the 1 MB limit for a scene");
  EXPECT_TRUE(contains(error_of([&] { read_png(big); }), "larger than the 64 MB limit for a PNG"));
  EXPECT_TRUE(contains(error_of([&] { NoiseTable::load(big); }),
                       "larger than the 256 KB limit for a noise table"));
}

TEST_F(FileRead, ReadsARegularFileWhole) {
  const std::string f = path("scene.toml");
  std::string text(300000, 'x');
  text[12345] = '\0';  // binary-safe
  std::ofstream(f, std::ios::binary) << text;
  EXPECT_EQ(read_bounded_file(f, FileKind::kScene), text);
  BoundedFile bf = BoundedFile::open(f, FileKind::kScene);
  std::string buf(bf.size(), '\0');
  bf.read_exactly(buf.data());
  EXPECT_EQ(buf, text);
}

TEST_F(FileRead, PngThatDeclaresAHugeImageIsRefused) {
  // A valid 1x1 PNG, then its IHDR says 100000 x 100000: a decompression bomb's header.
  Image one;
  one.width = one.height = 1;
  one.channels = 4;
  one.pixels = {1, 2, 3, 4};
  const std::string f = path("bomb.png");
  write_png(f, one);
  std::string bytes = read_bounded_file(f, FileKind::kImage);
  auto put32 = [&](size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>(v >> (24 - 8 * i));
  };
  put32(16, 100000);  // width, height: after the 8-byte signature, length and "IHDR"
  put32(20, 100000);
  // The IHDR CRC covers "IHDR" and its 13 bytes.
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 12; i < 29; ++i) {
    crc ^= static_cast<uint8_t>(bytes[i]);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  put32(29, ~crc);
  std::ofstream(f, std::ios::binary | std::ios::trunc) << bytes;
  const std::string e = error_of([&] { read_png(f, 4); });
  EXPECT_TRUE(contains(e, "100000x100000")) << e;
}

TEST(FormatBytes, ReadsLikeAPerson) {
  EXPECT_EQ(format_bytes(512), "512 bytes");
  EXPECT_EQ(format_bytes(1536), "1.5 KB");
  EXPECT_EQ(format_bytes(uint64_t{64} << 20), "64 MB");
  EXPECT_EQ(format_bytes(static_cast<uint64_t>(1.2 * (1 << 30))), "1.2 GB");
}

}  // namespace
}  // namespace candela
