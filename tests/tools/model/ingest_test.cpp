// Ingest: PNG folders and video files give the same aligned frames; the flame
// base lands where asked; several plumes are detected; the dataset round-trips.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/image.h"
#include "dataset.h"
#include "model_test_support.h"
#include "support/temp_dir.h"

namespace ct = candela::tools;

TEST(Ingest, VideoAndPngFoldersAgree) {
  const candela::test::TempDir tmp("candela_ingest_test_");
  const std::string& dir = tmp.path();
  const std::string video = dir + "/schodl.mkv";
  // A lossless video of the first 20 frames, made by the ffmpeg program.
  const std::string cmd = "ffmpeg -loglevel error -y -framerate 30 -i " +
                          ct::test::clip_dir("candle_schodl_singan") +
                          "/frames/%05d.png -frames:v 20 -c:v ffv1 " + video;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  ct::SourceClip from_png = ct::read_source(ct::test::clip_dir("candle_schodl_singan"), 20);
  ct::SourceClip from_video = ct::read_source(video);
  ASSERT_EQ(from_video.frames(), 20);
  ASSERT_EQ(from_png.frames(), 20);
  EXPECT_NEAR(from_video.fps, 30.0, 1e-6);
  EXPECT_EQ(from_video.width, from_png.width);
  double diff = 0;
  for (size_t i = 0; i < from_png.luma.size(); ++i)
    diff += std::abs(from_png.luma[i] - from_video.luma[i]);
  // Gray -> YUV -> RGB conversion costs at most a level or so.
  EXPECT_LT(diff / static_cast<double>(from_png.luma.size()), 0.004);
}

TEST(Ingest, FindsPngNamesAndFpsFromInfo) {
  ct::SourceClip c = ct::read_source(ct::test::clip_dir("candle_breeze_tfg_flameshaken"), 5);
  EXPECT_EQ(c.name, "candle_breeze_tfg_flameshaken");
  EXPECT_NEAR(c.fps, 60.0, 1e-9);
  EXPECT_EQ(c.frames(), 5);
}

static double linear(uint8_t encoded) {
  const double v = encoded / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

TEST(Ingest, AlignsTheFlameBaseAndRemovesTheBackground) {
  ct::IngestOptions o;
  o.width = 64;
  o.height = 104;
  for (const char* clip : {"candle_schodl_singan", "candle_breeze_tfg_flameshaken"}) {
    ct::Dataset d = ct::ingest({ct::read_source(ct::test::clip_dir(clip), 0, 4)}, o);
    std::vector<double> rows(d.height, 0.0);
    double corner = 0;
    for (int f = 0; f < d.frames(); ++f)
      for (int y = 0; y < d.height; ++y)
        for (int x = 0; x < d.width; ++x) {
          // The base is placed in linear light (the dataset stores sRGB-encoded gray).
          const double v = linear(d.frame(f)[y * d.width + x]);
          rows[y] += v;
          if (y < 8 && x < 8) corner += d.frame(f)[y * d.width + x];
        }
    const double peak = *std::max_element(rows.begin(), rows.end());
    int base = d.height - 1;
    while (base > 0 && rows[base] < 0.1 * peak) --base;
    EXPECT_NEAR(base, o.base_row * d.height, 3.0) << clip;
    EXPECT_LT(corner / (64.0 * d.frames()), 1.0) << clip << ": background left in the corner";
  }
}

TEST(Ingest, CountsDisjointPlumes) {
  std::vector<uint8_t> img(40 * 40, 0);
  auto blob = [&](int cx, int cy, int r) {
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x)
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) img[y * 40 + x] = 200;
  };
  blob(20, 25, 8);
  EXPECT_EQ(ct::count_plumes(img.data(), 40, 40, 0.25f, 0.03f), 1);
  blob(20, 6, 4);  // a detached tip above
  EXPECT_EQ(ct::count_plumes(img.data(), 40, 40, 0.25f, 0.03f), 2);
  img[0] = 200;  // a single hot pixel is not a plume
  EXPECT_EQ(ct::count_plumes(img.data(), 40, 40, 0.25f, 0.03f), 2);
}

TEST(Ingest, DatasetRoundTripsAndLabelsLand) {
  ct::IngestOptions o;
  o.width = 32;
  o.height = 48;
  o.labels.push_back(ct::parse_label("candle_schodl_singan:2-5:calm", "test"));
  ct::Dataset d = ct::ingest({ct::read_source(ct::test::clip_dir("candle_schodl_singan"), 10)}, o);
  const candela::test::TempDir tmp("candela_dataset_rt_");
  const std::string dir = tmp / "dataset";
  ct::save_dataset(d, dir);
  ct::Dataset back = ct::load_dataset(dir);
  EXPECT_EQ(back.pixels, d.pixels);
  ASSERT_EQ(back.clips.size(), 1u);
  ASSERT_EQ(back.clips[0].labels.size(), 1u);
  EXPECT_EQ(back.clips[0].labels[0].from, 2);
  EXPECT_EQ(back.clips[0].labels[0].label, "calm");
  EXPECT_THROW(ct::parse_label("nocolon", "test"), candela::ConfigError);
  // A frame file of the wrong size is refused, naming it.
  std::filesystem::resize_file(dir + "/frames.u8", 100);
  try {
    ct::load_dataset(dir);
    FAIL();
  } catch (const candela::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("frames.u8"), std::string::npos);
  }
}

// Found by dataset_manifest_fuzz: a key of the wrong JSON type escaped as
// nlohmann's type error ("type must be string, but is number"), naming no
// file; it is a ConfigError naming the manifest and the key, like the others.
TEST(Ingest, ManifestKeysOfTheWrongTypeNameTheFileAndKey) {
  const auto error_of = [](const std::string& text) -> std::string {
    try {
      ct::parse_manifest(text, "d/manifest.json");
    } catch (const candela::ConfigError& e) {
      return e.what();
    }
    return "parsed";
  };
  const std::string clip = R"("clips": [{"name": "c", "first": 0, "count": 1, "fps": 30)";
  const std::string head =
      R"("format": "candela-dataset", "version": 1, "width": 2, "height": 2, "frames": 1, )";
  EXPECT_EQ(error_of(R"({"format": 2})"), "d/manifest.json: format: expected \"candela-dataset\"");
  EXPECT_EQ(error_of(R"({"format": "candela-dataset", "version": "1"})"),
            "d/manifest.json: version: expected 1");
  EXPECT_EQ(error_of("{" + head + clip + R"(, "source": 7}]})"),
            "d/manifest.json: clips[0].source: expected a string");
  EXPECT_EQ(error_of("{" + head + clip + "}]}"), "parsed");
}

// Issue 34: a deeply nested manifest crashed `candela-tool build` (a
// recursive copy of the tree); it is refused while parsing, naming the file.
TEST(Ingest, DeeplyNestedManifestIsRefusedNamingTheFile) {
  const int depth = 100000;
  const std::string text = R"({"format": "candela-dataset", "version": 1, "x": )" +
                           std::string(depth, '[') + std::string(depth, ']') + "}";
  try {
    ct::parse_manifest(text, "d/manifest.json");
    FAIL() << "parsed";
  } catch (const candela::ConfigError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "d/manifest.json: expected JSON nested at most 32 arrays or objects deep, got deeper");
  }
}
