// The model file round-trips bit-exactly and every kind of damage is refused
// with its own error that names the file and the problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "model/flame_model.h"
#include "model/model_writer.h"

namespace cm = candela::model;
using Kind = cm::ModelError::Kind;

namespace {

// A small but complete model: 3 components over 8x6 pixels, 5 frames, one clip.
cm::ModelWriter small_model(int components = 3) {
  const int w = 8, h = 6, f = 5;
  const size_t px = static_cast<size_t>(w) * h;
  std::vector<float> mean(px), eig(components * px), weights(f * components), var(components);
  for (size_t p = 0; p < px; ++p) mean[p] = 10.0f + 3.0f * static_cast<float>(p);
  for (int k = 0; k < components; ++k)
    for (size_t p = 0; p < px; ++p)
      eig[k * px + p] = std::sin(0.3f * static_cast<float>(p * (k + 1)));
  for (int i = 0; i < f * components; ++i) weights[i] = 0.5f * static_cast<float>(i) - 2.0f;
  for (int k = 0; k < components; ++k) var[k] = 10.0f / static_cast<float>(k + 1);
  std::vector<int32_t> offsets{0, 1, 3, 4, 5, 6}, succ{1, 2, 4, 3, 4, 0};
  std::vector<float> cost{1, 1, 2, 1, 1, 3};
  cm::ModelWriter mw;
  mw.set_info(
      {{"kind", "eigenfires"},
       {"width", w},
       {"height", h},
       {"components", components},
       {"frames", f},
       {"total_variance", 20.0},
       {"graph", {{"theta_min", 0.5}}},
       {"clips",
        {{{"name", "c"},
          {"source", "x"},
          {"first", 0},
          {"count", f},
          {"fps", 30.0},
          {"labels", {{{"from", 1}, {"to", 3}, {"label", "calm"}}}}}}},
       {"colour",
        {{"hue", 30.0}, {"saturation", 0.8}, {"glow_radius", 0.05}, {"glow_strength", 0.5}}},
       {"provenance", {{"tool", "test"}}}});
  cm::add_quantised(mw, "mean", cm::quantise_images(mean.data(), 1, px, cm::DType::kU16), 1, w, h);
  cm::add_quantised(mw, "eigen", cm::quantise_images(eig.data(), 3, px, cm::DType::kU8), 3, w, h);
  mw.add_f32("weights", {f, components}, weights);
  mw.add_f32("variance", {components}, var);
  mw.add_i32("graph.offsets", {f + 1}, offsets);
  mw.add_i32("graph.successors", {6}, succ);
  mw.add_f32("graph.cost", {6}, cost);
  return mw;
}

// ctest runs each test of this file as its own process, in parallel: every
// process gets its own files (a shared name let one test truncate a file
// another was reading).
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("candela_model_test_" + std::to_string(getpid()) + "_" + name))
      .string();
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& b) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

// Loads and returns the error kind; fails the test if it loads.
Kind error_of(const std::vector<uint8_t>& bytes, std::string* message = nullptr) {
  const std::string path = temp_path("damaged.cmodel");
  write_bytes(path, bytes);
  try {
    cm::FlameModel::load(path);
  } catch (const cm::ModelError& e) {
    if (message) *message = e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.kind();
  }
  ADD_FAILURE() << "damaged file loaded";
  return Kind::kIo;
}

}  // namespace

TEST(ModelFile, RoundTripsBitExactly) {
  const std::vector<uint8_t> bytes = small_model().bytes();
  const std::string path = temp_path("rt.cmodel");
  write_bytes(path, bytes);
  cm::FlameModel m = cm::FlameModel::load(path);
  EXPECT_EQ(m.width(), 8);
  EXPECT_EQ(m.height(), 6);
  EXPECT_EQ(m.components(), 3);
  EXPECT_EQ(m.frames(), 5);
  ASSERT_EQ(m.clips.size(), 1u);
  EXPECT_EQ(m.clips[0].labels.at(0).label, "calm");
  EXPECT_EQ(m.weights[7], 0.5f * 7 - 2.0f);
  EXPECT_EQ(m.graph.successors_of(1).size(), 2u);
  // Every tensor aligned for mapping.
  for (const auto& t : m.file().tensors())
    EXPECT_EQ(reinterpret_cast<uintptr_t>(t.data) % cm::kAlignment, 0u) << t.name;
  // Quantised mean is within half a step of the original.
  EXPECT_NEAR(m.mean.value(0, 5), 25.0f, m.mean.scale[0] * 0.5f + 1e-4f);
  // Re-writing what was read gives the identical bytes.
  cm::ModelWriter again;
  again.set_info(m.file().info());
  for (const auto& t : m.file().tensors()) again.add(t.name, t.dtype, t.shape, {t.data, t.bytes});
  EXPECT_EQ(again.bytes(), bytes);
  cm::ModelFile back = cm::ModelFile::from_bytes(again.bytes(), "again");
  for (const auto& t : m.file().tensors()) {
    const cm::Tensor* u = back.find(t.name);
    ASSERT_NE(u, nullptr) << t.name;
    EXPECT_EQ(u->shape, t.shape);
    EXPECT_EQ(0, std::memcmp(u->data, t.data, t.bytes)) << t.name;
  }
  // And writing the same model twice is byte-identical.
  EXPECT_EQ(small_model().bytes(), bytes);
}

