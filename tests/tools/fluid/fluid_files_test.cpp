// Field files, the clip manifest and the `candela-tool simulate` command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "field_file.h"
#include "model/model_file.h"
#include "model/model_writer.h"
#include "sim_dataset.h"

namespace candela::fluid {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  fs::path d = fs::path(CANDELA_BINARY_DIR) / "test-scratch" / "fluid" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Runs a command, returns its exit status and stderr+stdout.
int run(const std::string& cmd, std::string& output) {
  output.clear();
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[512];
  while (fgets(buf, sizeof buf, p)) output += buf;
  const int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

FieldFrame sample_frame() {
  FieldFrame f;
  f.index = 7;
  f.time = 0.25;
  f.t_ambient = 300.0;
  f.t_reference = 1800.0;
  f.temperature = Grid2(5, 3);
  f.u = Grid2(5, 3);
  f.v = Grid2(5, 3);
  for (int k = 0; k < 15; ++k) {
    f.temperature.data[k] = 300.0 + 10.0 * k;
    f.u.data[k] = 0.5 * k;
    f.v.data[k] = -0.25 * k;
  }
  f.has_velocity = true;
  return f;
}

TEST(FieldFile, RoundTripsExactly) {
  const fs::path d = scratch("roundtrip");
  const FieldFrame f = sample_frame();
  write_field_file((d / "a.cfld").string(), f);
  const FieldFrame g = read_field_file((d / "a.cfld").string());
  EXPECT_EQ(g.index, 7u);
  EXPECT_EQ(g.time, 0.25);
  EXPECT_EQ(g.t_reference, 1800.0);
  ASSERT_TRUE(g.has_velocity);
  EXPECT_EQ(g.temperature.width, 5);
  EXPECT_EQ(g.temperature.height, 3);
  EXPECT_EQ(g.temperature.data, f.temperature.data);  // all exactly representable in float
  EXPECT_EQ(g.u.data, f.u.data);
  EXPECT_EQ(g.v.data, f.v.data);
  // A container file: three 64-byte aligned tensors of 15 floats after the header.
  const model::ModelFile file = model::ModelFile::open((d / "a.cfld").string());
  EXPECT_EQ(file.tensors().size(), 3u);
  EXPECT_EQ(fs::file_size(d / "a.cfld"), file.header_bytes() + 2u * 64u + 15u * 4u);
}

// Each defect is reported with the file and the field at fault.
TEST(FieldFile, DefectsNameTheFileAndField) {
  const fs::path d = scratch("defects");
  const std::string path = (d / "b.cfld").string();
  write_field_file(path, sample_frame());
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto expect_error = [&](std::string data, const std::string& field) {
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << data;
    }
    try {
      read_field_file(path);
      ADD_FAILURE() << "accepted a file with a bad " << field;
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_NE(e.key().find(field), std::string::npos) << e.what();
    }
  };
  // The container's own checks (field names as for a model file).
  expect_error(bytes.substr(0, 4), "header length");
  expect_error(bytes.substr(0, bytes.size() - 4), "data");
  std::string bad = bytes;
  bad[bad.size() - 1] ^= 1;
  expect_error(bad, "__metadata__.checksum");
  // A well-formed container that is not a good field file.
  auto remade = [&](const std::function<void(model::ModelWriter&, nlohmann::json&)>& change) {
    FieldFrame f = sample_frame();
    model::ModelWriter w;
    nlohmann::json info = {{"kind", "fluid-field"}, {"version", 1},       {"frame", 7},
                           {"time", 0.25},          {"t_ambient", 300.0}, {"t_reference", 1800.0},
                           {"velocity", true}};
    std::vector<float> t(f.temperature.data.begin(), f.temperature.data.end());
    w.add_f32("temperature", {3, 5}, t);
    w.add_f32("u", {3, 5}, t);
    w.add_f32("v", {3, 5}, t);
    change(w, info);
    w.set_info(info);
    const auto out = w.bytes();
    return std::string(out.begin(), out.end());
  };
  expect_error(remade([](auto&, auto& i) { i["kind"] = "noise-table"; }), "model.kind");
  expect_error(remade([](auto&, auto& i) { i["version"] = 2; }), "model.version");
  expect_error(remade([](auto&, auto& i) { i["t_reference"] = 100.0; }), "model.t_reference");
  expect_error(remade([](auto&, auto& i) { i["velocity"] = 1; }), "model.velocity");
  expect_error(remade([](auto&, auto& i) { i["velocity"] = false; }), "tensors");
  expect_error(remade([](auto& w, auto&) {
                 w.add_f32("u", {5, 3}, std::vector<float>(15));
               }),
               "tensor u");
  expect_error(remade([](auto& w, auto&) {
                 std::vector<float> t(15, 300.0f);
                 t[3] = std::nanf("");
                 w.add_f32("temperature", {3, 5}, t);
               }),
               "temperature[3]");
  EXPECT_THROW(read_field_file((d / "missing.cfld").string()), ConfigError);
}

TEST(SimManifest, RoundTripsAndRejectsBadValues) {
  const fs::path d = scratch("manifest");
  SimManifest m;
  m.name = "candle \"test\"";
  m.command = "candela-tool simulate --out 'x y'";
  m.frames = 12;
  m.fps = 24.0;
  m.width = 64;
  m.height = 80;
  m.colour = "blackbody";
  m.has_fields = true;
  m.grid_width = 32;
  m.grid_height = 40;
  m.t_reference = 1700.0;
  write_manifest(d.string(), m);
  const SimManifest r = read_manifest(d.string());
  EXPECT_EQ(r.name, m.name);
  EXPECT_EQ(r.command, m.command);
  EXPECT_EQ(r.frames, 12);
  EXPECT_EQ(r.fps, 24.0);
  EXPECT_EQ(r.colour, "blackbody");
  EXPECT_TRUE(r.has_fields);
  EXPECT_EQ(r.grid_height, 40);
  EXPECT_EQ(r.t_reference, 1700.0);
  {
    std::ofstream out(manifest_path(d.string()), std::ios::trunc);
    out << "[clip]\nname=\"x\"\nsource=\"s\"\nframes=0\nfps=30.0\nwidth=1\nheight=1\ncolour="
           "\"gray\"\n";
  }
  try {
    read_manifest(d.string());
    ADD_FAILURE() << "accepted frames = 0";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "clip.frames");
  }
}

