// The model file round-trips bit-exactly and every kind of damage is refused
// with its own error that names the file and the problem.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string_view>

#include "model/flame_model.h"
#include "model/model_writer.h"
#include "support/temp_dir.h"

namespace cm = candela::model;
using Kind = cm::ModelError::Kind;

namespace {

// A small but complete model: 3 components over 8x6 pixels, 5 frames, one clip
// (or as many components, as large and as finely quantised as asked).
cm::ModelWriter small_model(int components = 3, int w = 8, int h = 6,
                            cm::DType eigen_type = cm::DType::kU8) {
  const int f = 5;
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
  cm::add_quantised(mw, "eigen", cm::quantise_images(eig.data(), components, px, eigen_type),
                    components, w, h);
  mw.add_f32("weights", {f, components}, weights);
  mw.add_f32("variance", {components}, var);
  mw.add_i32("graph.offsets", {f + 1}, offsets);
  mw.add_i32("graph.successors", {6}, succ);
  mw.add_f32("graph.cost", {6}, cost);
  return mw;
}

// Adds a Learning Flames part: an ARP of `order` over np + nw + 1 + ne parameters.
cm::ModelWriter with_flames(cm::ModelWriter mw, int order, int np = 4, int nw = 4, int ne = 2,
                            int frames = 6) {
  const int w = 4, h = 5, d = np + nw + 1 + ne;
  nlohmann::json info = cm::ModelFile::from_bytes(mw.bytes(), "m").info();
  info["learning_flames"] = {{"np", np},         {"nw", nw},      {"ne", ne},
                             {"order", order},   {"width", w},    {"height", h},
                             {"frames", frames}, {"base_y", 4.0}, {"span", 2.5}};
  mw.set_info(info);
  const size_t px = static_cast<size_t>(w) * h;
  std::vector<float> mean(px, 30.0f), eig(static_cast<size_t>(ne) * px, 0.5f);
  cm::add_quantised(mw, "lf.mean", cm::quantise_images(mean.data(), 1, px, cm::DType::kU8), 1, w,
                    h);
  cm::add_quantised(mw, "lf.eigen", cm::quantise_images(eig.data(), ne, px, cm::DType::kU8), ne, w,
                    h);
  std::vector<float> params(static_cast<size_t>(frames) * d, 1.0f),
      a(static_cast<size_t>(order) * d * d, 0.0f), dd(d, 0.1f), b(static_cast<size_t>(d) * d, 0.0f);
  // Training states that differ and noise that drives the process (a still
  // one is refused).
  for (size_t i = 0; i < params.size(); ++i) params[i] += static_cast<float>(i % 3);
  for (int i = 0; i < d; ++i) b[static_cast<size_t>(i) * d + i] = 0.1f;
  mw.add_f32("lf.params", {frames, d}, params);
  mw.add_f32("arp.A", {order, d, d}, a);
  mw.add_f32("arp.d", {d}, dd);
  mw.add_f32("arp.B", {d, d}, b);
  return mw;
}

// The same model with its info edited.
cm::ModelWriter edited(cm::ModelWriter mw, const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json info = cm::ModelFile::from_bytes(mw.bytes(), "m").info();
  edit(info);
  mw.set_info(info);
  return mw;
}

// ctest runs each test of this file as its own process, in parallel: every
// process gets its own folder (a shared name let one test truncate a file
// another was reading), removed when the process ends.
std::string temp_path(const std::string& name) {
  static const candela::test::TempDir dir("candela_model_test_");
  return dir / name;
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

// A model built into the binary is read where it lies (no copy of its
// megabytes), with the same checks as a file.
TEST(ModelFile, StaticBytesAreReadInPlace) {
  const std::vector<uint8_t> bytes = small_model().bytes();
  alignas(cm::kAlignment) static uint8_t held[1 << 16];
  ASSERT_LE(bytes.size(), sizeof held);
  std::memcpy(held, bytes.data(), bytes.size());
  const std::string_view view(reinterpret_cast<const char*>(held), bytes.size());
  const cm::ModelFile f = cm::ModelFile::from_static(view, "<built-in small>");
  ASSERT_FALSE(f.tensors().empty());
  for (const auto& t : f.tensors()) {
    EXPECT_GE(t.data, held) << t.name;
    EXPECT_LE(t.data + t.bytes, held + bytes.size()) << t.name;
    EXPECT_EQ(reinterpret_cast<uintptr_t>(t.data) % cm::kAlignment, 0u) << t.name;
  }
  EXPECT_EQ(cm::FlameModel::from(f).frames(), 5);
  // Cut short, it is refused as a file would be, naming where it came from.
  try {
    (void)cm::ModelFile::from_static(view.substr(0, bytes.size() / 2), "<built-in small>");
    ADD_FAILURE() << "a truncated built-in model loaded";
  } catch (const cm::ModelError& e) {
    EXPECT_EQ(e.kind(), Kind::kTruncated);
    EXPECT_NE(std::string(e.what()).find("<built-in small>"), std::string::npos) << e.what();
  }
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

// Issue 34: 100,000 nested arrays in a 200 KB header crashed the reader with
// SIGSEGV (the checksum re-serialises the header recursively) before the
// checksum could refuse it. The nesting is refused while parsing, by name.
TEST(ModelFile, DeeplyNestedHeaderIsAHeaderErrorNotACrash) {
  const int depth = 100000;
  const std::string text = R"({"__metadata__": {"format": "candela-model", "version": 1}, "x": )" +
                           std::string(depth, '[') + std::string(depth, ']') + "}";
  std::vector<uint8_t> b(8);
  for (int i = 0; i < 8; ++i) b[i] = static_cast<uint8_t>(text.size() >> (8 * i));
  b.insert(b.end(), text.begin(), text.end());
  std::string msg;
  EXPECT_EQ(error_of(b, &msg), Kind::kHeader);
  EXPECT_NE(msg.find("nested at most 32"), std::string::npos) << msg;
  EXPECT_NE(msg.find("header"), std::string::npos) << msg;
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

// Issue 15: a model with a valid checksum that the players cannot play is
// refused by the reader (so the element falls back to the built-in model)
// instead of loading and then being dropped, or worse.
TEST(FlameModel, RefusesWhatThePlayersCannotPlay) {
  const auto load = [](const cm::ModelWriter& mw) {
    return cm::FlameModel::from(cm::ModelFile::from_bytes(mw.bytes(), "m"));
  };
  // What they can play loads: an ARP of order 4 over 64 parameters.
  const cm::FlameModel ok = load(with_flames(small_model(), 4, 30, 30, 3));
  EXPECT_TRUE(ok.has_learning_flames);
  EXPECT_EQ(ok.flames.dim, cm::kMaxArpDim);
  std::string msg;
  // Order 5..8 used to pass (the ARP takes at most 4).
  EXPECT_EQ(error_of(with_flames(small_model(), 5).bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("learning_flames.order: expected an integer in [1, 4]"), std::string::npos)
      << msg;
  // 65 parameters (sizes up to 256 each used to pass; the ARP state holds 64).
  EXPECT_EQ(error_of(with_flames(small_model(), 2, 30, 30, 4).bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("np + nw + 1 + ne = 65"), std::string::npos) << msg;
  // A size that is no integer at all says so (not the range of an int).
  EXPECT_EQ(error_of(edited(with_flames(small_model(), 2),
                            [](nlohmann::json& i) { i["learning_flames"]["np"] = "4"; })
                         .bytes(),
                     &msg),
            Kind::kInconsistent);
  EXPECT_NE(msg.find("learning_flames.np: expected an integer"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("2147483647"), std::string::npos) << msg;
  // Fewer training frames than the order.
  EXPECT_EQ(error_of(with_flames(small_model(), 3, 4, 4, 2, 2).bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("learning_flames.frames"), std::string::npos) << msg;
  // Issue 34: what no display shows at frame rate (a 16384x4096 model took
  // 1.4 GB and tens of seconds a frame), refused before its images are read.
  EXPECT_EQ(
      error_of(edited(small_model(), [](nlohmann::json& i) { i["width"] = 4096; }).bytes(), &msg),
      Kind::kInconsistent);
  EXPECT_NE(msg.find("model.width: expected an integer in [1, 2048]"), std::string::npos) << msg;
  EXPECT_EQ(error_of(edited(small_model(),
                            [](nlohmann::json& i) {
                              i["width"] = 2048;
                              i["height"] = 2048;
                              i["components"] = 17;
                            })
                         .bytes(),
                     &msg),
            Kind::kInconsistent);
  EXPECT_NE(msg.find("model.components: expected at most 64 Mi texels"), std::string::npos) << msg;
  // A clip at 100000 fps overflowed the Q16.16 frame rate.
  EXPECT_EQ(
      error_of(
          edited(small_model(), [](nlohmann::json& i) { i["clips"][0]["fps"] = 100000.0; }).bytes(),
          &msg),
      Kind::kInconsistent);
  EXPECT_NE(msg.find("clips[0].fps"), std::string::npos) << msg;
  // Negative jump costs, and a frame with more jumps than the walker sums in Q16.16.
  cm::ModelWriter neg = small_model();
  std::vector<float> cost{1, 1, -2, 1, 1, 3};
  neg.add_f32("graph.cost", {6}, cost);
  EXPECT_EQ(error_of(neg.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("graph.cost"), std::string::npos) << msg;
  cm::ModelWriter wide = small_model();
  const int n = cm::kMaxSuccessors + 1;
  std::vector<int32_t> offsets{0, n, n + 1, n + 2, n + 3, n + 4},
      succ(static_cast<size_t>(n) + 4, 2);
  std::vector<float> costs(succ.size(), 1.0f);
  wide.add_i32("graph.offsets", {6}, offsets);
  wide.add_i32("graph.successors", {static_cast<int64_t>(succ.size())}, succ);
  wide.add_f32("graph.cost", {static_cast<int64_t>(succ.size())}, costs);
  EXPECT_EQ(error_of(wide.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("1025 successors"), std::string::npos) << msg;
}

// Issue 34: values that load but would play an invisible or frozen flame
// (found among CRC-valid mutations) are refused naming the tensor, so the
// element plays the built-in model and `--check` says why.
TEST(FlameModel, RefusesInvisibleOrFrozenFlames) {
  std::string msg;
  // The mean image scaled to nothing: a black frame.
  cm::ModelWriter dark = small_model();
  dark.add_f32("mean.scale", {1}, std::vector<float>{0.0f});
  dark.add_f32("mean.offset", {1}, std::vector<float>{0.0f});
  EXPECT_EQ(error_of(dark.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("tensor mean.scale: expected a mean image whose brightest pixel is at least "
                     "16 of 255, got 0"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("invisible"), std::string::npos) << msg;
  // Eigen-images scaled to nothing: every frame is the mean.
  cm::ModelWriter still = small_model();
  still.add_f32("eigen.scale", {3}, std::vector<float>(3, 0.0f));
  still.add_f32("eigen.offset", {3}, std::vector<float>(3, 0.0f));
  EXPECT_EQ(error_of(still.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("tensor eigen.scale: expected the components to move the image"),
            std::string::npos)
      << msg;
  // Every frame's weights alike: the same.
  cm::ModelWriter same = small_model();
  same.add_f32("weights", {5, 3}, std::vector<float>(15, 2.0f));
  EXPECT_EQ(error_of(same.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("the flame would stand still"), std::string::npos) << msg;
  // A tiny motion still plays: a swing of 1 level or more somewhere.
  cm::ModelWriter faint = small_model();
  std::vector<float> w(15, 0.0f);
  w[3] = 1.0f;  // frame 1, component 0: one unit over an image range of about 2
  faint.add_f32("weights", {5, 3}, w);
  EXPECT_NO_THROW(cm::FlameModel::from(cm::ModelFile::from_bytes(faint.bytes(), "m")));
  // Learning Flames: a black shape image, no noise, one training state.
  const int d = 4 + 4 + 1 + 2;
  cm::ModelWriter lf_dark = with_flames(small_model(), 2);
  lf_dark.add_f32("lf.mean.scale", {1}, std::vector<float>{0.0f});
  lf_dark.add_f32("lf.mean.offset", {1}, std::vector<float>{3.0f});
  EXPECT_EQ(error_of(lf_dark.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("tensor lf.mean.scale: expected a mean image whose brightest pixel"),
            std::string::npos)
      << msg;
  cm::ModelWriter quiet = with_flames(small_model(), 2);
  quiet.add_f32("arp.B", {d, d}, std::vector<float>(static_cast<size_t>(d) * d, 0.0f));
  EXPECT_EQ(error_of(quiet.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("tensor arp.B: expected some noise"), std::string::npos) << msg;
  cm::ModelWriter one_pose = with_flames(small_model(), 2);
  one_pose.add_f32("lf.params", {6, d}, std::vector<float>(static_cast<size_t>(6) * d, 1.5f));
  EXPECT_EQ(error_of(one_pose.bytes(), &msg), Kind::kInconsistent);
  EXPECT_NE(msg.find("tensor lf.params: expected training states that differ"), std::string::npos)
      << msg;
}

// Issue 15: special and huge files are refused by what they are, before any read.
TEST(ModelFile, SpecialAndHugeFilesAreRefusedBeforeReading) {
  const std::string fifo = temp_path("fifo.cmodel");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  try {
    cm::FlameModel::load(fifo);  // used to block in open() for ever
    ADD_FAILURE() << "a FIFO loaded";
  } catch (const cm::ModelError& e) {
    EXPECT_EQ(e.kind(), Kind::kIo);
    EXPECT_EQ(std::string(e.what()), fifo + ": not a regular file (a FIFO)");
  }
  std::remove(fifo.c_str());
  // 4 GB (sparse): the reader used to allocate and read all of it before its 8-byte header.
  const std::string big = temp_path("big.cmodel");
  const int fd = ::open(big.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(ftruncate(fd, off_t{4} << 30), 0);
  ::close(fd);
  try {
    cm::FlameModel::load(big);
    ADD_FAILURE() << "a 4 GB model loaded";
  } catch (const cm::ModelError& e) {
    EXPECT_EQ(e.kind(), Kind::kIo);
    EXPECT_EQ(std::string(e.what()), big + ": 4 GB, larger than the 256 MB limit for a model");
  }
  std::remove(big.c_str());
}

// A model built into the binary is read in place from the binary's file
// mapping. Once its images are on the GPU the eigen-flame gives their pages
// back (issue 36: 6.3 MB of the eigen fireplace's resident memory): the
// process stops holding them, and the model still reconstructs the same
// images (they are paged in again from the file). A model read from a file
// is its own only copy and is left alone.
namespace {

// At the built-in fire model's image size.
cm::ModelWriter large_model() { return small_model(48, 128, 160, cm::DType::kU16); }

// Resident bytes of this process (/proc/self/statm).
size_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  size_t total = 0, resident = 0;
  statm >> total >> resident;
  return resident * static_cast<size_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace

TEST(FlameModel, ABuiltInModelGivesItsImagePagesBackAndStillReconstructs) {
  const std::string path = temp_path("built_in.cmodel");
  write_bytes(path, large_model().bytes());
  // The binary's read-only data is a private, read-only file mapping: so is this.
  const int fd = ::open(path.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  struct stat st {};
  ASSERT_EQ(fstat(fd, &st), 0);
  const size_t size = static_cast<size_t>(st.st_size);
  void* map = mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  ASSERT_NE(map, MAP_FAILED);
  {
    const cm::FlameModel m = cm::FlameModel::from(
        cm::ModelFile::from_static({static_cast<const char*>(map), size}, "built-in"));
    const size_t image_bytes =
        m.eigen.pixels() * static_cast<size_t>(m.eigen.count) * cm::dtype_size(m.eigen.dtype);
    std::vector<float> before(m.eigen.pixels()), after(m.eigen.pixels());
    m.reconstruct(m.weights_of(3), before);  // reads every image: all resident now
    const size_t held = resident_bytes();
    const size_t given = m.give_back_image_pages();
    const size_t now = resident_bytes();
    EXPECT_GE(given, image_bytes - 2 * static_cast<size_t>(sysconf(_SC_PAGESIZE)));
    EXPECT_GE(held - std::min(held, now), given * 9 / 10) << "resident " << held << " -> " << now;
    m.reconstruct(m.weights_of(3), after);
    EXPECT_EQ(before, after);
  }
  munmap(map, size);
  // Read from a file: the model's bytes are its only copy, nothing is given back.
  const cm::FlameModel loaded = cm::FlameModel::load(path);
  std::vector<float> before(loaded.eigen.pixels()), after(loaded.eigen.pixels());
  loaded.reconstruct(loaded.weights_of(2), before);
  EXPECT_EQ(loaded.give_back_image_pages(), 0u);
  loaded.reconstruct(loaded.weights_of(2), after);
  EXPECT_EQ(before, after);
}
