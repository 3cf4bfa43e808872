#include "model/flame_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace candela::model {
namespace {

const nlohmann::json& member(const ModelFile& f, const nlohmann::json& obj, const std::string& path,
                             const char* key) {
  if (!obj.is_object()) f.fail(path, "expected an object");
  auto it = obj.find(key);
  if (it == obj.end()) f.fail(path + "." + key, "missing");
  return *it;
}

int get_int(const ModelFile& f, const nlohmann::json& obj, const std::string& path, const char* key,
            int lo, int hi) {
  const auto& v = member(f, obj, path, key);
  if (!v.is_number_integer() || v.get<int64_t>() < lo || v.get<int64_t>() > hi)
    f.fail(path + "." + key,
           "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v.get<int64_t>());
}

double get_num(const ModelFile& f, const nlohmann::json& obj, const std::string& path,
               const char* key, double lo, double hi) {
  const auto& v = member(f, obj, path, key);
  if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
    f.fail(path + "." + key,
           "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v.get<double>();
}

std::string get_str(const ModelFile& f, const nlohmann::json& obj, const std::string& path,
                    const char* key) {
  const auto& v = member(f, obj, path, key);
  if (!v.is_string()) f.fail(path + "." + key, "expected a string");
  return v.get<std::string>();
}

void require_finite(const ModelFile& f, const std::string& name, std::span<const float> v) {
  for (float x : v)
    if (!std::isfinite(x)) f.fail("tensor " + name, "holds a value that is not finite");
}

QuantisedImages quantised(const ModelFile& f, const std::string& name, int count, int width,
                          int height) {
  QuantisedImages q;
  const Tensor* t = f.find(name + ".q");
  if (!t) f.fail("tensor " + name + ".q", "missing");
  if (t->dtype != DType::kU8 && t->dtype != DType::kU16)
    f.fail("tensor " + name + ".q", "expected dtype U8 or U16");
  f.require(name + ".q", t->dtype, {count, height, width});
  q.dtype = t->dtype;
  q.count = count;
  q.width = width;
  q.height = height;
  q.data = t->data;
  q.scale = f.require(name + ".scale", DType::kF32, {count}).view<float>();
  q.offset = f.require(name + ".offset", DType::kF32, {count}).view<float>();
  require_finite(f, name + ".scale", q.scale);
  require_finite(f, name + ".offset", q.offset);
  return q;
}

// Issue 34: values that load but play nothing a viewer would call a flame.
// A mean image no brighter than this (display-coded, 255 = white; the
// ramp's default black level is 4) shows no flame; the built-in models'
// means peak above 200.
constexpr float kMinVisiblePeak = 16.0f;
// The least swing, in display levels, that the motion must give some pixel
// (a weight's spread over the frames times its image's range); below it the
// flame stands still. The built-in models swing by tens of levels.
constexpr double kMinMotionLevels = 1.0;

void require_visible(const ModelFile& f, const std::string& name, const QuantisedImages& q) {
  float peak = -std::numeric_limits<float>::infinity();
  for (size_t p = 0; p < q.pixels(); ++p) peak = std::max(peak, q.value(0, p));
  if (!(peak >= kMinVisiblePeak))
    f.fail("tensor " + name + ".scale", "expected a mean image whose brightest pixel is at least " +
                                            std::to_string(static_cast<int>(kMinVisiblePeak)) +
                                            " of 255, got " + std::to_string(peak) +
                                            ": the flame would be invisible");
}

// The largest swing any of the first components gives a pixel over the
// model's frames: the weight's spread times the image's range.
double motion_levels(const FlameModel& m) {
  const int e = m.components(), frames = m.frames();
  double best = 0;
  for (int k = 0; k < std::min(e, 16); ++k) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int i = 0; i < frames; ++i) {
      const float w = m.weights[static_cast<size_t>(i) * e + k];
      lo = std::min(lo, w);
      hi = std::max(hi, w);
    }
    float ilo = std::numeric_limits<float>::infinity(), ihi = -ilo;
    for (size_t p = 0; p < m.eigen.pixels(); ++p) {
      const float v = m.eigen.value(k, p);
      ilo = std::min(ilo, v);
      ihi = std::max(ihi, v);
    }
    best = std::max(best, (static_cast<double>(hi) - lo) * (static_cast<double>(ihi) - ilo));
  }
  return best;
}

}  // namespace

