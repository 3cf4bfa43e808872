#include "elements/hearth/hearth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/flicker.h"
#include "core/random.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"
#include "params/params.h"

namespace candela {
namespace {

constexpr int kMaxLogs = 12;
constexpr int kAround = 18;  // mesh segments around a log
constexpr int kAlong = 16;   // segments along it: enough for a log's bends and knots
constexpr int kLogVec4 = 2;  // per log: from + radius, to + seed
// The log cache's targets: colour, cracks, relief normal. The firebox's
// cache shares the first two and has no normal.
constexpr GLenum kLogTargets[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
constexpr GLenum kFireboxTargets[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_NONE};

struct LogDesc {
  Vec3 from, to;
  float radius = 0.05f;
};

// The firebox the fire burns in: a back wall, two sides splayed towards the
// opening and a floor, all old firebrick, lit by the fire. width 0: none.
struct FireboxDesc {
  float width = 0;           // the opening, at the front of the bed (m)
  float height = 0.8f;       // the walls' height (m)
  float depth = 0.55f;       // from the opening to the back wall (m)
  float back_width = 0.62f;  // the back wall's width, of the opening's
  Vec3 brick{0.45f, 0.22f, 0.14f};
  float soot = 1.0f;  // how black the back wall is above the fire (0: clean brick)
};

struct HearthSettings {
  float width = 0.9f, depth = 0.4f;  // the ember bed, metres
  std::vector<LogDesc> logs;
  Vec3 bark{0.23f, 0.14f, 0.09f};
  Vec3 light{1.0f, 0.55f, 0.22f};
  float light_strength = 1.0f;
  Vec3 light_at{0, 0.25f, 0};  // where the firelight comes from, relative to position
  float embers = 1.0f;         // ember glow strength
  FireboxDesc firebox;
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
      // Wound as the side is (counter-clockwise seen from outside), so that
      // back faces can be culled.
      if (end)
        put(along, 0, cap * 2), put(along, r1, cap), put(along, r0, cap);  // |cap| 2: centre
      else
        put(along, 0, cap * 2), put(along, r0, cap), put(along, r1, cap);
    }
  return v;
}

// The firebox's surfaces as triangles around `origin` (the hearth's
// position): per vertex its position, its coordinates on the surface in metres (the
// sides continue the back wall's, so the courses of bricks run round the
// corners), its normal (into the box) and which surface (0 back, 1 side, 2 floor).
std::vector<float> firebox_mesh(const FireboxDesc& b, float bed_depth, Vec3 origin) {
  std::vector<float> v;
  const float zf = bed_depth * 0.5f + 0.06f, zb = zf - b.depth;
  const float fw = b.width * 0.5f, bw = fw * b.back_width, h = b.height;
  const auto quad = [&](const std::array<Vec3, 4>& p, const std::array<std::array<float, 2>, 4>& uv,
                        Vec3 n, float surface) {
    for (int i : {0, 1, 2, 0, 2, 3}) {
      const Vec3 at = p[i] + origin;
      v.insert(v.end(), {at.x, at.y, at.z, uv[i][0], uv[i][1], n.x, n.y, n.z, surface});
    }
  };
  quad({Vec3{-bw, 0, zb}, Vec3{bw, 0, zb}, Vec3{bw, h, zb}, Vec3{-bw, h, zb}},
       {{{-bw, 0}, {bw, 0}, {bw, h}, {-bw, h}}}, Vec3{0, 0, 1}, 0);
  const float side = std::hypot(fw - bw, zf - zb);
  const float nx = (zf - zb) / side, nz = (fw - bw) / side;
  quad({Vec3{-fw, 0, zf}, Vec3{-bw, 0, zb}, Vec3{-bw, h, zb}, Vec3{-fw, h, zf}},
       {{{-bw - side, 0}, {-bw, 0}, {-bw, h}, {-bw - side, h}}}, Vec3{nx, 0, nz}, 1);
  quad({Vec3{bw, 0, zb}, Vec3{fw, 0, zf}, Vec3{fw, h, zf}, Vec3{bw, h, zb}},
       {{{bw, 0}, {bw + side, 0}, {bw + side, h}, {bw, h}}}, Vec3{-nx, 0, nz}, 1);
  quad({Vec3{-bw, 0, zb}, Vec3{-fw, 0, zf}, Vec3{fw, 0, zf}, Vec3{bw, 0, zb}},
       {{{-bw, zb}, {-fw, zf}, {fw, zf}, {bw, zb}}}, Vec3{0, 1, 0}, 2);
  return v;
}

class Hearth final : public Element {
 public:
  Hearth(const HearthSettings& s, Vec3 position, uint64_t seed)
      : s_(s), position_(position), light_(seed), seed_(static_cast<float>(seed % 1000) * 0.37f) {
    logs_cache_prog_ =
        Program::from_library("hearth_log.vert", {"value_noise.frag", "hearth_log.frag"});
    logs_prog_ =
        Program::from_library("hearth_log.vert", {"value_noise.frag", "hearth_log_shade.frag"});
    bed_cache_prog_ =
        Program::from_library("floor_quad.vert", {"value_noise.frag", "hearth_bed.frag"});
    bed_prog_ =
        Program::from_library("floor_quad.vert", {"value_noise.frag", "hearth_bed_shade.frag"});
    if (s_.firebox.width > 0) make_firebox();
    const auto u = [&](const Program& p, const char* n) { return p.uniform(n); };
    ulc_ = {u(logs_cache_prog_, "u_view_projection"), u(logs_cache_prog_, "u_light_pos"),
            u(logs_cache_prog_, "u_bark")};
    ul_ = {u(logs_prog_, "u_view_projection"), u(logs_prog_, "u_light_pos"),
           u(logs_prog_, "u_light"),           u(logs_prog_, "u_time"),
           u(logs_prog_, "u_colour"),          u(logs_prog_, "u_crack"),
           u(logs_prog_, "u_origin"),          u(logs_prog_, "u_camera"),
           u(logs_prog_, "u_normal")};
    ubc_ = {u(bed_cache_prog_, "u_view_projection"), u(bed_cache_prog_, "u_centre"),
            u(bed_cache_prog_, "u_half"), u(bed_cache_prog_, "u_seed")};
    ub_ = {u(bed_prog_, "u_view_projection"),
           u(bed_prog_, "u_centre"),
           u(bed_prog_, "u_half"),
           u(bed_prog_, "u_time"),
           u(bed_prog_, "u_light"),
           u(bed_prog_, "u_embers"),
           u(bed_prog_, "u_cache"),
           u(bed_prog_, "u_origin")};

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
    // The fire's right half flickers on its own: the same signal, 1.7 s away.
    if (firebox_vertices_ > 0) right_flicker_ = light_.at(step.time + Fixed::from_ratio(17, 10));
  }
  void hash_state(StateHash& hash) const override {
    hash.add(time_);
    hash.add(flicker_);
    if (firebox_vertices_ > 0) hash.add(right_flicker_);
  }

