#include "elements/candle/candles.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/log.h"
#include "core/random.h"
#include "elements/candle/candle_body_mesh.h"
#include "elements/candle/flame_still.h"
#include "elements/candle/flame_warp.h"
#include "gl/instances.h"
#include "gl/program.h"
#include "gl/texture.h"

namespace candela {
namespace {

constexpr int kFlameVec4 = 12;  // per flame instance: 10 lines, anchor, pose
constexpr int kBodyVec4 = 3;
constexpr int kGlowVec4 = 2;
constexpr int kSmokeVec4 = 2;
constexpr float kWickLength = 0.011f;  // metres, scaled by flame_scale

class Candles final : public Element {
 public:
  Candles(const CandlesSpec& spec, const SceneContext& ctx);
  void update(const StepContext& step) override {
    dt_seconds_ = step.dt.to_float();
    for (auto& r : rigs_) r.update(step);
  }
  void prepare(const FrameContext& frame) override;
  void draw(const FrameContext& frame, DrawPass pass) override;
  int candles_lit() const override {
    int n = 0;
    for (const auto& r : rigs_) n += r.state().lit;
    return n;
  }
  // Silent while calm: a puff for each candle that went out this step, a
  // sputter share for each flame clinging to its wick.
  void add_sound_cue(SoundCue& cue) const override {
    int out = 0, stuck = 0, lit = 0;
    Fixed wind;
    for (const auto& r : rigs_) {
      const CandleState& st = r.state();
      out += st.out_steps == 0;
      stuck += st.lit && st.stuck;
      lit += st.lit;
      wind = std::max(wind, st.wind_speed);
    }
    const auto add = [](uint16_t& c, int n) { c = static_cast<uint16_t>(std::min(0xffff, c + n)); };
    add(cue.blowouts, out);
    add(cue.sputters, stuck);
    add(cue.lit, lit);
    cue.wind = std::max(cue.wind, wind);
  }
  void hash_state(StateHash& hash) const override {
    hash.add(static_cast<uint64_t>(rigs_.size()));
    for (const auto& r : rigs_) {
      const CandleState& st = r.state();
      for (uint32_t p : st.phase) hash.add(p);
      for (Fixed v : {st.ax, st.vx, st.az, st.vz, st.lean, st.tilt, st.stretch, st.width,
                      st.strength, st.tip, st.grow, st.wind_speed})
        hash.add(v);
      for (Fixed v : st.turbulence) hash.add(v);
      hash.add(st.out_steps);
      hash.add(st.relight_in);
      hash.add(st.times_out);
      hash.add(st.lit);
      hash.add(st.stuck);
    }
  }

 private:
  std::vector<CandleDesc> desc_;
  std::vector<CandleRig> rigs_;
  std::vector<std::shared_ptr<const NoiseTable>> user_tables_;  // keep alive
  FlameLook look_;
  float aspect_ = 0.5f;
  float smoke_seconds_ = 2.5f;
  float dt_seconds_ = 1.0f / 60;

  Program flame_prog_, body_prog_;
  Billboards glows_, smokes_;
  Texture still_;
  InstancedMesh flames_, bodies_;  // instances filled in prepare(), every frame

  std::vector<uint32_t> order_;  // candles far to near
  Vec3 sorted_for_{1e30f, 0, 0};

