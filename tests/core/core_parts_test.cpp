// core/'s small shared parts: the one WxH parser, atomic file writes, the
// SplitMix64 seed spreader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"
#include "core/json.h"
#include "core/json_parse.h"
#include "core/random.h"
#include "core/wxh.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

// The one bounded JSON parse: kMaxJsonDepth levels parse (and the tree can
// be re-serialised), one more is refused naming the file, as is text that is
// not JSON; nothing of the text is echoed.
TEST(JsonParse, NestingIsBoundedBeforeATreeIsBuilt) {
  const auto nested = [](int depth) {
    return std::string(depth, '[') + "1" + std::string(depth, ']');
  };
  const nlohmann::json ok = parse_json(nested(kMaxJsonDepth), "f.json");
  EXPECT_EQ(ok.dump(), nested(kMaxJsonDepth));
  try {
    parse_json(nested(kMaxJsonDepth + 1), "f.json", "header");
    FAIL() << "parsed";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "f.json: header: expected JSON nested at most 32 arrays or objects deep, got deeper");
  }
  std::string error;
  EXPECT_FALSE(try_parse_json(std::string(1 << 20, '['), &error));
  EXPECT_NE(error.find("nested at most 32"), std::string::npos) << error;
  EXPECT_FALSE(try_parse_json("{\"a\": \"secret", &error));
  EXPECT_NE(error.find("not valid JSON"), std::string::npos) << error;
  EXPECT_EQ(error.find("secret"), std::string::npos) << error;
  const auto ordered = try_parse_json<nlohmann::ordered_json>(R"({"b": 1, "a": [2]})", &error);
  ASSERT_TRUE(ordered);
  EXPECT_EQ(ordered->dump(), R"({"b":1,"a":[2]})");
}

TEST(Wxh, PlainDigitsWithinBounds) {
  const WxH lo{16, 16}, hi{16384, 16384};
  const auto s = parse_wxh("1280x720", lo, hi);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->width, 1280);
  EXPECT_EQ(s->height, 720);
  EXPECT_TRUE(parse_wxh("16x16384", lo, hi));
  for (const char* bad :
       {"", "x", "1280", "1280x", "x720", "12by5", "15x720", "1280x16385", "+1280x720", " 1280x720",
        "1280x720 ", "1280x720x1", "-1x720", "99999999999999999999x720", "1280X720"})
    EXPECT_FALSE(parse_wxh(bad, lo, hi)) << bad;
  EXPECT_FALSE(parse_wxh("200x149", {200, 150}, {8192, 8192}));  // each side its own bounds
  EXPECT_TRUE(parse_wxh("200x150", {200, 150}, {8192, 8192}));
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("candela-core-" + std::to_string(getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

TEST(AtomicFile, WholeFileOrNothingAndNoTemporary) {
  TempDir d;
  const std::string path = (d.path / "a.txt").string();
  write_atomic(path, "first\n");
  write_atomic(path, std::string_view("second\n"));
  EXPECT_EQ(read_text(path), "second\n");
  // A streaming writer that gives up leaves the old file and no .tmp.
  EXPECT_THROW(write_atomic(path,
                            [](std::FILE* f) {
                              std::fputs("half", f);
                              throw std::runtime_error("gave up");
                            }),
               std::runtime_error);
  EXPECT_EQ(read_text(path), "second\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  write_atomic(path, [](std::FILE* f) { std::fputs("streamed\n", f); });
  EXPECT_EQ(read_text(path), "streamed\n");
  try {
    write_atomic((d.path / "missing" / "b.txt").string(), "x");
    FAIL() << "wrote into a missing folder";
  } catch (const FileError& e) {
    EXPECT_EQ(e.error_number(), ENOENT);
    EXPECT_NE(std::string(e.what()).find("missing/b.txt: cannot write: No such file"),
              std::string::npos)
        << e.what();
  }
}

TEST(Random, SplitSeedIsSplitMix64) {
  // The first outputs of SplitMix64 from seed 0 (Vigna's reference code).
  EXPECT_EQ(split_seed(0, 0), 0xE220A8397B1DCDAFULL);
  EXPECT_EQ(split_seed(0, 1), 0x6E789E6AA1B965F4ULL);
  EXPECT_NE(split_seed(1, 0), split_seed(2, 0));
}

TEST(Json, NumbersRoundAsPrintfDoes) {
  EXPECT_EQ(json_decimals(0.5, 3), 0.5);
  EXPECT_EQ(json_decimals(0.12345678, 4), 0.1235);
  EXPECT_EQ(json_decimals(0.03125, 4), 0.0312);  // a tie: printf rounds half to even
  EXPECT_EQ(json_digits(1234567.0, 6), 1234570.0);
}

}  // namespace
}  // namespace candela