  // The embers and logs are the fire's body: its roar follows the
  // firelight's flicker, and it crackles more as the light flares (0 at the
  // flicker's low 0.55, about 1 at its mean, 1.8 at its peak 1.35).
  void add_sound_cue(SoundCue& cue) const override {
    cue.fire += flicker_;
    cue.activity += clamp((flicker_ - Fixed::from_ratio(55, 100)) * Fixed::from_ratio(9, 4),
                          Fixed{}, Fixed::from_int(2));
  }

  // The bed and the logs behind or among the flames go in the body pass,
  // before any fire element's flame pass; logs at the front of the bed go in
  // the overlay pass, after the flames, so they hide the flames' feet as
  // front logs do (a fire element draws no depth).
  // The cache of what the view alone decides (refresh_cache), when the view
  // or the screen's size changed.
  void prepare(const FrameContext& f) override { refresh_cache(f); }

  // The bed and the logs (hearth_log.vert's knobbly radius is at most 1.12
  // times the log's); a firebox fills the view, so no bound then.
  bool drawn_bounds(const FrameContext&, Box3& box) const override {
    if (firebox_vertices_ > 0) return false;
    if (s_.embers > 0) {
      const Vec3 c = bed_centre();
      box.add(c + Vec3{-s_.width * 0.5f, 0, -s_.depth * 0.5f});
      box.add(c + Vec3{s_.width * 0.5f, 0, s_.depth * 0.5f});
    }
    for (const LogDesc& d : s_.logs) {
      box.add(d.from + position_, d.radius * 1.15f);
      box.add(d.to + position_, d.radius * 1.15f);
    }
    return true;
  }

  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass == DrawPass::kOverlay) {
      draw_logs(f, back_count_, log_count_ - back_count_);
      return;
    }
    if (pass != DrawPass::kBody) return;
    const float t = static_cast<float>(time_.to_double());
    const Vec3 lc = s_.light * (s_.light_strength * flicker_.to_float());
    // The firebox behind everything; the bed flat on its floor; then the
    // logs over it, depth-tested against each other.
    draw_firebox(f);
    if (s_.embers > 0) {
      bed_prog_.use();
      set_bed_quad(f, ub_[0], ub_[1], ub_[2]);
      glUniform1f(ub_[3], t);
      glUniform3f(ub_[4], lc.x, lc.y, lc.z);
      glUniform1f(ub_[5], s_.embers);
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, bed_tex_.get());
      glUniform1i(ub_[6], 0);
      glUniform2i(ub_[7], cache_key_.viewport[0], cache_key_.viewport[1]);
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
  // What the cache was rendered for: it holds per screen pixel what does not
  // change while the view stays put.
  struct CacheKey {
    std::array<float, 16> view_projection{};
    std::array<GLint, 4> viewport{};
    bool operator==(const CacheKey&) const = default;
  };