TEST(SimulateCommand, ShortFormWritesAConsistentClip) {
  const fs::path d = scratch("cli") / "clip";
  std::string out;
  const int rc = run(std::string(CANDELA_TOOL_EXE) + " simulate --frames 4 --warmup 0.2 --out " +
                         d.string() + " --grid 24x32",
                     out);
  ASSERT_EQ(rc, 0) << out;
  const SimManifest m = read_manifest(d.string());
  EXPECT_EQ(m.frames, 4);
  EXPECT_EQ(m.name, "clip");
  EXPECT_EQ(m.source, "candela-tool simulate");
  EXPECT_EQ(m.width, 24);
  EXPECT_EQ(m.height, 32);
  for (int k = 0; k < 4; ++k) {
    const Image img = read_png(frame_path(d.string(), k));
    EXPECT_EQ(img.width, 24);
    EXPECT_EQ(img.height, 32);
    const FieldFrame f = read_field_file(field_path(d.string(), k));
    EXPECT_EQ(f.index, static_cast<uint32_t>(k));
    ASSERT_TRUE(f.has_velocity);
    // The frame shows the field: the hottest cell's pixel has its normalised
    // temperature as gray level (fields run bottom-up, images top-down).
    int best = 0;
    for (int i = 1; i < 24 * 32; ++i)
      if (f.temperature.data[i] > f.temperature.data[best]) best = i;
    const int bx = best % 24, by = 31 - best / 24;
    const double s = (f.temperature.data[best] - f.t_ambient) / (f.t_reference - f.t_ambient);
    EXPECT_GT(s, 0.3) << "the source must have heated the air, frame " << k;
    EXPECT_NEAR(img.at(bx, by), 255.0 * std::min(s, 1.0), 1.0) << "frame " << k;
  }
  EXPECT_FALSE(fs::exists(frame_path(d.string(), 4)));
}