  struct FlameUniforms {
    GLint view_projection, camera, src, weights, aspect, base, still;
  } fu_{};
  GLint body_vp_ = -1, body_camera_ = -1;
};

Candles::Candles(const CandlesSpec& spec, const SceneContext& ctx)
    : desc_(spec.candles), look_(spec.look) {
  rigs_.reserve(desc_.size());
  for (size_t i = 0; i < desc_.size(); ++i) {
    CandleDesc& d = desc_[i];
    d.position = d.position + spec.position;
    const uint64_t seed = d.seed ? d.seed : candle_seed(ctx.seed, i);
    rigs_.emplace_back(d.params, look_.layout, WindPosition::from(d.position), seed);
  }
  if (!desc_.empty()) smoke_seconds_ = desc_[0].params.smoke_seconds.to_float();

  // The still: the user's, or the one drawn by code.
  Image still = look_.still ? *look_.still : make_flame_still(256, look_.layout);
  aspect_ = static_cast<float>(still.width) / static_cast<float>(still.height);
  still_ = upload_rgba8(still.width, still.height, still.pixels.data());

  flame_prog_ = Program::from_library("candle_flame.vert", "candle_flame.frag");
  body_prog_ = Program::from_library("candle_body.vert", "candle_body.frag");
  fu_ = {flame_prog_.uniform("u_view_projection"),
         flame_prog_.uniform("u_camera"),
         flame_prog_.uniform("u_src"),
         flame_prog_.uniform("u_weights"),
         flame_prog_.uniform("u_aspect"),
         flame_prog_.uniform("u_base"),
         flame_prog_.uniform("u_still")};
  body_vp_ = body_prog_.uniform("u_view_projection");
  body_camera_ = body_prog_.uniform("u_camera");

  const size_t n = desc_.size();
  order_.resize(n);
  for (size_t i = 0; i < n; ++i) order_[i] = static_cast<uint32_t>(i);

  // Flame: the mesh over the still (source positions) + per-instance lines.
  {
    const auto verts = mesh_vertices(look_.mesh, aspect_);
    std::vector<float> v;
    for (const auto& p : verts)
      v.insert(v.end(), {static_cast<float>(p.x), static_cast<float>(p.y)});
    // Cells where the still is fully transparent stay so however they move:
    // leave them out (llvmpipe's cost is mostly per triangle).
    const int cells = look_.mesh;
    const auto idx = mesh_indices(cells, [&](int ci, int cj) {
      const int x0 = std::max(0, ci * still.width / cells - 1);
      const int x1 = std::min(still.width, (ci + 1) * still.width / cells + 1);
      const int y0 = std::max(0, (cells - 1 - cj) * still.height / cells - 1);
      const int y1 = std::min(still.height, (cells - cj) * still.height / cells + 1);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
          if (still.at(x, y, 3) > 0) return true;
      return false;
    });
    flames_ = InstancedMesh(v, {2}, idx, kFlameVec4, n);
  }
  // Glow: a camera-facing quad per candle.
  glows_ = Billboards("candle_glow.vert", "candle_glow.frag", kGlowVec4, n);
  // Body: one mesh, per-instance placement, wax colour and flame light.
  {
    const BodyMesh m = make_body_mesh(16, 5);
    bodies_ = InstancedMesh(m.vertices, {4, 3}, m.indices, kBodyVec4, n);
  }
  // Smoke wisps of candles that just went out.
  smokes_ = Billboards("candle_smoke.vert", "candle_smoke.frag", kSmokeVec4, n);
  glBindVertexArray(0);
}

// Fills and uploads every instance buffer for this frame.
void Candles::prepare(const FrameContext& frame) {
  if (desc_.empty()) return;
  const Vec3 cam = frame.camera_position;
  if (length(cam - sorted_for_) > 1e-4f) {
    // Far to near, so that blended flames overlap correctly.
    std::sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
      const float da = length(desc_[a].position - cam), db = length(desc_[b].position - cam);
      return da != db ? da > db : a < b;
    });
    sorted_for_ = cam;
  }
  flames_.instances().clear();
  glows_.instances().clear();
  smokes_.instances().clear();
  bodies_.instances().set_count(static_cast<int>(order_.size()));
  const float base_y = look_.layout.base.to_float();
  for (size_t k = 0; k < order_.size(); ++k) {
    const uint32_t i = order_[k];
    const CandleDesc& d = desc_[i];
    const CandleRig& rig = rigs_[i];
    const CandleState& s = rig.state();
    const float wick = kWickLength * d.flame_scale;
    const float top = d.position.y + d.height - kPoolDepth * d.radius;
    // The flame's base sits a little below the wick's tip.
    const Vec3 base{d.position.x, top + wick * 0.7f, d.position.z};
    const float bright = rig.brightness().to_float();
    const float scale = look_.flame_height * d.flame_scale * s.grow.to_float();
    const float tilt = s.tilt.to_float();
    // The billboard's axes, as the vertex shader builds them.
    Vec3 f{cam.x - base.x, 0, cam.z - base.z};
    f = length(f) > 1e-5f ? normalize(f) : Vec3{0, 0, 1};
    const Vec3 right{f.z, 0, -f.x};
    const Vec3 up = Vec3{0, std::cos(tilt), 0} + f * std::sin(tilt);
    auto to_world = [&](float bx, float by) {
      return base + right * (bx * scale) + up * ((by - base_y) * scale);
    };

    // Bodies go near to far, so hidden wax fails the depth test early.
    float* b = bodies_.instances().record(order_.size() - 1 - k);
    // The flame's light: from the middle of the morphed centre line.
    const ControlLines& L = rig.lines();
    const float mx = 0.5f * (L.line[0].px.to_float() + L.line[2].qx.to_float());
    const float my = 0.5f * (L.line[0].py.to_float() + L.line[2].qy.to_float());
    const Vec3 centre = s.lit ? to_world(mx, my) : base;
    const float light = s.lit ? bright : 0.0f;
    const float body[kBodyVec4 * 4] = {d.position.x, d.position.y, d.position.z, d.radius,
                                       d.height,     d.wax.x,      d.wax.y,      d.wax.z,
                                       centre.x,     centre.y,     centre.z,     light};
    std::copy(std::begin(body), std::end(body), b);

    if (s.lit && scale > 1e-5f) {
      float* fl = flames_.instances().add();
      for (int l = 0; l < kMaxControlLines; ++l) {
        const ControlLine& c = L.line[l];
        fl[l * 4 + 0] = c.px.to_float();
        fl[l * 4 + 1] = c.py.to_float();
        fl[l * 4 + 2] = c.qx.to_float();
        fl[l * 4 + 3] = c.qy.to_float();
      }
      const float anchor_pose[8] = {
          base.x, base.y, base.z, scale, tilt, static_cast<float>(L.count), bright, 0};
      std::copy(std::begin(anchor_pose), std::end(anchor_pose), fl + kMaxControlLines * 4);

      // Glow: diameter follows the morphed billboard's diagonal (V1's start to
      // V2's end); it fades with distance; brightness follows the flame's size.
      const float dx = L.line[3].px.to_float() - L.line[8].qx.to_float();
      const float dy = L.line[3].py.to_float() - L.line[8].qy.to_float();
      const float diag = std::sqrt(dx * dx + dy * dy) * scale;
      const float dist = length(centre - cam);
      const float fade = 1.0f / (1.0f + (dist / look_.glow_falloff) * (dist / look_.glow_falloff));
      const float warm = std::clamp(bright, 0.0f, 1.5f);
      float* g = glows_.instances().add();
      const float glow[kGlowVec4 * 4] = {centre.x,
                                         centre.y,
                                         centre.z,
                                         diag * look_.glow_scale,
                                         1.0f,
                                         0.55f + 0.1f * warm,
                                         0.22f + 0.08f * warm,
                                         look_.glow_strength * fade * warm};
      std::copy(std::begin(glow), std::end(glow), g);
    }
    const float smoke_age =
        s.out_steps >= 0 ? static_cast<float>(s.out_steps) * dt_seconds_ : -1.0f;
    if (smoke_age >= 0 && smoke_age < smoke_seconds_) {
      float* sm = smokes_.instances().add();
      const float smoke[kSmokeVec4 * 4] = {base.x,
                                           base.y + wick * 0.3f,
                                           base.z,
                                           smoke_age / smoke_seconds_,
                                           d.flame_scale,
                                           static_cast<float>(i % 97) * 0.137f,
                                           0,
                                           0};
      std::copy(std::begin(smoke), std::end(smoke), sm);
    }
  }
  flames_.instances().upload();
  bodies_.instances().upload();
  glows_.instances().upload();
  smokes_.instances().upload();
}