  // The expensive part of the hearth (the bark, char and crack noise of the
  // logs, the ember bed's cell search) depends only on the view, so it is
  // rendered into screen-sized textures once, and again only when the view or
  // the viewport changes; every frame then draws the same geometry with
  // shaders that read that cache at their pixel and add what moves (the
  // firelight's flicker, the embers' and cracks' pulses). The geometry and
  // its depth are drawn as before, so the logs hide and are hidden exactly as
  // they were.
  void refresh_cache(const FrameContext& f) {
    CacheKey key;
    std::copy(std::begin(f.view_projection.m), std::end(f.view_projection.m),
              key.view_projection.begin());
    key.viewport = {0, 0, f.width, f.height};  // the draw passes' (scene/element.h)
    if (cache_valid_ && key == cache_key_) return;
    const int w = std::max(1, key.viewport[2]), h = std::max(1, key.viewport[3]);
    if (!cache_valid_ || w != cache_key_.viewport[2] || h != cache_key_.viewport[3])
      make_cache(w, h);
    cache_key_ = key;
    cache_valid_ = true;
    glViewport(0, 0, w, h);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    if (s_.embers > 0) {
      glBindFramebuffer(GL_FRAMEBUFFER, bed_fbo_.get());
      glClearColor(0, 0, 0, 0);
      glClear(GL_COLOR_BUFFER_BIT);
      glDisable(GL_DEPTH_TEST);
      bed_cache_prog_.use();
      set_bed_quad(f, ubc_[0], ubc_[1], ubc_[2]);
      glUniform1f(ubc_[3], seed_);
      glBindVertexArray(bed_vao_.get());
      glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, logs_fbo_.get());
    glDrawBuffers(3, kLogTargets);
    glClearColor(0, 0, 0, 0);
    glDepthMask(GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (firebox_vertices_ > 0) {
      // The firebox shares the logs' cache: the logs, drawn after it, hide it where they stand.
      glDrawBuffers(3, kFireboxTargets);
      firebox_cache_prog_.use();
      glUniformMatrix4fv(ufc_[0], 1, GL_FALSE, f.view_projection.m);
      const Vec3 lp = light_pos();
      glUniform3f(ufc_[1], lp.x, lp.y, lp.z);
      glUniform1f(ufc_[2], 0.3f * s_.width);
      const Vec3 lc = s_.light * s_.light_strength;
      glUniform3f(ufc_[3], lc.x, lc.y, lc.z);
      glUniform3f(ufc_[4], s_.firebox.brick.x, s_.firebox.brick.y, s_.firebox.brick.z);
      glUniform1f(ufc_[5], s_.firebox.soot);
      glUniform1f(ufc_[6], seed_ * 0.013f);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glBindVertexArray(firebox_vao_.get());
      glDrawArrays(GL_TRIANGLES, 0, firebox_vertices_);
      glDisable(GL_DEPTH_TEST);
    }
    if (log_count_ > 0) {
      glDrawBuffers(3, kLogTargets);
      logs_cache_prog_.use();
      glUniformMatrix4fv(ulc_[0], 1, GL_FALSE, f.view_projection.m);
      const Vec3 lp = light_pos();
      glUniform3f(ulc_[1], lp.x, lp.y, lp.z);
      glUniform3f(ulc_[2], s_.bark.x, s_.bark.y, s_.bark.z);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      bind_log_instances(0);
      cull_back_faces(true);
      glDrawArraysInstanced(GL_TRIANGLES, 0, vertex_count_, log_count_);
      cull_back_faces(false);
      glDisable(GL_DEPTH_TEST);
    }
    glBindVertexArray(0);
  }

  void make_firebox() {
    firebox_cache_prog_ =
        Program::from_library("hearth_firebox.vert", {"value_noise.frag", "hearth_firebox.frag"});
    firebox_prog_ = Program::from_library("hearth_firebox.vert", "hearth_firebox_shade.frag");
    const auto u = [&](const Program& p, const char* n) { return p.uniform(n); };
    ufc_ = {u(firebox_cache_prog_, "u_view_projection"), u(firebox_cache_prog_, "u_light_pos"),
            u(firebox_cache_prog_, "u_spread"),          u(firebox_cache_prog_, "u_light"),
            u(firebox_cache_prog_, "u_brick"),           u(firebox_cache_prog_, "u_soot"),
            u(firebox_cache_prog_, "u_noise_seed")};
    uf_ = {u(firebox_prog_, "u_view_projection"), u(firebox_prog_, "u_flicker"),
           u(firebox_prog_, "u_cache"), u(firebox_prog_, "u_origin")};
    const std::vector<float> mesh = firebox_mesh(s_.firebox, s_.depth, position_);
    firebox_vertices_ = static_cast<GLsizei>(mesh.size() / 9);
    firebox_vao_ = make_vertex_array();
    glBindVertexArray(firebox_vao_.get());
    firebox_vbo_ = make_buffer();
    glBindBuffer(GL_ARRAY_BUFFER, firebox_vbo_.get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.size() * sizeof(float)), mesh.data(),
                 GL_STATIC_DRAW);
    const int offsets[] = {0, 3, 5, 8}, sizes[] = {3, 2, 3, 1};
    for (GLuint k = 0; k < 4; ++k) {
      glEnableVertexAttribArray(k);
      glVertexAttribPointer(
          k, sizes[k], GL_FLOAT, GL_FALSE, 9 * sizeof(float),
          reinterpret_cast<const void*>(static_cast<uintptr_t>(offsets[k]) * sizeof(float)));
    }
    glBindVertexArray(0);
  }