// --slices: independent simulations side by side on one wider canvas; each
// slice its own seed, so the fire's parts differ from each other.
TEST(SimulateCommand, SlicesMakeOneWiderPictureOfDifferentFires) {
  const fs::path d = scratch("slices") / "clip";
  std::string out;
  const int rc = run(std::string(CANDELA_TOOL_EXE) +
                         " simulate -q --preset tongues --grid 48x128 --frames 2 --warmup 0.6 "
                         "--render radiance --exposure 3 --soot 70 --no-fields --slices 3 "
                         "--slice-spacing 1 --out " +
                         d.string(),
                     out);
  ASSERT_EQ(rc, 0) << out;
  const SimManifest m = read_manifest(d.string());
  EXPECT_EQ(m.width, 144) << "48 px slices, centres one slice width apart";
  EXPECT_EQ(m.height, 128);
  const Image img = read_png(frame_path(d.string(), 1));
  ASSERT_EQ(img.width, 144);
  // Each third of the canvas holds flame, and no two thirds are the same
  // picture (nor mirror images: slices may be mirrored).
  double lit[3] = {0, 0, 0};
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 144; ++x) lit[x / 48] += img.at(x, y);
  for (double l : lit) EXPECT_GT(l, 128 * 48 * 2.0) << "a slice with no flame";
  auto diff = [&](int a, int b, bool mirror) {
    double s = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = 8; x < 40; ++x)
        s += std::abs(img.at(a * 48 + x, y) - img.at(b * 48 + (mirror ? 47 - x : x), y));
    return s / (128 * 32);
  };
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      EXPECT_GT(diff(a, b, false), 2.0) << a << " and " << b;
      EXPECT_GT(diff(a, b, true), 2.0) << a << " and " << b << " mirrored";
    }
  EXPECT_EQ(run(std::string(CANDELA_TOOL_EXE) + " simulate --slices 3 --render radiance --out " +
                    (scratch("slices") / "f").string(),
                out),
            2);
  EXPECT_NE(out.find("--no-fields"), std::string::npos) << out;
}

// --slice-rates: each slice's clock runs at its own rate. The two slices of a
// two-slice fire run at 1 -/+ S, so after the same warm-up (the plumes still
// rising) the fast one's top is higher and the slow one's lower than at 1x.
TEST(SimulateCommand, SliceRatesRunEachSliceAtItsOwnPace) {
  auto plume_top = [](const Image& img, int x0, int x1) {  // rows from the bottom
    for (int y = 0; y < img.height; ++y)
      for (int x = x0; x < x1; ++x)
        if (img.at(x, y) > 20) return img.height - y;
    return 0;
  };
  const std::string base = std::string(CANDELA_TOOL_EXE) +
                           " simulate -q --preset tongues --grid 48x128 --frames 1 --warmup 0.5 "
                           "--render radiance --exposure 3 --soot 70 --no-fields --slices 2 "
                           "--slice-spacing 1 --seed 4 --out ";
  std::string out;
  const fs::path same = scratch("rates") / "same", spread = scratch("rates") / "spread";
  ASSERT_EQ(run(base + same.string(), out), 0) << out;
  ASSERT_EQ(run(base + spread.string() + " --slice-rates 0.5", out), 0) << out;
  const Image a = read_png(frame_path(same.string(), 0));
  const Image b = read_png(frame_path(spread.string(), 0));
  const int a0 = plume_top(a, 0, 48), a1 = plume_top(a, 48, 96);
  const int b0 = plume_top(b, 0, 48), b1 = plume_top(b, 48, 96);
  EXPECT_GT(a0, 10) << "no plume at 1x";
  EXPECT_TRUE((b0 + 4 < a0 && b1 > a1 + 4) || (b0 > a0 + 4 && b1 + 4 < a1))
      << "plume tops (rows): same rates " << a0 << ", " << a1 << "; spread " << b0 << ", " << b1;
  const std::string bad = std::string(CANDELA_TOOL_EXE) +
                          " simulate --render radiance --no-fields --out " +
                          (scratch("rates") / "bad").string();
  EXPECT_EQ(run(bad + " --slices 3 --slice-rates 0.7", out), 2);
  EXPECT_NE(out.find("slice-rates: a spread in 0..0.6"), std::string::npos) << out;
  EXPECT_EQ(run(bad + " --slice-rates 0.2", out), 2);
  EXPECT_NE(out.find("slice-rates: applies to --slices 2 or more"), std::string::npos) << out;
}