// A kiosk owner copies a new model over the one candela is showing: the
// running display keeps the model it loaded (a mapped file would die of
// SIGBUS on the truncated pages) and the file is only read again on reload.
TEST(ModelFile, OverwritingTheFileLeavesALoadedModelIntact) {
  const std::vector<uint8_t> bytes = small_model().bytes();
  const std::string path = temp_path("live.cmodel");
  write_bytes(path, bytes);
  cm::FlameModel m = cm::FlameModel::load(path);
  const std::vector<uint8_t> nothing(16, 0xee);
  write_bytes(path, nothing);  // truncated to 16 bytes, in place
  ASSERT_EQ(std::filesystem::file_size(path), 16u);
  EXPECT_NEAR(m.mean.value(0, 5), 25.0f, m.mean.scale[0] * 0.5f + 1e-4f);
  const cm::ModelFile original = cm::ModelFile::from_bytes(bytes, "original");
  for (const auto& t : m.file().tensors()) {  // every byte still readable and as written
    const cm::Tensor* u = original.find(t.name);
    ASSERT_NE(u, nullptr) << t.name;
    ASSERT_EQ(u->bytes, t.bytes) << t.name;
    EXPECT_EQ(0, std::memcmp(u->data, t.data, t.bytes)) << t.name;
  }
  std::remove(path.c_str());
}

TEST(ModelFile, TruncationIsReported) {
  const std::vector<uint8_t> full = small_model().bytes();
  for (size_t keep : {size_t{0}, size_t{5}, size_t{40}, full.size() / 2, full.size() - 1}) {
    std::string msg;
    std::vector<uint8_t> cut(full.begin(), full.begin() + static_cast<ptrdiff_t>(keep));
    EXPECT_EQ(error_of(cut, &msg), Kind::kTruncated) << keep << ": " << msg;
  }
}

TEST(ModelFile, CorruptionIsCaughtByTheChecksum) {
  std::vector<uint8_t> b = small_model().bytes();
  b[b.size() - 100] ^= 0x10;  // a bit in the tensor data
  std::string msg;
  EXPECT_EQ(error_of(b, &msg), Kind::kChecksum);
  EXPECT_NE(msg.find("checksum"), std::string::npos) << msg;
  // A changed value in the header (the hue) is caught too.
  std::vector<uint8_t> h = small_model().bytes();
  std::string text(h.begin() + 8, h.begin() + 400);
  size_t at = text.find("\"hue\":30");
  ASSERT_NE(at, std::string::npos);
  h[8 + at + 7] = '4';
  EXPECT_EQ(error_of(h), Kind::kChecksum);
}

TEST(ModelFile, WrongVersionIsReported) {
  std::string msg;
  EXPECT_EQ(error_of(small_model().bytes(2), &msg), Kind::kVersion);
  EXPECT_NE(msg.find("version 2"), std::string::npos) << msg;
}

TEST(ModelFile, NotAModelIsAHeaderError) {
  std::vector<uint8_t> b(64, ' ');
  b[0] = 56;  // header length 56, then spaces: not JSON
  EXPECT_EQ(error_of(b), Kind::kHeader);
  std::vector<uint8_t> png{0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 0};
  EXPECT_EQ(error_of(png), Kind::kHeader);
}

TEST(ModelFile, InconsistentContentsAreReported) {
  // Correct checksum, but the info claims 4 components while the tensors hold 3.
  cm::ModelWriter mw = small_model();
  cm::ModelFile ok = cm::ModelFile::from_bytes(mw.bytes(), "ok");
  nlohmann::json info = ok.info();
  info["components"] = 4;
  mw.set_info(info);
  std::string msg;
  EXPECT_EQ(error_of(mw.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("eigen"), std::string::npos) << msg;
  // A successor outside the frames.
  cm::ModelWriter bad = small_model();
  std::vector<int32_t> succ{1, 2, 9, 3, 4, 0};
  bad.add_i32("graph.successors", {6}, succ);  // replaces the good one
  EXPECT_EQ(error_of(bad.bytes(), &msg), Kind::kInconsistent);
}

TEST(ModelFile, MissingFileIsAnIoError) {
  try {
    cm::FlameModel::load("/nonexistent/dir/x.cmodel");
    FAIL();
  } catch (const cm::ModelError& e) {
    EXPECT_EQ(e.kind(), Kind::kIo);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/x.cmodel"), std::string::npos);
  }
}

TEST(FlameModel, ReconstructsFromQuantisedImages) {
  cm::ModelFile f = cm::ModelFile::from_bytes(small_model().bytes(), "m");
  cm::FlameModel m = cm::FlameModel::from(f);
  std::vector<float> out(m.mean.pixels());
  std::vector<float> w{2.0f, -1.0f, 0.5f};
  m.reconstruct(w, out);
  for (size_t p = 0; p < out.size(); ++p) {
    float want = 10.0f + 3.0f * static_cast<float>(p);
    for (int k = 0; k < 3; ++k) want += w[k] * std::sin(0.3f * static_cast<float>(p * (k + 1)));
    // 8-bit eigen-images over [-1,1]: half a step is 1/255 per unit weight.
    EXPECT_NEAR(out[p], want, 0.1f) << p;
  }
}