  // Per frame the firebox only reads its cache and flickers it. It is drawn
  // first and everything in the box is in front of it, so it needs no depth
  // (depth tests and writes were a third of its cost on llvmpipe).
  void draw_firebox(const FrameContext& f) {
    if (firebox_vertices_ <= 0 || !cache_valid_) return;
    const float k = s_.light_strength > 0 ? 1.0f : 0.0f;
    firebox_prog_.use();
    glUniformMatrix4fv(uf_[0], 1, GL_FALSE, f.view_projection.m);
    glUniform2f(uf_[1], k * flicker_.to_float(), k * right_flicker_.to_float());
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, log_crack_tex_.get());
    glUniform1i(uf_[2], 0);
    glUniform2i(uf_[3], cache_key_.viewport[0], cache_key_.viewport[1]);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(firebox_vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, firebox_vertices_);
    glBindVertexArray(0);
  }

  // Where the firelight comes from, in the scene.
  Vec3 light_pos() const { return position_ + s_.light_at; }

  static Texture make_cache_texture(GLenum format, int w, int h) {
    Texture t = make_texture();
    glBindTexture(GL_TEXTURE_2D, t.get());
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
  }

  void make_cache(int w, int h) {
    // The logs' colour in 10 bits a channel (it is multiplied up by the
    // firelight, 8 would show steps); the crack glow and the bed's heat are
    // split over two 8-bit channels by their shaders.
    log_colour_tex_ = make_cache_texture(GL_RGB10_A2, w, h);
    log_crack_tex_ = make_cache_texture(GL_RGBA8, w, h);
    logs_fbo_ = make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, logs_fbo_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           log_colour_tex_.get(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D,
                           log_crack_tex_.get(), 0);
    // The normal with the bark's relief, 8 bits a component (enough for light).
    log_normal_tex_ = make_cache_texture(GL_RGBA8, w, h);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D,
                           log_normal_tex_.get(), 0);
    logs_depth_ = attach_depth_buffer(w, h);
    glDrawBuffers(3, kLogTargets);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("hearth: log cache framebuffer incomplete");
    bed_tex_ = make_cache_texture(GL_RGBA8, w, h);
    bed_fbo_ = make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, bed_fbo_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, bed_tex_.get(), 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("hearth: ember cache framebuffer incomplete");
  }

  // The ember bed's quad (floor_quad.vert) lies just above the floor.
  Vec3 bed_centre() const { return {position_.x, position_.y + 0.001f, position_.z}; }

  void set_bed_quad(const FrameContext& f, GLint vp, GLint centre, GLint half) const {
    glUniformMatrix4fv(vp, 1, GL_FALSE, f.view_projection.m);
    const Vec3 c = bed_centre();
    glUniform3f(centre, c.x, c.y, c.z);
    glUniform2f(half, s_.width * 0.5f, s_.depth * 0.5f);
  }

  // A log is a closed mesh wound counter-clockwise seen from outside
  // (log_mesh): its back faces always lie behind its front faces, so they
  // are culled rather than shaded and then hidden by the depth test (on a
  // software rasteriser that was a third of the logs' cost).
  static void cull_back_faces(bool on) {
    if (!on) {
      glDisable(GL_CULL_FACE);
      return;
    }
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  }

  // Binds the log VAO with the per-log attributes starting at instance `first`.
  void bind_log_instances(GLsizei first) const {
    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, inst_vbo_.get());
    for (int k = 0; k < kLogVec4; ++k)
      glVertexAttribPointer(
          static_cast<GLuint>(1 + k), 4, GL_FLOAT, GL_FALSE, kLogVec4 * 4 * sizeof(float),
          reinterpret_cast<const void*>((static_cast<uintptr_t>(first) * kLogVec4 + k) * 4 *
                                        sizeof(float)));
  }

  void draw_logs(const FrameContext& f, GLsizei first, GLsizei count) {
    if (count <= 0 || !cache_valid_) return;
    const float light = s_.light_strength * flicker_.to_float();
    const Vec3 lc = s_.light * light;
    const float t = static_cast<float>(time_.to_double());
    logs_prog_.use();
    glUniformMatrix4fv(ul_[0], 1, GL_FALSE, f.view_projection.m);
    const Vec3 lp = light_pos();
    glUniform3f(ul_[1], lp.x, lp.y, lp.z);
    glUniform4f(ul_[2], lc.x, lc.y, lc.z, s_.embers);
    glUniform1f(ul_[3], t);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, log_colour_tex_.get());
    glUniform1i(ul_[4], 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, log_crack_tex_.get());
    glUniform1i(ul_[5], 1);
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D, log_normal_tex_.get());
    glUniform1i(ul_[8], 2);
    glActiveTexture(GL_TEXTURE0);
    glUniform2i(ul_[6], cache_key_.viewport[0], cache_key_.viewport[1]);
    glUniform3f(ul_[7], f.camera_position.x, f.camera_position.y, f.camera_position.z);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    // Instances [first, first + count).
    bind_log_instances(first);
    cull_back_faces(true);
    glDrawArraysInstanced(GL_TRIANGLES, 0, vertex_count_, count);
    cull_back_faces(false);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
  }

  HearthSettings s_;
  Vec3 position_;
  Flicker light_;
  float seed_;
  Fixed time_, flicker_ = Fixed::from_int(1);
  Program logs_cache_prog_, logs_prog_, bed_cache_prog_, bed_prog_;
  VertexArray vao_, bed_vao_;
  Buffer mesh_vbo_, inst_vbo_;
  GLsizei vertex_count_ = 0, log_count_ = 0;
  std::array<GLint, 3> ulc_{};
  std::array<GLint, 9> ul_{};
  GLsizei back_count_ = 0;  // logs [0, back_count_) behind the flames, the rest in front
  std::array<GLint, 4> ubc_{};
  std::array<GLint, 8> ub_{};
  // The firebox (absent when its width is 0).
  Program firebox_cache_prog_, firebox_prog_;
  VertexArray firebox_vao_;
  Buffer firebox_vbo_;
  GLsizei firebox_vertices_ = 0;
  std::array<GLint, 7> ufc_{};
  std::array<GLint, 4> uf_{};
  Fixed right_flicker_ = Fixed::from_int(1);
  // The cache (refresh_cache): per screen pixel, what the view alone decides.
  Texture log_colour_tex_, log_crack_tex_, log_normal_tex_, bed_tex_;
  Renderbuffer logs_depth_;
  Framebuffer logs_fbo_, bed_fbo_;
  CacheKey cache_key_;
  bool cache_valid_ = false;
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
  if (r.has("firebox")) {
    ParamReader b = r.table("firebox");
    FireboxDesc& fb = s.firebox;
    fb.width = static_cast<float>(b.number("width", std::max(1.4 * s.width, 0.3), 0.1, 20));
    fb.height = static_cast<float>(b.number("height", fb.height, 0.1, 10));
    fb.depth = static_cast<float>(b.number("depth", std::max(0.55, s.depth + 0.2), 0.1, 10));
    fb.back_width = static_cast<float>(b.number("back_width", fb.back_width, 0.2, 1));
    fb.brick = b.color("brick", fb.brick);
    fb.soot = static_cast<float>(b.number("soot", fb.soot, 0, 1));
    b.finish();
  }
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
