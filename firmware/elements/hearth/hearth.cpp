#include "elements/hearth/hearth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/flicker.h"
#include "core/random.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "scene/params.h"

namespace candela {
namespace {

constexpr int kMaxLogs = 12;
constexpr int kAround = 18;  // mesh segments around a log
constexpr int kAlong = 6;    // segments along it
constexpr int kLogVec4 = 2;  // per log: from + radius, to + seed

struct LogDesc {
  Vec3 from, to;
  float radius = 0.05f;
};

struct HearthSettings {
  float width = 0.9f, depth = 0.4f;  // the ember bed, metres
  std::vector<LogDesc> logs;
  Vec3 bark{0.23f, 0.14f, 0.09f};
  Vec3 light{1.0f, 0.55f, 0.22f};
  float light_strength = 1.0f;
  Vec3 light_at{0, 0.25f, 0};  // where the firelight comes from, relative to position
  float embers = 1.0f;         // ember glow strength
};

// A pile that reads as a fire's logs: two back logs and a front log lying
// across the bed, and two leaning in from the sides, a little different for
// every seed. The front log comes last: it is drawn after the flames.
std::vector<LogDesc> default_logs(int count, float width, float depth, float radius,
                                  uint64_t seed) {
  Pcg32 rng(seed, 0x6c6f6773);
  const auto jitter = [&](float amount) {
    return (static_cast<float>(rng.unit().to_double()) * 2 - 1) * amount;
  };
  const float hw = width * 0.5f, hd = depth * 0.5f;
  const LogDesc pattern[] = {
      {{-hw * 0.95f, radius, -hd * 0.45f}, {hw * 0.9f, radius, -hd * 0.6f}, radius * 1.15f},
      {{-hw * 0.85f, radius, hd * 0.35f}, {hw * 0.95f, radius * 1.1f, hd * 0.5f}, radius},
      {{-hw * 0.75f, radius * 0.9f, -hd * 0.1f},
       {hw * 0.15f, radius * 2.7f, -hd * 0.25f},
       radius * 0.85f},
      {{hw * 0.8f, radius * 0.9f, hd * 0.1f},
       {-hw * 0.1f, radius * 2.6f, -hd * 0.05f},
       radius * 0.8f},
      {{-hw * 0.3f, radius * 0.8f, hd * 0.95f},
       {hw * 0.45f, radius * 0.8f, hd * 0.8f},
       radius * 0.7f},
      {{-hw * 0.2f, radius * 2.2f, -hd * 0.9f},
       {hw * 0.6f, radius * 2.9f, -hd * 0.5f},
       radius * 0.75f},
  };
  std::vector<LogDesc> out;
  for (int i = 0; i < count; ++i) {
    LogDesc d = pattern[static_cast<size_t>(i) % std::size(pattern)];
    if (i >= static_cast<int>(std::size(pattern))) {  // more logs: further along the pile
      const float shift = (i / static_cast<int>(std::size(pattern))) * radius * 2.2f;
      d.from.y += shift, d.to.y += shift;
    }
    d.from.x += jitter(hw * 0.08f), d.to.x += jitter(hw * 0.08f);
    d.from.z += jitter(hd * 0.12f), d.to.z += jitter(hd * 0.12f);
    d.radius *= 1.0f + jitter(0.12f);
    out.push_back(d);
  }
  return out;
}

// The log mesh in its own coordinates: (along 0..1, angle 0..1, cap) per
// vertex; cap -1/+1 marks the end discs (angle then is the rim point, and a
// centre vertex has along < 0 or > 1). The vertex shader places it.
std::vector<float> log_mesh() {
  std::vector<float> v;
  const auto put = [&](float along, float around, float cap) {
    v.insert(v.end(), {along, around, cap});
  };
  for (int j = 0; j < kAlong; ++j)
    for (int i = 0; i < kAround; ++i) {
      const float a0 = static_cast<float>(j) / kAlong, a1 = static_cast<float>(j + 1) / kAlong;
      const float r0 = static_cast<float>(i) / kAround, r1 = static_cast<float>(i + 1) / kAround;
      put(a0, r0, 0), put(a1, r0, 0), put(a1, r1, 0);
      put(a0, r0, 0), put(a1, r1, 0), put(a0, r1, 0);
    }
  for (int end = 0; end < 2; ++end)
    for (int i = 0; i < kAround; ++i) {
      const float r0 = static_cast<float>(i) / kAround, r1 = static_cast<float>(i + 1) / kAround;
      const float cap = end ? 1.0f : -1.0f, along = static_cast<float>(end);
      put(along, 0, cap * 2), put(along, r0, cap), put(along, r1, cap);  // |cap| 2: centre
    }
  return v;
}

class Hearth final : public Element {
 public:
  Hearth(const HearthSettings& s, Vec3 position, uint64_t seed)
      : s_(s), position_(position), light_(seed), seed_(static_cast<float>(seed % 1000) * 0.37f) {
    logs_prog_ = Program::from_library("hearth_log.vert", "hearth_log.frag");
    bed_prog_ = Program::from_library("floor_quad.vert", "hearth_bed.frag");
    const auto u = [&](const Program& p, const char* n) { return p.uniform(n); };
    ul_ = {
        u(logs_prog_, "u_view_projection"), u(logs_prog_, "u_camera"), u(logs_prog_, "u_light_pos"),
        u(logs_prog_, "u_light"),           u(logs_prog_, "u_bark"),   u(logs_prog_, "u_time")};
    ub_ = {u(bed_prog_, "u_view_projection"),
           u(bed_prog_, "u_centre"),
           u(bed_prog_, "u_half"),
           u(bed_prog_, "u_time"),
           u(bed_prog_, "u_light"),
           u(bed_prog_, "u_seed"),
           u(bed_prog_, "u_embers")};

    // In front: a log whose middle lies in the front fifth of the bed.
    const auto behind = [&](const LogDesc& d) {
      return (d.from.z + d.to.z) * 0.5f < 0.3f * s_.depth;
    };
    back_count_ = static_cast<GLsizei>(
        std::stable_partition(s_.logs.begin(), s_.logs.end(), behind) - s_.logs.begin());
    std::vector<float> inst;
    for (const LogDesc& d : s_.logs) {
      const Vec3 a = d.from + position_, b = d.to + position_;
      inst.insert(inst.end(), {a.x, a.y, a.z, d.radius, b.x, b.y, b.z,
                               static_cast<float>(inst.size() / 8) * 1.618f + seed_});
    }
    log_count_ = static_cast<GLsizei>(s_.logs.size());
    const std::vector<float> mesh = log_mesh();
    vertex_count_ = static_cast<GLsizei>(mesh.size() / 3);
    vao_ = make_vertex_array();
    glBindVertexArray(vao_.get());
    mesh_vbo_ = make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.size() * sizeof(float)), mesh.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    inst_vbo_ = make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, inst_vbo_.get());
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(std::max<size_t>(1, inst.size()) * sizeof(float)),
                 inst.empty() ? nullptr : inst.data(), GL_STATIC_DRAW);
    for (int k = 0; k < kLogVec4; ++k) {
      const auto loc = static_cast<GLuint>(1 + k);
      glEnableVertexAttribArray(loc);
      glVertexAttribPointer(
          loc, 4, GL_FLOAT, GL_FALSE, kLogVec4 * 4 * sizeof(float),
          reinterpret_cast<const void*>(static_cast<uintptr_t>(k) * 4 * sizeof(float)));
      glVertexAttribDivisor(loc, 1);
    }
    bed_vao_ = make_vertex_array();
    glBindVertexArray(0);
  }

  void update(const StepContext& step) override {
    time_ = step.time;
    flicker_ = light_.at(step.time);
  }

  // The bed and the logs behind or among the flames go in the body pass,
  // before any fire element's flame pass; logs at the front of the bed go in
  // the overlay pass, after the flames, so they hide the flames' feet as
  // front logs do (a fire element draws no depth).
  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass == DrawPass::kOverlay) {
      draw_logs(f, back_count_, log_count_ - back_count_);
      return;
    }
    if (pass != DrawPass::kBody) return;
    const float t = static_cast<float>(time_.to_double());
    const Vec3 lc = s_.light * (s_.light_strength * flicker_.to_float());
    // The bed first, flat on the floor; then the logs over it, depth-tested
    // against each other.
    if (s_.embers > 0) {
      bed_prog_.use();
      glUniformMatrix4fv(ub_[0], 1, GL_FALSE, f.view_projection.m);
      glUniform3f(ub_[1], position_.x, position_.y + 0.001f, position_.z);
      glUniform2f(ub_[2], s_.width * 0.5f, s_.depth * 0.5f);
      glUniform1f(ub_[3], t);
      glUniform3f(ub_[4], lc.x, lc.y, lc.z);
      glUniform1f(ub_[5], seed_);
      glUniform1f(ub_[6], s_.embers);
      glDisable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      glBindVertexArray(bed_vao_.get());
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
      glDisable(GL_BLEND);
      glDepthMask(GL_TRUE);
    }
    draw_logs(f, 0, back_count_);
  }

 private:
  void draw_logs(const FrameContext& f, GLsizei first, GLsizei count) {
    if (count <= 0) return;
    const float light = s_.light_strength * flicker_.to_float();
    const Vec3 lc = s_.light * light;
    const float t = static_cast<float>(time_.to_double());
    logs_prog_.use();
    glUniformMatrix4fv(ul_[0], 1, GL_FALSE, f.view_projection.m);
    glUniform3f(ul_[1], f.camera_position.x, f.camera_position.y, f.camera_position.z);
    const Vec3 lp = position_ + s_.light_at;
    glUniform3f(ul_[2], lp.x, lp.y, lp.z);
    glUniform4f(ul_[3], lc.x, lc.y, lc.z, s_.embers);
    glUniform3f(ul_[4], s_.bark.x, s_.bark.y, s_.bark.z);
    glUniform1f(ul_[5], t);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glBindVertexArray(vao_.get());
    // Instances [first, first + count): point the per-log attributes there.
    glBindBuffer(GL_ARRAY_BUFFER, inst_vbo_.get());
    for (int k = 0; k < kLogVec4; ++k)
      glVertexAttribPointer(
          static_cast<GLuint>(1 + k), 4, GL_FLOAT, GL_FALSE, kLogVec4 * 4 * sizeof(float),
          reinterpret_cast<const void*>((static_cast<uintptr_t>(first) * kLogVec4 + k) * 4 *
                                        sizeof(float)));
    glDrawArraysInstanced(GL_TRIANGLES, 0, vertex_count_, count);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
  }

  HearthSettings s_;
  Vec3 position_;
  Flicker light_;
  float seed_;
  Fixed time_, flicker_ = Fixed::from_int(1);
  Program logs_prog_, bed_prog_;
  VertexArray vao_, bed_vao_;
  Buffer mesh_vbo_, inst_vbo_;
  GLsizei vertex_count_ = 0, log_count_ = 0;
  std::array<GLint, 6> ul_{};
  GLsizei back_count_ = 0;  // logs [0, back_count_) behind the flames, the rest in front
  std::array<GLint, 7> ub_{};
};

class HearthSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext& context) const override {
    HearthSettings s = settings;
    if (!explicit_logs)
      s.logs = default_logs(log_count, s.width, s.depth, log_radius, context.seed);
    return std::make_unique<Hearth>(s, position, context.seed);
  }
  HearthSettings settings;
  bool explicit_logs = false;
  int log_count = 5;
  float log_radius = 0.05f;
};

std::unique_ptr<ElementSpec> parse(ParamReader& r) {
  auto spec = std::make_unique<HearthSpec>();
  HearthSettings& s = spec->settings;
  s.width = static_cast<float>(r.number("width", s.width, 0.05, 20));
  s.depth = static_cast<float>(r.number("depth", s.depth, 0.05, 20));
  spec->log_count = static_cast<int>(r.integer("logs", spec->log_count, 0, kMaxLogs));
  spec->log_radius = static_cast<float>(r.number("log_radius", 0.055 * s.width / 0.9, 0.005, 2));
  s.bark = r.color("bark", s.bark);
  s.light = r.color("light", s.light);
  s.light_strength = static_cast<float>(r.number("light_strength", s.light_strength, 0, 10));
  s.light_at = r.vec3("light_at", {0, 0.3f * s.width, 0});
  s.embers = static_cast<float>(r.number("embers", s.embers, 0, 10));
  auto logs = r.table_array("log");
  if (logs.size() > static_cast<size_t>(kMaxLogs))
    r.fail("log", "expected at most " + std::to_string(kMaxLogs) + " [[log]] tables, got " +
                      std::to_string(logs.size()));
  for (ParamReader& l : logs) {
    LogDesc d;
    d.from = l.vec3("from", {-0.3f, 0.05f, 0});
    d.to = l.vec3("to", {0.3f, 0.05f, 0});
    d.radius = static_cast<float>(l.number("radius", 0.05, 0.005, 2));
    if (length(d.to - d.from) < d.radius)
      l.fail("to", "expected a log longer than its radius (from and to are too close)");
    l.finish();
    s.logs.push_back(d);
  }
  spec->explicit_logs = !logs.empty();
  r.finish();
  return spec;
}

}  // namespace

const ElementKind& hearth_kind() {
  static const ElementKind kind{
      "hearth", "logs, a bed of glowing embers and the fire's flickering light on them", parse};
  return kind;
}

}  // namespace candela