// --shutter: a short shutter shows the last substep alone (crisp); the whole
// frame's shutter averages the substeps (moving edges blur). --slice-edge-fade:
// each grid's light fades to nothing at its sides (a dim exposure, so the
// soft clip does not hide the change).
TEST(SimulateCommand, ShutterAndSliceEdgeFadeShapeTheLight) {
  const std::string base = std::string(CANDELA_TOOL_EXE) +
                           " simulate -q --preset tongues --grid 48x128 --frames 1 --warmup 0.8 "
                           "--render radiance --exposure 0.4 --soot 70 --no-fields --slices 2 "
                           "--slice-spacing 1 --seed 4 --substeps 4 --out ";
  std::string out;
  const fs::path d = scratch("shutter");
  ASSERT_EQ(run(base + (d / "long").string(), out), 0) << out;
  ASSERT_EQ(run(base + (d / "short").string() + " --shutter 0.25", out), 0) << out;
  ASSERT_EQ(run(base + (d / "fade").string() + " --slice-edge-fade 0.25", out), 0) << out;
  const Image lng = read_png(frame_path((d / "long").string(), 0));
  const Image sht = read_png(frame_path((d / "short").string(), 0));
  const Image fad = read_png(frame_path((d / "fade").string(), 0));
  auto mean_gradient = [](const Image& img) {
    double s = 0;
    for (int y = 1; y < img.height; ++y)
      for (int x = 1; x < img.width; ++x)
        s += std::abs(img.at(x, y) - img.at(x - 1, y)) + std::abs(img.at(x, y) - img.at(x, y - 1));
    return s / (img.width * img.height);
  };
  EXPECT_GT(mean_gradient(sht), 1.05 * mean_gradient(lng)) << "a short shutter is crisper";
  // The same simulation drawn twice: per canvas column, faded light over
  // unfaded light is the fade's window there: ~1 mid-grid, near 0 by a side.
  auto column = [](const Image& img, int x) {
    double s = 0;
    for (int y = 0; y < img.height; ++y) s += img.at(x, y);
    return s;
  };
  int brightest = 0;
  double lowest_ratio = 1.0;
  for (int x = 0; x < lng.width; ++x) {
    if (column(lng, x) > column(lng, brightest)) brightest = x;
    if (column(lng, x) > 200.0)
      lowest_ratio = std::min(lowest_ratio, column(fad, x) / column(lng, x));
  }
  EXPECT_GT(column(fad, brightest) / column(lng, brightest), 0.9) << "the flames' middle is kept";
  EXPECT_LT(lowest_ratio, 0.6)
      << "lit columns by a grid's side fade out (sRGB: 0.6 is ~0.3 of the light)";
  const std::string bad = std::string(CANDELA_TOOL_EXE) +
                          " simulate --render radiance --no-fields --slices 2 --out " +
                          (d / "bad").string();
  EXPECT_EQ(run(bad + " --shutter 0", out), 2);
  EXPECT_NE(out.find("shutter: a share of the frame in (0, 1]"), std::string::npos) << out;
  EXPECT_EQ(run(bad + " --slice-edge-fade 0.3", out), 2);
  EXPECT_NE(out.find("slice-edge-fade: a share of the grid in 0..0.25"), std::string::npos) << out;
}

TEST(SimulateCommand, BadOptionsFailWithAClearMessage) {
  const std::string exe =
      std::string(CANDELA_TOOL_EXE) + " simulate --out " + (scratch("bad") / "x").string() + " ";
  std::string out;
  EXPECT_EQ(run(exe + "--grid 12by12", out), 2);
  EXPECT_NE(out.find("--grid"), std::string::npos) << out;
  EXPECT_EQ(run(exe + "--source x=0.5,q=2", out), 2);
  EXPECT_NE(out.find("unknown key \"q\""), std::string::npos) << out;
  EXPECT_EQ(run(exe + "--source x=1.5", out), 2);
  EXPECT_NE(out.find("source 1 x"), std::string::npos) << out;
  EXPECT_EQ(run(exe + "--wind 2:10,1:0", out), 2);
  EXPECT_NE(out.find("--wind"), std::string::npos) << out;
  EXPECT_EQ(run(exe + "--colour purple", out), 2);
  EXPECT_NE(out.find("--colour"), std::string::npos) << out;
  EXPECT_EQ(run(exe + "--frames 0", out), 2);
  EXPECT_NE(out.find("frames"), std::string::npos) << out;
  EXPECT_NE(run(std::string(CANDELA_TOOL_EXE) + " simulate --frames 3", out), 0);
  EXPECT_NE(out.find("--out"), std::string::npos) << out;
}

}  // namespace
}  // namespace candela::fluid