std::optional<SizeProblem> learning_flames_size_problem(int np, int nw, int ne, int order) {
  const auto range = [](const char* field, int v, int lo, int hi) -> std::optional<SizeProblem> {
    if (v >= lo && v <= hi) return std::nullopt;
    return SizeProblem{
        field, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]"};
  };
  if (auto p = range("np", np, 2, 256)) return p;
  if (auto p = range("nw", nw, 2, 256)) return p;
  if (auto p = range("ne", ne, 1, 256)) return p;
  if (auto p = range("order", order, 1, kMaxArpOrder)) return p;
  const int dim = np + nw + 1 + ne;
  if (dim > kMaxArpDim)
    return SizeProblem{"", "np + nw + 1 + ne = " + std::to_string(dim) +
                               "; the ARP player takes a state of at most " +
                               std::to_string(kMaxArpDim)};
  return std::nullopt;
}

FlameModel FlameModel::load(const std::string& path) { return from(ModelFile::open(path)); }

FlameModel FlameModel::from(ModelFile file) {
  FlameModel m;
  const ModelFile& f = file;
  const nlohmann::json& info = f.info();
  const std::string kind = get_str(f, info, "model", "kind");
  if (kind != "eigenfires") f.fail("model.kind", "expected \"eigenfires\"");
  const int w = get_int(f, info, "model", "width", 1, kMaxModelSide);
  const int h = get_int(f, info, "model", "height", 1, kMaxModelSide);
  const int e = get_int(f, info, "model", "components", 1, 65536);
  const int64_t texels = int64_t{std::min(e, kMaxPlayedComponents)} * w * h;
  if (texels > kMaxModelTexels)
    f.fail("model.components",
           "expected at most " + std::to_string(kMaxModelTexels >> 20) +
               " Mi texels of played eigen-images (components, at most " +
               std::to_string(kMaxPlayedComponents) + " played, x width x height), got " +
               std::to_string(std::min(e, kMaxPlayedComponents)) + " x " + std::to_string(w) +
               " x " + std::to_string(h) + ": fewer components or smaller images");
  const int frames = get_int(f, info, "model", "frames", 1, 1 << 24);
  m.frames_ = frames;
  m.total_variance = get_num(f, info, "model", "total_variance", 0, 1e30);
  m.mean = quantised(f, "mean", 1, w, h);
  m.eigen = quantised(f, "eigen", e, w, h);
  m.weights = f.require("weights", DType::kF32, {frames, e}).view<float>();
  require_finite(f, "weights", m.weights);
  m.variance = f.require("variance", DType::kF32, {e}).view<float>();
  require_finite(f, "variance", m.variance);
  require_visible(f, "mean", m.mean);
  if (const double motion = frames > 1 ? motion_levels(m) : kMinMotionLevels;
      motion < kMinMotionLevels)
    f.fail("tensor eigen.scale",
           "expected the components to move the image by at least 1 of 255 over the frames "
           "(weights' spread x eigen-image range), got " +
               std::to_string(motion) + ": the flame would stand still");

  // Motion graph: CSR with every frame having somewhere to go.
  m.graph.offsets = f.require("graph.offsets", DType::kI32, {frames + 1}).view<int32_t>();
  m.graph.successors = f.require("graph.successors", DType::kI32, {-1}).view<int32_t>();
  const int64_t edges = static_cast<int64_t>(m.graph.successors.size());
  m.graph.cost = f.require("graph.cost", DType::kF32, {edges}).view<float>();
  require_finite(f, "graph.cost", m.graph.cost);
  for (float c : m.graph.cost)
    if (c < 0) f.fail("tensor graph.cost", "expected distances >= 0, got " + std::to_string(c));
  if (m.graph.offsets[0] != 0 || m.graph.offsets[frames] != edges)
    f.fail("tensor graph.offsets", "must start at 0 and end at the number of successors");
  for (int i = 0; i < frames; ++i) {
    if (m.graph.offsets[i + 1] <= m.graph.offsets[i])
      f.fail("tensor graph.offsets", "frame " + std::to_string(i) + " has no successor");
    if (m.graph.offsets[i + 1] - m.graph.offsets[i] > kMaxSuccessors)
      f.fail("tensor graph.offsets",
             "frame " + std::to_string(i) + " has " +
                 std::to_string(m.graph.offsets[i + 1] - m.graph.offsets[i]) +
                 " successors; the graph player takes at most " + std::to_string(kMaxSuccessors));
  }
  for (int32_t s : m.graph.successors)
    if (s < 0 || s >= frames) f.fail("tensor graph.successors", "frame index out of range");
  const auto& g = member(f, info, "model", "graph");
  m.graph.theta_min = static_cast<float>(get_num(f, g, "model.graph", "theta_min", 0, 1e30));

  // Clips tile the frames in order.
  const auto& clips = member(f, info, "model", "clips");
  if (!clips.is_array() || clips.empty()) f.fail("model.clips", "expected a non-empty array");
  int next = 0;
  for (size_t i = 0; i < clips.size(); ++i) {
    const std::string p = "model.clips[" + std::to_string(i) + "]";
    ClipInfo c;
    c.name = get_str(f, clips[i], p, "name");
    c.source = get_str(f, clips[i], p, "source");
    c.first = get_int(f, clips[i], p, "first", 0, frames);
    c.count = get_int(f, clips[i], p, "count", 1, frames);
    c.fps = get_num(f, clips[i], p, "fps", 0.1, kMaxClipFps);
    if (c.first != next || c.first + c.count > frames)
      f.fail(p, "clips must cover the frames in order without gaps");
    next = c.first + c.count;
    const auto& labels = member(f, clips[i], p, "labels");
    if (!labels.is_array()) f.fail(p + ".labels", "expected an array");
    for (size_t j = 0; j < labels.size(); ++j) {
      const std::string lp = p + ".labels[" + std::to_string(j) + "]";
      ClipLabel l;
      l.from = get_int(f, labels[j], lp, "from", c.first, c.first + c.count);
      l.to = get_int(f, labels[j], lp, "to", l.from, c.first + c.count);
      l.label = get_str(f, labels[j], lp, "label");
      c.labels.push_back(std::move(l));
    }
    m.clips.push_back(std::move(c));
  }
  if (next != frames)
    f.fail("model.clips", "clips must cover all " + std::to_string(frames) + " frames");

  const auto& col = member(f, info, "model", "colour");
  m.colour.hue = static_cast<float>(get_num(f, col, "model.colour", "hue", 0, 360));
  m.colour.saturation = static_cast<float>(get_num(f, col, "model.colour", "saturation", 0, 1));
  m.colour.glow_radius = static_cast<float>(get_num(f, col, "model.colour", "glow_radius", 0, 1));
  m.colour.glow_strength =
      static_cast<float>(get_num(f, col, "model.colour", "glow_strength", 0, 4));
  if (col.contains("black_level"))  // optional; older files use the default
    m.colour.black_level =
        static_cast<float>(get_num(f, col, "model.colour", "black_level", 0, 255));

  auto lf_it = info.find("learning_flames");
  if (lf_it != info.end()) {
    const auto& lf = *lf_it;
    const std::string p = "model.learning_flames";
    LearningFlamesModel& L = m.flames;
    // Any integer here; learning_flames_size_problem says which ones the players take.
    const auto size = [&](const char* key) {
      const auto& v = member(f, lf, p, key);
      if (!v.is_number_integer() || v.get<int64_t>() < std::numeric_limits<int>::min() ||
          v.get<int64_t>() > std::numeric_limits<int>::max())
        f.fail(p + "." + key, "expected an integer");
      return static_cast<int>(v.get<int64_t>());
    };
    L.np = size("np");
    L.nw = size("nw");
    L.ne = size("ne");
    L.order = size("order");
    if (auto bad = learning_flames_size_problem(L.np, L.nw, L.ne, L.order))
      f.fail(bad->field.empty() ? p : p + "." + bad->field, bad->problem);
    L.width = get_int(f, lf, p, "width", 1, kMaxModelSide);
    L.height = get_int(f, lf, p, "height", 1, kMaxModelSide);
    L.frames = get_int(f, lf, p, "frames", 1, 1 << 24);
    L.base_y = static_cast<float>(get_num(f, lf, p, "base_y", -1e6, 1e6));
    L.span = static_cast<float>(get_num(f, lf, p, "span", 0.1, 100));
    L.dim = L.np + L.nw + 1 + L.ne;
    if (L.frames < L.order)
      f.fail(p + ".frames", "expected at least order = " + std::to_string(L.order) +
                                " training frames, got " + std::to_string(L.frames));
    L.mean = quantised(f, "lf.mean", 1, L.width, L.height);
    L.eigen = quantised(f, "lf.eigen", L.ne, L.width, L.height);
    L.params = f.require("lf.params", DType::kF32, {L.frames, L.dim}).view<float>();
    L.A = f.require("arp.A", DType::kF32, {L.order, L.dim, L.dim}).view<float>();
    L.d = f.require("arp.d", DType::kF32, {L.dim}).view<float>();
    L.B = f.require("arp.B", DType::kF32, {L.dim, L.dim}).view<float>();
    require_finite(f, "lf.params", L.params);
    require_finite(f, "arp.A", L.A);
    require_finite(f, "arp.d", L.d);
    require_finite(f, "arp.B", L.B);
    require_visible(f, "lf.mean", L.mean);
    if (std::all_of(L.B.begin(), L.B.end(), [](float b) { return b == 0.0f; }))
      f.fail("tensor arp.B",
             "expected some noise (all zero): the process would settle and the flame stand still");
    // The player keeps each parameter near its training range: one range of
    // nothing everywhere plays one pose for ever.
    bool moves = false;
    for (size_t i = static_cast<size_t>(L.dim); i < L.params.size() && !moves; ++i)
      moves = L.params[i] != L.params[i % static_cast<size_t>(L.dim)];
    if (!moves)
      f.fail("tensor lf.params", "expected training states that differ (all " +
                                     std::to_string(L.frames) +
                                     " are the same): the flame would stand still");
    m.has_learning_flames = true;
  }
  m.file_ = std::move(file);
  return m;
}

