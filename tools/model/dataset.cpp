#include "dataset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/json_parse.h"

namespace candela::tools {

nlohmann::json clips_to_json(const std::vector<model::ClipInfo>& clips) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& c : clips) {
    nlohmann::json labels = nlohmann::json::array();
    for (const auto& l : c.labels)
      labels.push_back({{"from", l.from}, {"to", l.to}, {"label", l.label}});
    a.push_back({{"name", c.name},
                 {"source", c.source},
                 {"first", c.first},
                 {"count", c.count},
                 {"fps", c.fps},
                 {"labels", labels}});
  }
  return a;
}

void save_dataset(const Dataset& d, const std::string& dir) {
  std::filesystem::create_directories(dir);
  nlohmann::json plumes = nlohmann::json::array();
  for (int i = 0; i < d.frames(); ++i)
    if (d.multi_plume[i]) plumes.push_back(i);
  nlohmann::json m = {{"format", "candela-dataset"},
                      {"version", 1},
                      {"width", d.width},
                      {"height", d.height},
                      {"frames", d.frames()},
                      {"intensity", "srgb"},
                      {"clips", clips_to_json(d.clips)},
                      {"multi_plume", plumes},
                      {"options", d.options}};
  {
    std::ofstream f(dir + "/frames.u8", std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(d.pixels.data()),
            static_cast<std::streamsize>(d.pixels.size()));
    if (!f) throw RuntimeError("cannot write " + dir + "/frames.u8");
  }
  std::ofstream f(dir + "/manifest.json", std::ios::trunc);
  f << m.dump(2) << "\n";
  if (!f) throw RuntimeError("cannot write " + dir + "/manifest.json");
}

namespace {
int need_int(const std::string& file, const nlohmann::json& j, const std::string& path,
             const char* key, int lo, int hi) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_number_integer() || it->get<int64_t>() < lo ||
      it->get<int64_t>() > hi)
    throw ConfigError(
        file, path + key,
        "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return it->get<int>();
}
}  // namespace

uint8_t encode_srgb8(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  const float e = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return static_cast<uint8_t>(std::lround(e * 255.0f));
}

Dataset parse_manifest(std::string_view text, const std::string& mf, bool* linear) {
  // Nesting bounded before the tree is built (core/json_parse.h).
  const nlohmann::json m = parse_json(text, mf);
  // Compared as JSON, not read with value(), which throws a type error
  // naming no file for a key of another type (found by dataset_manifest_fuzz).
  if (!m.is_object() || !m.contains("format") || m["format"] != "candela-dataset")
    throw ConfigError(mf, "format", "expected \"candela-dataset\"");
  if (!m.contains("version") || m["version"] != 1) throw ConfigError(mf, "version", "expected 1");
  Dataset d;
  d.width = need_int(mf, m, "", "width", 1, 16384);
  d.height = need_int(mf, m, "", "height", 1, 16384);
  const int frames = need_int(mf, m, "", "frames", 1, 1 << 24);
  if (!m.contains("clips") || !m["clips"].is_array() || m["clips"].empty())
    throw ConfigError(mf, "clips", "expected a non-empty array");
  int next = 0;
  for (size_t i = 0; i < m["clips"].size(); ++i) {
    const auto& c = m["clips"][i];
    const std::string p = "clips[" + std::to_string(i) + "].";
    model::ClipInfo ci;
    if (!c.is_object() || !c.contains("name") || !c["name"].is_string())
      throw ConfigError(mf, p + "name", "expected a string");
    ci.name = c["name"].get<std::string>();
    if (c.contains("source") && !c["source"].is_string())
      throw ConfigError(mf, p + "source", "expected a string");
    ci.source = c.contains("source") ? c["source"].get<std::string>() : "";
    ci.first = need_int(mf, c, p, "first", 0, frames);
    ci.count = need_int(mf, c, p, "count", 1, frames);
    if (ci.first != next || ci.first + ci.count > frames)
      throw ConfigError(mf, p + "first", "clips must cover the frames in order");
    next = ci.first + ci.count;
    if (!c.contains("fps") || !c["fps"].is_number() || !(c["fps"].get<double>() > 0))
      throw ConfigError(mf, p + "fps", "expected a positive number");
    ci.fps = c["fps"].get<double>();
    if (c.contains("labels")) {
      if (!c["labels"].is_array()) throw ConfigError(mf, p + "labels", "expected an array");
      for (size_t j = 0; j < c["labels"].size(); ++j) {
        const auto& l = c["labels"][j];
        const std::string lp = p + "labels[" + std::to_string(j) + "].";
        model::ClipLabel cl;
        cl.from = need_int(mf, l, lp, "from", ci.first, ci.first + ci.count);
        cl.to = need_int(mf, l, lp, "to", cl.from, ci.first + ci.count);
        if (!l.contains("label") || !l["label"].is_string())
          throw ConfigError(mf, lp + "label", "expected a string");
        cl.label = l["label"].get<std::string>();
        ci.labels.push_back(cl);
      }
    }
    d.clips.push_back(std::move(ci));
  }
  if (next != frames) throw ConfigError(mf, "clips", "clips must cover all frames");
  d.multi_plume.assign(frames, 0);
  if (m.contains("multi_plume")) {
    if (!m["multi_plume"].is_array()) throw ConfigError(mf, "multi_plume", "expected an array");
    for (const auto& v : m["multi_plume"]) {
      if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() >= frames)
        throw ConfigError(mf, "multi_plume", "expected frame indices");
      d.multi_plume[v.get<int>()] = 1;
    }
  }
  if (m.contains("options")) d.options = m["options"];
  const auto in = m.find("intensity");
  const bool lin = in == m.end() || *in == "linear";
  if (!lin && *in != "srgb") throw ConfigError(mf, "intensity", "expected \"srgb\" or \"linear\"");
  if (linear) *linear = lin;
  return d;
}