void Candles::draw(const FrameContext& frame, DrawPass pass) {
  if (pass != DrawPass::kGlow && pass != DrawPass::kBody && pass != DrawPass::kFlame) return;
  if (desc_.empty()) return;
  const Mat4& v = frame.view;
  const Vec3 right{v.at(0, 0), v.at(0, 1), v.at(0, 2)};
  const Vec3 up{v.at(1, 0), v.at(1, 1), v.at(1, 2)};
  const Vec3 cam = frame.camera_position;
  if (pass == DrawPass::kGlow) {
    if (!glows_.count()) return;
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glows_.draw(frame.view_projection, right, up);
  } else if (pass == DrawPass::kBody) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    body_prog_.use();
    glUniformMatrix4fv(body_vp_, 1, GL_FALSE, frame.view_projection.m);
    glUniform3f(body_camera_, cam.x, cam.y, cam.z);
    bodies_.draw();
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied
    if (flames_.count()) {
      flame_prog_.use();
      glUniformMatrix4fv(fu_.view_projection, 1, GL_FALSE, frame.view_projection.m);
      glUniform3f(fu_.camera, cam.x, cam.y, cam.z);
      const ControlLines src = source_lines(look_.layout);
      float s[kMaxControlLines * 4];
      for (int l = 0; l < kMaxControlLines; ++l) {
        s[l * 4 + 0] = src.line[l].px.to_float();
        s[l * 4 + 1] = src.line[l].py.to_float();
        s[l * 4 + 2] = src.line[l].qx.to_float();
        s[l * 4 + 3] = src.line[l].qy.to_float();
      }
      glUniform4fv(fu_.src, kMaxControlLines, s);
      glUniform3f(fu_.weights, look_.warp_a, look_.warp_b, look_.warp_p);
      glUniform1f(fu_.aspect, aspect_);
      glUniform1f(fu_.base, look_.layout.base.to_float());
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, still_.get());
      glUniform1i(fu_.still, 0);
      flames_.draw();
    }
    if (smokes_.count()) {
      glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      smokes_.draw(frame.view_projection, right, up);
    }
    glDepthMask(GL_TRUE);
  }
  glBindVertexArray(0);
}

}  // namespace

uint64_t candle_seed(uint64_t element_seed, size_t index) {
  return split_seed(element_seed, index) | 1;
}

std::unique_ptr<Element> CandlesSpec::create(const SceneContext& context) const {
  return std::make_unique<Candles>(*this, context);
}

}  // namespace candela