int FlameModel::clip_of(int frame) const {
  for (size_t i = 0; i < clips.size(); ++i)
    if (frame >= clips[i].first && frame < clips[i].first + clips[i].count)
      return static_cast<int>(i);
  return -1;
}

size_t FlameModel::give_back_image_pages() const {
  const auto bytes_of = [](const QuantisedImages& q) {
    return q.pixels() * static_cast<size_t>(q.count) * dtype_size(q.dtype);
  };
  size_t given = 0;
  for (const QuantisedImages* q : {&mean, &eigen, &flames.mean, &flames.eigen})
    if (q->data) given += file_.give_back_pages(q->data, bytes_of(*q));
  return given;
}

void FlameModel::reconstruct(std::span<const float> w, std::span<float> out) const {
  const size_t n = mean.pixels();
  const int e = std::min(static_cast<int>(w.size()), components());
  for (size_t p = 0; p < n; ++p) out[p] = mean.value(0, p);
  for (int k = 0; k < e; ++k) {
    if (w[k] == 0.0f) continue;
    const float a = w[k] * eigen.scale[k], b = w[k] * eigen.offset[k];
    for (size_t p = 0; p < n; ++p) out[p] += a * static_cast<float>(eigen.raw(k, p)) + b;
  }
}

}  // namespace candela::model