Dataset load_dataset(const std::string& dir) {
  const std::string mf = dir + "/manifest.json";
  std::ifstream in(mf);
  if (!in)
    throw ConfigError(mf, "",
                      "cannot open (is " + dir + " a dataset made by `candela-tool ingest`?)");
  std::ostringstream text;
  text << in.rdbuf();
  bool linear = false;
  Dataset d = parse_manifest(text.str(), mf, &linear);
  const int frames = d.frames();
  const std::string ff = dir + "/frames.u8";
  const size_t want = d.frame_pixels() * frames;
  std::error_code ec;
  const auto have = std::filesystem::file_size(ff, ec);
  if (ec || have != want)
    throw ConfigError(ff, "",
                      "expected " + std::to_string(want) + " bytes (" + std::to_string(frames) +
                          " frames of " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                          ")");
  d.pixels.resize(want);
  std::ifstream fin(ff, std::ios::binary);
  fin.read(reinterpret_cast<char*>(d.pixels.data()), static_cast<std::streamsize>(want));
  if (!fin) throw ConfigError(ff, "", "read failed");
  // Datasets made before intensities were display-encoded hold linear luma:
  // encode them as ingest does now, so old and new datasets build alike.
  if (linear) {
    std::array<uint8_t, 256> lut;
    for (int i = 0; i < 256; ++i) lut[i] = encode_srgb8(i / 255.0f);
    for (uint8_t& p : d.pixels) p = lut[p];
  }
  return d;
}

Dataset resample_dataset(const Dataset& d, int frames) {
  Dataset out;
  out.width = d.width;
  out.height = d.height;
  out.options = d.options;
  out.options["resampled_to"] = frames;
  const size_t px = d.frame_pixels();
  out.pixels.resize(px * frames);
  out.multi_plume.assign(frames, 0);
  const double ratio = static_cast<double>(frames) / d.frames();
  int next = 0;
  for (size_t ci = 0; ci < d.clips.size(); ++ci) {
    const auto& c = d.clips[ci];
    model::ClipInfo nc = c;
    nc.first = next;
    nc.count = ci + 1 == d.clips.size()
                   ? frames - next
                   : std::max(1, static_cast<int>(std::lround((c.first + c.count) * ratio)) - next);
    nc.fps = c.fps * nc.count / c.count;
    nc.labels.clear();
    for (const auto& l : c.labels) {
      auto map = [&](int f) {
        return std::clamp(nc.first + static_cast<int>(std::lround((f - c.first) * ratio)), nc.first,
                          nc.first + nc.count);
      };
      nc.labels.push_back({map(l.from), map(l.to), l.label});
    }
    for (int i = 0; i < nc.count; ++i) {
      // Position in the source clip; blend the two nearest frames.
      const double s = nc.count > 1 ? static_cast<double>(i) * (c.count - 1) / (nc.count - 1) : 0.0;
      const int a = c.first + std::min(static_cast<int>(s), c.count - 1);
      const int b = std::min(a + 1, c.first + c.count - 1);
      const float t = static_cast<float>(s - std::floor(s));
      const uint8_t* pa = d.frame(a);
      const uint8_t* pb = d.frame(b);
      uint8_t* o = out.pixels.data() + px * (nc.first + i);
      for (size_t p = 0; p < px; ++p)
        o[p] = static_cast<uint8_t>(std::lround(pa[p] + t * (static_cast<float>(pb[p]) - pa[p])));
      out.multi_plume[nc.first + i] = d.multi_plume[t < 0.5f ? a : b];
    }
    next += nc.count;
    out.clips.push_back(std::move(nc));
  }
  return out;
}

}  // namespace candela::tools
