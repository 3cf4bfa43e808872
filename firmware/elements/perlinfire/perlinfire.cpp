#include "elements/perlinfire/perlinfire.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/error.h"
#include "core/fixed.h"
#include "core/flicker.h"
#include "core/image.h"
#include "core/log.h"
#include "elements/perlinfire/fire_profile.h"
#include "elements/perlinfire/noise_tables.h"
#include "elements/perlinfire/quality_governor.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"
#include "params/params.h"
#include "wind/lean.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

constexpr int kMaxOctaves = 8;
// The swell's heights: this many points across the fire, joined smoothly
// (perlinfire.frag), so about three rises and falls fit across it.
constexpr int kSwellPoints = 8;
constexpr double kTwoPi = 6.283185307179586;
// The tongue field's sway: new places a second.
constexpr double kSwayRate = 0.4;

// Where the noise's offsets wrap: the 3-D noise repeats every 768 lattice
// units, so its offsets wrap without a seam; the 4-D noise has no period, so
// its offsets wrap rarely, where float precision is still fine.
int64_t offset_period(FireNoise kind) {
  return kind == FireNoise::kSimplex3d || kind == FireNoise::kFlow3d
             ? NoiseConstants::kPeriod3
             : NoiseConstants::kPeriod3 * 21;
}

struct FireSettings {
  Vec3 size{0.4f, 0.7f, 0.4f};
  Image profile;  // empty: the default, made at start-up
  double profile_width = 0.8, profile_taper = 0.65, profile_height = 0.92;  // the default profile
  FireNoise noise = FireNoise::kFlow3d;
  int octaves = 4;
  double weight = 0.5, gain = 0.5;             // octave o weighs weight * gain^o
  Fixed speed = Fixed::from_ratio(3, 4);       // fire heights per second the turbulence rises
  double frequency = 3.5;                      // noise lattice cells per fire height
  Fixed flow_speed = Fixed::from_ratio(3, 2);  // flow3d: radians per second
  Fixed evolve = Fixed::from_ratio(1, 2);      // 4-D kinds: lattice units per second along w
  float displacement = 0.8f;
  float intensity = 4.0f;
  FireShading shading = FireShading::kSheets;
  float sheet_edge = 0.3f, sheet_softness = 0.6f;  // density threshold of the flame sheets
  float rise_growth = 0.1f;   // displacement at the base relative to the top's (sheets)
  float wobble = 0.3f;        // radial share of the displacement (sheets)
  double stretch = 1.0;       // noise cells are this much taller than wide
  float breathing = 0.0f;     // how much the flame's height swells and falls (sheets)
  double tongues = 3.0;       // tongue field cells per fire height across (sheets)
  float tongue_gap = 0.0f;    // how deep the gaps between tongues cut (sheets; 0: none)
  float tongue_width = 0.2f;  // how wide those gaps are (of the field's |noise|)
  float tongue_roots = 0.0f;  // how deep the gaps cut at the base: 0 one bed, 1 separate roots
  float glow = 0.0f;          // brightness of the soft glow around the flames (sheets)
  float cooling = 0.0f;  // how much the flames' heat falls from the bed's top to the tips (sheets)
  float swell = 0.0f;    // how far the flames' height swells and sinks across the fire (sheets)
  Fixed swell_rate = Fixed::from_ratio(1, 4);  // how fast: new heights per second
  float halo = 0.0f;          // the camera's soft halo around bright flames (sheets, reduced scale)
  float halo_radius = 0.06f;  // how far it spreads, of the picture's height
  double shutter = 0;  // the camera's exposure time, s (reduced scale; 0: each frame an instant)
  // What is drawn nearer than the fire's middle plane hides it (reduced scale).
  bool occlude = false;
  double tongue_stretch = 8;  // the tongue field's cells are this much taller than wide
  float tongue_base = 0.45f;  // the height (of the volume) where the gaps reach full depth
  Fixed tongue_rise = Fixed::from_int(1);    // how fast the tongue field rises, of the turbulence's
  Fixed tongue_evolve = Fixed::from_int(1);  // how fast it changes in place, of that rise
  double fine_tongues = 15;  // a second, finer tongue field's cells per fire height across
  float fine_gap = 0.0f;     // how deep its gaps cut (0: none); it rises with the turbulence
  float fine_width = 0.55f;  // how wide its gaps are (of its |noise|)
  double fine_stretch = 6;   // how much taller than wide its cells are
  double tongue_sway = 0;    // how far the tongue field wanders sideways (its cells), slowly
  float tongue_comb = 0;     // 0: gaps at the tongue field's creases; > 0: evenly spaced gaps
                             // that wander by up to this share of their spacing
  Vec3 color{1, 1, 1};
  bool additive = true;
  float obstacle = 0;         // fraction of the volume's height that is solid (logs, grate)
  float obstacle_relief = 0;  // how far its top rises and falls across the fire (volume heights)
  Fixed wind_lean = Fixed::from_ratio(15, 100);  // tip offset per m/s, in volume widths
  Fixed max_lean = Fixed::from_ratio(6, 10);
  Fixed wind_drift = Fixed::from_ratio(1, 2);  // turbulence drift per m/s, fire heights/s
  Fixed lean_response = Fixed::from_int(3);    // 1/s: how fast the flame follows the wind
  QualityLevel quality{20, 4, 1.0f};
  bool auto_quality = false;
  double target_fps = 30;
  float min_scale = 0.25f;
};

// GL texture set-up shared by the tables.
Texture make_table_texture(GLenum internal, GLenum format, GLenum type, const void* data) {
  Texture t = make_texture();
  glBindTexture(GL_TEXTURE_2D, t.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), NoiseTables::kSize,
               NoiseTables::kSize, 0, format, type, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

// Where a profile can put anything: below `top` (volume heights) and inside
// the cone radius(h) = radius - slope * h (profile units: 1 = the rim).
// Lookups are only ever displaced upwards, so these bound the drawn fire too.
struct ProfileBound {
  float radius = 1, slope = 0, top = 1;
};

ProfileBound profile_bound(const Image& img) {
  const int w = img.width, h = img.height;
  // reach[y]: how far out anything reaches at or above row y (rows top down),
  // half a texel wider for linear filtering.
  std::vector<float> reach(static_cast<size_t>(h), 0.0f);
  float top = 0, running = 0;
  for (int row = 0; row < h; ++row) {
    for (int col = w - 1; col >= 0; --col)
      if (img.at(col, row, 3) > 0) {
        running = std::max(running, std::min(1.0f, (col + 1.5f) / w));
        if (top == 0) top = std::min(1.0f, 1.0f - (row - 0.5f) / h);
        break;
      }
    reach[static_cast<size_t>(row)] = running;
  }
  ProfileBound b;
  b.top = top;
  b.radius = reach.empty() ? 0.0f : reach.back();
  // The steepest cone through (0, radius) that stays outside every row.
  float slope = 1e9f;
  for (int row = 0; row + 1 < h; ++row) {
    const float y = 1.0f - (row + 1.0f) / h;  // the row's lower edge
    if (y > 0) slope = std::min(slope, (b.radius - reach[static_cast<size_t>(row)]) / y);
  }
  b.slope = std::max(0.0f, slope == 1e9f ? 0.0f : slope);
  return b;
}

class PerlinFire final : public Element {
 public:
  PerlinFire(const FireSettings& s, Vec3 position, uint64_t seed)
      : s_(s),
        position_(position),
        period_(offset_period(s.noise)),
        governor_(QualityGovernor::make_ladder(
                      s.quality, std::min(min_steps(s.shading), s.quality.steps),
                      std::min(1, s.quality.octaves), std::min(s.min_scale, s.quality.scale)),
                  governor_settings(s)),
        breath_(seed ^ 0x62726561746865ULL),
        swell_heights_(seed ^ 0x7377656c6cULL),
        sway_(seed ^ 0x73776179ULL) {
    program_ = Program::from_library("perlinfire.vert",
                                     {"perlinfire_noise.frag", "fire_ramp.frag", "perlinfire.frag"},
                                     perlinfire_defines(s.noise, s.shading) +
                                         (s.tongue_comb > 0 ? "#define PF_TONGUE_COMB\n" : "") +
                                         (s.fine_gap > 0 ? "#define PF_FINE_TONGUES\n" : ""));
    // The upscaling pass: the ramp (sheets colour after upscaling), then the composite.
    composite_ = Program::from_library(
        "fullscreen.vert", {"fire_ramp.frag", "perlinfire_composite.frag"},
        "#define PF_SHADING " + std::to_string(static_cast<int>(s.shading)) +
            (s.occlude ? "\n#define PF_OCCLUDE" : "") + "\nprecision highp float;\n");
    vao_ = make_vertex_array();
    locate_uniforms();
    halo_ = s.shading == FireShading::kSheets && s.halo > 0;
    if (s.shutter > 0)
      shutter_fade_ = Program::from_library("fullscreen.vert", "perlinfire_shutter.frag");

    const NoiseTables tables(seed);
    perm_ = make_table_texture(GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, tables.perm2d().data());
    grad3_ = make_table_texture(GL_RGBA8_SNORM, GL_RGBA, GL_BYTE, tables.grad3_rgba().data());
    grad4_ = make_table_texture(GL_RGBA8_SNORM, GL_RGBA, GL_BYTE, tables.grad4_rgba().data());

    Image profile =
        s.profile.pixels.empty()
            ? make_default_fire_profile(64, 128, s.profile_width, s.profile_taper, s.profile_height)
            : s.profile;
    bound_ = profile_bound(profile);
    // Premultiplied, so linear filtering does not bleed colour out of empty texels.
    for (size_t i = 0; i < profile.pixels.size(); i += 4)
      for (size_t c = 0; c < 3; ++c)
        profile.pixels[i + c] =
            static_cast<uint8_t>((profile.pixels[i + c] * profile.pixels[i + 3] + 127) / 255);
    profile_ = upload_rgba8(profile.width, profile.height, profile.pixels.data(), true);

    for (int o = 0; o < kMaxOctaves; ++o)
      weights_[static_cast<size_t>(o)] = static_cast<float>(s.weight * std::pow(s.gain, o));
  }

  void update(const StepContext& step) override {
    // Wind: the tip leans with the wind (first-order lag) and the turbulence drifts.
    WindSample w{};
    if (step.wind) w = step.wind->sample(position_);
    const Fixed k = lag_gain(step.dt, s_.lean_response);
    lean_x_ = lean_toward(lean_x_, w.x, s_.wind_lean, s_.max_lean, k);
    lean_z_ = lean_toward(lean_z_, w.z, s_.wind_lean, s_.max_lean, k);
    const Fixed lattice_per_height = Fixed::from_double(s_.frequency);
    const int32_t wrap = static_cast<int32_t>(period_) * Fixed::kOne;
    drift_x_.raw = (drift_x_.raw + (w.x * s_.wind_drift * lattice_per_height * step.dt).raw) % wrap;
    drift_z_.raw = (drift_z_.raw + (w.z * s_.wind_drift * lattice_per_height * step.dt).raw) % wrap;
    time_ = step.time;
    // Breathing: the whole fire swells and falls as its tongues do (about
    // 0.55..1.35 of the mean turbulence subtracted).
    breath_now_ = breath_.at(step.time);
    wind_speed_ = abs(w.x) + abs(w.z);  // (L1: no square root on the step)
    uniforms_dirty_ = true;
  }
  void hash_state(StateHash& hash) const override {
    for (Fixed v : {lean_x_, lean_z_, drift_x_, drift_z_, time_, breath_now_, wind_speed_})
      hash.add(v);
  }

  // The fire's loudness follows its breathing (the swell of its tongues),
  // its crackling how far the breath is above its low point, its whoosh the
  // wind at the flames.
  void add_sound_cue(SoundCue& cue) const override {
    cue.fire += breath_now_;
    cue.activity +=
        clamp((breath_now_ - Fixed::from_ratio(55, 100)) * 2, Fixed{}, Fixed::from_int(2));
    cue.wind = std::max(cue.wind, wind_speed_);
  }

  // This frame's quality and where the fire lies on screen; at a reduced
  // render scale, the march into the offscreen target (composited onto the
  // screen in the flame pass).
  void prepare(const FrameContext& f) override {
    if (s_.auto_quality && f.last_frame_ms > 0) governor_.add_frame(f.last_frame_ms);
    quality_ = s_.auto_quality ? governor_.current() : s_.quality;
    if (uniforms_dirty_) compute_octave_uniforms();

    // The march box: the unit volume widened on the side the flame leans to.
    const float lx = lean_x_.to_float(), lz = lean_z_.to_float();
    box_min_ = {-0.5f + std::min(0.0f, lx), 0.0f, -0.5f + std::min(0.0f, lz)};
    box_max_ = {0.5f + std::max(0.0f, lx), 1.0f, 0.5f + std::max(0.0f, lz)};
    const Mat4 model = Mat4::translate(position_) * Mat4::scale(s_.size);
    mvp_ = f.view_projection * model;
    visible_ = screen_rect(mvp_, box_min_, box_max_, f.width, f.height, rect_);
    offscreen_ = quality_.scale < 0.999f;
    if (!visible_ || !offscreen_) {
      trail_ = false;
      return;
    }

    const FramebufferRestore screen;
    const bool new_target = ensure_target(f.width, f.height);
    const int sub_w = std::max(1, static_cast<int>(std::lround(f.width * quality_.scale)));
    const int sub_h = std::max(1, static_cast<int>(std::lround(f.height * quality_.scale)));
    // The shutter: the share of the earlier frames' exposure this one keeps.
    // None after a gap, a new target or a new scale; all of it (nothing to
    // draw) when the animation has not moved since the last frame.
    double keep = 0;
    if (s_.shutter > 0 && trail_ && !new_target && sub_w == sub_w_ && sub_h == sub_h_) {
      const double dt = (time_ - trail_time_).to_double();
      if (dt <= 0) return;
      keep = std::exp(-2.0 * dt / s_.shutter);
    }
    trail_ = s_.shutter > 0;
    trail_time_ = time_;
    sub_w_ = sub_w;
    sub_h_ = sub_h;
    target_.bind();
    glViewport(0, 0, sub_w_, sub_h_);
    glEnable(GL_SCISSOR_TEST);
    const float sx = static_cast<float>(sub_w_) / f.width,
                sy = static_cast<float>(sub_h_) / f.height;
    const int x0 = std::max(0, static_cast<int>(std::floor(rect_[0] * sx)) - 2);
    const int y0 = std::max(0, static_cast<int>(std::floor(rect_[1] * sy)) - 2);
    // Two texels past the part in use are cleared too: the B-spline reads them.
    const int x1 = std::min(target_.width(), static_cast<int>(std::ceil(rect_[2] * sx)) + 3);
    const int y1 = std::min(target_.height(), static_cast<int>(std::ceil(rect_[3] * sy)) + 3);
    glClearColor(0, 0, 0, 0);
    // The halo reads the target blurred (its mipmaps), whose coarse texels
    // reach past the part in use: the whole target is cleared, as what an
    // earlier frame left outside the box (it moves with the lean) or at a
    // larger scale (automatic quality) would show in the halo. So is a
    // shutter's: its trail is kept over the whole target, so what the box
    // leaves when it moves fades out with the rest.
    if (halo_ || s_.shutter > 0)
      glScissor(0, 0, target_.width(), target_.height());
    else
      glScissor(x0, y0, x1 - x0, y1 - y0);
    if (keep > 0) {
      // An exponential trail, keep = exp(-2 dt / shutter): the exposure's
      // mean age is half the shutter's, as a camera's box exposure has.
      glEnable(GL_BLEND);
      glBlendColor(0, 0, 0, static_cast<float>(keep));
      glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);  // keep * earlier - 1/255
      glBlendFunc(GL_ONE, GL_CONSTANT_ALPHA);
      shutter_fade_.use();
      glBindVertexArray(vao_.get());
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glBlendEquation(GL_FUNC_ADD);  // + (1 - keep) * this frame
      glBlendFunc(GL_ONE_MINUS_CONSTANT_ALPHA, GL_ONE);
    } else {
      glClear(GL_COLOR_BUFFER_BIT);
      glDisable(GL_BLEND);
    }
    glScissor(x0, y0, x1 - x0, y1 - y0);
    // The fade takes 1/255 off; this frame's share (1 - keep) of the lift gives it back.
    march(f, keep > 0 ? static_cast<float>(1.0 / 255.0 / (1.0 - keep)) : 0.0f);
    glDisable(GL_BLEND);
    glBlendColor(0, 0, 0, 0);
    glDisable(GL_SCISSOR_TEST);
    if (halo_) {
      glBindTexture(GL_TEXTURE_2D, target_.texture());
      glGenerateMipmap(GL_TEXTURE_2D);
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    glDepthMask(GL_TRUE);
    glActiveTexture(GL_TEXTURE0);
  }

  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass != DrawPass::kFlame || !visible_) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect_[0], rect_[1], rect_[2] - rect_[0], rect_[3] - rect_[1]);
    set_blend();
    if (offscreen_) {
      composite_.use();
      glUniform2f(u_.uv_per_pixel, static_cast<float>(sub_w_) / f.width / target_.width(),
                  static_cast<float>(sub_h_) / f.height / target_.height());
      glUniform3f(u_.composite_color, s_.color.x, s_.color.y, s_.color.z);
      // The halo's blur: its share of the picture's height, whatever the scale.
      glUniform1f(u_.halo, halo_ ? s_.halo : 0.0f);
      glUniform1i(u_.bspline, quality_.scale <= 0.5f ? 1 : 0);
      glUniform2f(u_.texels, static_cast<float>(target_.width()),
                  static_cast<float>(target_.height()));
      glUniform1f(u_.halo_lod,
                  std::log2(std::max(1.0f, s_.halo_radius * static_cast<float>(sub_h_))));
      bind_texture(4, target_.texture(), u_.image);
      // Occluding: the fire as one sheet through its middle, so the logs in
      // front of that (their depth is in the buffer from the body pass) hide
      // it and the logs behind it do not: flames rise from between the logs.
      if (s_.occlude) {
        const Vec4 mid = mvp_ * Vec4{0.0f, 0.3f, 0.0f, 1.0f};
        glUniform1f(u_.depth,
                    mid.w > 1e-6f ? std::clamp(0.5f * mid.z / mid.w + 0.5f, 0.0f, 1.0f) : 0.0f);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
      } else {
        glDisable(GL_DEPTH_TEST);
      }
      glDisable(GL_CULL_FACE);
      glDepthMask(GL_FALSE);
      glBindVertexArray(vao_.get());
      glDrawArrays(GL_TRIANGLES, 0, 3);
    } else {
      march(f);
    }
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glActiveTexture(GL_TEXTURE0);
  }

 private:
  // The ray march through the box into the bound framebuffer (the screen,
  // or the offscreen target at a reduced scale). `trail_lift` is added to
  // every fragment drawn: a shutter's share of what its fade took off.
  void march(const FrameContext& f, float trail_lift = 0) {
    const QualityLevel q = quality_;
    const bool offscreen = offscreen_;
    const float lx = lean_x_.to_float(), lz = lean_z_.to_float();
    const Vec3 box_min = box_min_, box_max = box_max_;
    const Mat4& mvp = mvp_;
    program_.use();
    glUniformMatrix4fv(u_.mvp, 1, GL_FALSE, mvp.m);
    glUniform3f(u_.box_min, box_min.x, box_min.y, box_min.z);
    glUniform3f(u_.box_max, box_max.x, box_max.y, box_max.z);
    const Vec3 cam{(f.camera_position.x - position_.x) / s_.size.x,
                   (f.camera_position.y - position_.y) / s_.size.y,
                   (f.camera_position.z - position_.z) / s_.size.z};
    glUniform3f(u_.camera, cam.x, cam.y, cam.z);
    const Vec3 ws = s_.size * (1.0f / s_.size.y);
    glUniform3f(u_.world_scale, ws.x, ws.y, ws.z);
    const float fq = static_cast<float>(s_.frequency);
    glUniform3f(u_.noise_scale, ws.x * fq, ws.y * fq / static_cast<float>(s_.stretch), ws.z * fq);
    // Steps of equal length: `steps` of them across the volume's width.
    glUniform1f(u_.step_length, std::max(ws.x, ws.z) / static_cast<float>(q.steps));
    glUniform1i(u_.max_steps, 2 * q.steps);
    const float lean_len = std::sqrt(lx * lx + lz * lz);
    glUniform1i(u_.octaves, std::min(q.octaves, kMaxOctaves));
    glUniform1fv(u_.weights, kMaxOctaves, weights_.data());
    glUniform3fv(u_.offset, kMaxOctaves, offsets_.data());
    glUniform2fv(u_.flow_cs, kMaxOctaves, flow_cs_.data());
    glUniform1fv(u_.time4, kMaxOctaves, time4_.data());
    glUniform2f(u_.lean, lx, lz);
    glUniform1f(u_.displacement, s_.displacement);
    // The mean of |noise| is about 0.22 for all four kinds.
    float weight_sum = 0;
    for (int o = 0; o < std::min(q.octaves, kMaxOctaves); ++o)
      weight_sum += weights_[static_cast<size_t>(o)];
    const float breath = 1.0f + s_.breathing * (breath_now_.to_float() - 1.0f);
    const float turbulence_mean = 0.22f * weight_sum * breath;
    glUniform1f(u_.turbulence_mean, turbulence_mean);
    // Where turbulence is below its mean the lookup moves down (sheets), so
    // tongues may rise above the profile's top: up to a quarter of the
    // volume's height more, fading out on the way (perlinfire.frag).
    const float top =
        s_.shading == FireShading::kSheets ? std::min(1.0f, bound_.top + 0.25f) : bound_.top;
    glUniform4f(u_.bound, 0.5f * (bound_.radius + lean_len), 0.5f * bound_.slope, top, 0.0f);
    glUniform1f(u_.intensity, s_.intensity);
    glUniform2f(u_.sheet, s_.sheet_edge, s_.sheet_softness);
    glUniform1f(u_.rise_growth, s_.rise_growth);
    glUniform1f(u_.wobble, s_.wobble);
    // Sheets colour after upscaling, so a reduced scale keeps crisp edges.
    glUniform1i(u_.ramp_here, offscreen ? 0 : 1);
    // Sheets sample slabs, not steps: a third as many (the quality ladder's
    // steps 20 -> 6 give 6 -> 2 slabs).
    glUniform1i(u_.slices, std::clamp(q.steps / 3, 2, 16));
    const float tq = static_cast<float>(s_.tongues);
    glUniform3f(u_.tongue_scale, ws.x * tq, ws.y * tq / static_cast<float>(s_.tongue_stretch),
                s_.tongue_comb);
    glUniform3fv(u_.tongue_offset, 1, tongue_offset_.data());
    const float fq2 = static_cast<float>(s_.fine_tongues);
    glUniform3f(u_.fine_scale, ws.x * fq2, ws.y * fq2 / static_cast<float>(s_.fine_stretch), 0.0f);
    glUniform3fv(u_.fine_offset, 1, fine_offset_.data());
    glUniform2f(u_.fine_gap, s_.fine_gap, s_.fine_width);
    glUniform1f(u_.glow, s_.glow);
    glUniform1f(u_.tongue_roots, s_.tongue_roots);
    glUniform1f(u_.cooling, s_.cooling);
    glUniform1f(u_.trail_lift, trail_lift);
    glUniform1f(u_.swell, s_.swell);
    glUniform1fv(u_.swell_scale, kSwellPoints, swell_scale_.data());
    glUniform3f(u_.tongue_gap, s_.tongue_gap, s_.tongue_width, s_.tongue_base);
    glUniform1f(u_.obstacle, s_.obstacle > 0 ? s_.obstacle : -1e9f);
    glUniform1f(u_.obstacle_relief, s_.obstacle_relief);
    glUniform3f(u_.color, s_.color.x, s_.color.y, s_.color.z);
    bind_texture(0, perm_.get(), u_.perm);
    bind_texture(1, grad3_.get(), u_.grad3);
    bind_texture(2, grad4_.get(), u_.grad4);
    bind_texture(3, profile_.get(), u_.profile);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);  // back faces: one fragment per pixel, camera inside or out
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 36);
    glDisable(GL_CULL_FACE);
  }

  // The fewest ray steps automatic quality goes down to. Flame sheets sample
  // steps / 3 slabs, and under three slabs the fire's lit area halves (the
  // Perlin fireplace at 960x540: four slabs light 15.6% of the frame, three
  // 14.8%, two 8.9%; issue 35 asks for 12%): a slow board gets a softer fire
  // (lower render scale, fewer octaves), not a sparse one.
  static int min_steps(FireShading shading) { return shading == FireShading::kSheets ? 9 : 6; }

  static QualityGovernor::Settings governor_settings(const FireSettings& s) {
    QualityGovernor::Settings g;
    g.budget_ms = 1000.0 / s.target_fps;
    return g;
  }

  void locate_uniforms() {
    const auto u = [&](const char* n) { return program_.uniform(n); };
    u_.mvp = u("u_model_view_projection");
    u_.box_min = u("u_box_min");
    u_.box_max = u("u_box_max");
    u_.camera = u("u_camera");
    u_.world_scale = u("u_world_scale");
    u_.noise_scale = u("u_noise_scale");
    u_.step_length = u("u_step_length");
    u_.max_steps = u("u_max_steps");
    u_.bound = u("u_bound");
    u_.octaves = u("u_octaves");
    u_.weights = u("u_weights");
    u_.offset = u("u_offset");
    u_.flow_cs = u("u_flow_cs");
    u_.time4 = u("u_time4");
    u_.lean = u("u_lean");
    u_.displacement = u("u_displacement");
    u_.turbulence_mean = u("u_turbulence_mean");
    u_.intensity = u("u_intensity");
    u_.obstacle = u("u_obstacle");
    u_.obstacle_relief = u("u_obstacle_relief");
    u_.color = u("u_color");
    u_.perm = u("u_perm");
    u_.grad3 = u("u_grad3");
    u_.grad4 = u("u_grad4");
    u_.profile = u("u_profile");
    u_.sheet = u("u_sheet");
    u_.rise_growth = u("u_rise_growth");
    u_.wobble = u("u_wobble");
    u_.ramp_here = u("u_ramp_here");
    u_.slices = u("u_slices");
    u_.tongue_scale = u("u_tongue_scale");
    u_.tongue_offset = u("u_tongue_offset");
    u_.fine_scale = u("u_fine_scale");
    u_.fine_offset = u("u_fine_offset");
    u_.fine_gap = u("u_fine_gap");
    u_.tongue_gap = u("u_tongue_gap");
    u_.glow = u("u_glow");
    u_.tongue_roots = u("u_tongue_roots");
    u_.cooling = u("u_cooling");
    u_.trail_lift = u("u_trail_lift");
    u_.swell = u("u_swell");
    u_.swell_scale = u("u_swell_scale");
    u_.composite_color = composite_.uniform("u_color");
    u_.image = composite_.uniform("u_image");
    u_.uv_per_pixel = composite_.uniform("u_uv_per_pixel");
    u_.halo = composite_.uniform("u_halo");
    u_.halo_lod = composite_.uniform("u_halo_lod");
    u_.bspline = composite_.uniform("u_bspline");
    u_.texels = composite_.uniform("u_texels");
    u_.depth = composite_.uniform("u_depth");
  }

  static void bind_texture(int unit, GLuint texture, GLint location) {
    if (location < 0) return;  // this noise kind does not read it
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D, texture);
    glUniform1i(location, unit);
  }

  void set_blend() const {
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    if (s_.additive)
      glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
    else
      glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  }

  // The offscreen target, made once per screen size at the largest render
  // scale the ladder uses; smaller scales use its lower-left part.
  // True when it was made anew (its content undefined).
  bool ensure_target(int w, int h) {
    if (w == screen_w_ && h == screen_h_) return false;
    screen_w_ = w;
    screen_h_ = h;
    const float top = s_.quality.scale;
    target_ = RenderTarget(std::max(1, static_cast<int>(std::ceil(w * top))),
                           std::max(1, static_cast<int>(std::ceil(h * top))));
    if (!target_.complete())
      LOG_ERROR("perlinfire: offscreen target %dx%d incomplete", target_.width(), target_.height());
    if (halo_) {  // blurred reads: trilinear, up to the level a 4K screen's halo needs
      glBindTexture(GL_TEXTURE_2D, target_.texture());
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 6);
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    return true;
  }

  // The box's pixels on screen (x0, y0, x1, y1; GL's bottom-left origin), a
  // little widened for filtering. False when it is off screen.
  static bool screen_rect(const Mat4& mvp, Vec3 lo, Vec3 hi, int w, int h, int out[4]) {
    float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
    for (int c = 0; c < 8; ++c) {
      const Vec4 p =
          mvp * Vec4{(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z, 1.0f};
      if (p.w < 1e-4f) {  // a corner behind the camera: use the whole screen
        out[0] = 0, out[1] = 0, out[2] = w, out[3] = h;
        return true;
      }
      x0 = std::min(x0, p.x / p.w), x1 = std::max(x1, p.x / p.w);
      y0 = std::min(y0, p.y / p.w), y1 = std::max(y1, p.y / p.w);
    }
    out[0] = std::max(0, static_cast<int>(std::floor((x0 * 0.5f + 0.5f) * w)) - 2);
    out[1] = std::max(0, static_cast<int>(std::floor((y0 * 0.5f + 0.5f) * h)) - 2);
    out[2] = std::min(w, static_cast<int>(std::ceil((x1 * 0.5f + 0.5f) * w)) + 2);
    out[3] = std::min(h, static_cast<int>(std::ceil((y1 * 0.5f + 0.5f) * h)) + 2);
    return out[2] > out[0] && out[3] > out[1];
  }

  // Per-octave offsets, flow angles and 4th coordinates from the fixed-point
  // clock, in integer arithmetic and wrapped where the noise repeats, so the
  // floats handed to the shader stay small and the same on every machine.
  void compute_octave_uniforms() {
    uniforms_dirty_ = false;
    const int64_t t = time_.raw;  // Q16.16 seconds
    const int64_t wrap = period_ << Fixed::kFracBits;
    // How far a lattice with this many cells per fire height along y has
    // risen with the turbulence (Q16.16 cells), and where a field with this
    // many cells per fire height across has drifted with the wind (cells).
    const auto risen = [&](double cells_per_height) {
      return (t * Fixed::from_double(cells_per_height).raw >> Fixed::kFracBits) * s_.speed.raw >>
             Fixed::kFracBits;
    };
    const auto drifted = [&](double cells_per_height, double extra = 0) {
      return static_cast<float>(
          std::fmod(drift_x_.to_double() * (cells_per_height / s_.frequency) + extra,
                    static_cast<double>(period_)));
    };
    // Lattice cells per fire height along y (taller cells when stretched).
    const int64_t rise = risen(s_.frequency / s_.stretch);
    const int64_t evolve = t * s_.evolve.raw >> Fixed::kFracBits;
    const int64_t spin = t * s_.flow_speed.raw >> Fixed::kFracBits;  // radians, Q16.16
    const double to_float = 1.0 / Fixed::kOne;
    for (int o = 0; o < kMaxOctaves; ++o) {
      const int64_t f = int64_t{1} << o;
      const auto i = static_cast<size_t>(o);
      offsets_[i * 3 + 0] = static_cast<float>(((drift_x_.raw * f) % wrap) * to_float);
      offsets_[i * 3 + 1] = static_cast<float>(((rise * f) % wrap) * to_float);
      offsets_[i * 3 + 2] = static_cast<float>(((drift_z_.raw * f) % wrap) * to_float);
      time4_[i] = static_cast<float>(((evolve * f) % wrap) * to_float);
      const double angle = std::fmod(static_cast<double>(spin * f) * to_float, kTwoPi);
      flow_cs_[i * 2 + 0] = static_cast<float>(std::cos(angle));
      flow_cs_[i * 2 + 1] = static_cast<float>(std::sin(angle));
    }
    // The tongue field rises with the turbulence (its own lattice) and drifts with the wind.
    const int64_t tongue_cells = risen(s_.tongues / s_.tongue_stretch);
    const int64_t tongue_rise = tongue_cells * s_.tongue_rise.raw >> Fixed::kFracBits;
    const int64_t tongue_evolve = tongue_cells * s_.tongue_evolve.raw >> Fixed::kFracBits;
    // The sway: a slow random walk sideways (about kSwayRate new places a
    // second, smoothly joined), so tongues wander without coming and going.
    const double sway =
        s_.tongue_sway *
        sway_.noise(t * Fixed::from_double(kSwayRate).raw >> Fixed::kFracBits, 0).to_double();
    tongue_offset_[0] = drifted(s_.tongues, sway);
    tongue_offset_[1] = static_cast<float>((tongue_rise % wrap) * to_float);
    // It evolves through its third axis.
    tongue_offset_[2] = static_cast<float>((tongue_evolve % wrap) * to_float);
    // The fine tongue field rises and evolves with the turbulence: the flicker
    // over broad tongues that stand where their fuel burns.
    const int64_t fine_cells = risen(s_.fine_tongues / s_.fine_stretch);
    fine_offset_[0] = drifted(s_.fine_tongues);
    fine_offset_[1] = static_cast<float>((fine_cells % wrap) * to_float);
    fine_offset_[2] = static_cast<float>((fine_cells % wrap) * to_float);
    if (s_.swell > 0) compute_swell(t);
  }

  // The swell: at each of kSwellPoints across the fire, a slow random value
  // f in -1..1 (its own seeded signal, swell_rate new values a second) scales
  // the flames' height there, up to 1 / (1 - swell) as high, down to
  // 1 / (1 + swell / 2). The scales are then divided by their mean across the fire,
  // weighted by the fire's depth there, so height moves from one place to
  // another and the lit area stays about the same: a swell that added height
  // made the whole fire's area and brightness swing twice as far as a real
  // fire's (issue 35). The lookup's height is multiplied by the scale, so a
  // flame 1/scale as tall, and the area goes with the mean of 1/scale.
  void compute_swell(int64_t t) {
    const int64_t x = t * s_.swell_rate.raw >> Fixed::kFracBits;
    std::array<float, kSwellPoints> scale{};
    float area = 0, depth_sum = 0;
    for (int i = 0; i < kSwellPoints; ++i) {
      const float f = swell_heights_.noise(x, static_cast<uint32_t>(i)).to_float();
      const auto k = static_cast<size_t>(i);
      scale[k] = 1.0f - s_.swell * std::max(f, -0.5f);
      // The elliptic volume's depth at this point across it (-0.5..0.5).
      const float across = static_cast<float>(i) / (kSwellPoints - 1) - 0.5f;
      const float depth = std::sqrt(std::max(0.25f - across * across, 0.0f)) + 0.05f;
      area += depth / scale[k];
      depth_sum += depth;
    }
    const float mean = area / depth_sum;
    // Never below 1 / (1 + swell / 3), however tall the rest: deeper, the
    // low places open gaps that split the fire (FireplaceFill).
    for (size_t k = 0; k < scale.size(); ++k)
      swell_scale_[k] = std::min(scale[k] * mean, 1.0f + s_.swell / 3);
  }

  struct Uniforms {
    GLint mvp, box_min, box_max, camera, world_scale, noise_scale, step_length, max_steps, bound,
        octaves, weights, offset, flow_cs, time4, lean, displacement, turbulence_mean, intensity,
        obstacle, obstacle_relief, color, perm, grad3, grad4, profile, sheet, rise_growth, wobble,
        ramp_here, slices, tongue_scale, tongue_offset, tongue_gap, glow, tongue_roots, cooling,
        trail_lift, swell, swell_scale, image, uv_per_pixel, composite_color, halo, halo_lod,
        bspline, texels, depth, fine_scale, fine_offset, fine_gap;
  };

  FireSettings s_;
  ProfileBound bound_;
  Vec3 position_;
  int64_t period_;
  QualityGovernor governor_;
  Program program_, composite_;
  Program shutter_fade_;  // a shutter's trail fading (perlinfire_shutter.frag)
  VertexArray vao_;
  Uniforms u_{};
  Texture perm_, grad3_, grad4_, profile_;
  RenderTarget target_;  // reduced render scales: the march, upscaled in the flame pass
  int screen_w_ = 0, screen_h_ = 0;
  // This frame's, from prepare(): quality, the box and where it lies on screen.
  QualityLevel quality_;
  Vec3 box_min_, box_max_;
  Mat4 mvp_;
  int rect_[4] = {0, 0, 0, 0};
  bool visible_ = false, offscreen_ = false;
  bool halo_ = false;  // sheets with a halo: the offscreen target gets mipmaps
  int sub_w_ = 1, sub_h_ = 1;
  bool trail_ = false;  // the target holds the last frame's exposure (a shutter's trail)
  Fixed trail_time_;    // that frame's animation time
  std::array<float, kMaxOctaves> weights_{}, time4_{};
  std::array<float, kMaxOctaves * 3> offsets_{};
  std::array<float, kMaxOctaves * 2> flow_cs_{};
  std::array<float, 3> tongue_offset_{};
  std::array<float, 3> fine_offset_{};
  std::array<float, kSwellPoints> swell_scale_{};  // the lookup's height scale across the fire
  Flicker breath_;
  Flicker swell_heights_;  // the swell's slow random heights, one signal per point across
  Flicker sway_;           // where the tongue field has wandered sideways
  Fixed lean_x_, lean_z_, drift_x_, drift_z_, time_, breath_now_ = Fixed::from_int(1);
  Fixed wind_speed_;  // |wind| at the fire this step (L1), m/s
  bool uniforms_dirty_ = true;
};

class PerlinFireSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext& context) const override {
    return std::make_unique<PerlinFire>(settings, position, context.seed);
  }
  FireSettings settings;
};

std::unique_ptr<ElementSpec> parse(ParamReader& r) {
  auto spec = std::make_unique<PerlinFireSpec>();
  FireSettings& s = spec->settings;
  s.size = r.vec3("size", s.size);
  if (!(s.size.x > 0 && s.size.y > 0 && s.size.z > 0))
    r.fail("size", "expected three positive numbers [width, height, depth] in metres");
  s.shading = r.string("shading", "sheets", {"sheets", "profile"}) == "sheets"
                  ? FireShading::kSheets
                  : FireShading::kProfile;
  int octaves = 4;
  double render_scale = 1.0;
  if (s.shading == FireShading::kProfile) {  // the paper's soft look keeps its old defaults
    s.intensity = 4.0f;
  } else {
    // Tuned against the real fire clips (../shared/eval): a broad, low bed of
    // fire (the clips show a whole log bed, about as wide as the flames are
    // tall) torn into a row of tongues with separate roots, tips that break
    // off, a dim envelope around them, cores clipping to white; detail that
    // decorrelates in about 26 ms.
    s.profile_width = 0.97, s.profile_taper = 0.15, s.profile_height = 0.35;
    s.tongues = 15, s.tongue_gap = 1.0f, s.tongue_width = 0.55f, s.tongue_stretch = 6;
    s.tongue_base = 0.13f, s.tongue_roots = 0.3f, s.glow = 0.5f;
    s.displacement = 2.8f, s.intensity = 22.0f, s.speed = Fixed::from_ratio(3, 2);
    s.frequency = 7.0, s.stretch = 3.0, s.flow_speed = Fixed::from_int(4);
    s.rise_growth = 0.1f, s.wobble = 0.3f, s.sheet_softness = 1.5f, s.breathing = 0.3f;
    s.quality.steps = 12, octaves = 2, render_scale = 0.7;
  }
  const std::string profile = r.path("profile");
  if (!profile.empty()) s.profile = load_fire_profile(profile, r.file(), r.key_path("profile"));
  s.profile_width = r.number("profile_width", s.profile_width, 0.1, 0.97);
  s.profile_taper = r.number("profile_taper", s.profile_taper, 0.1, 2);
  s.profile_height = r.number("profile_height", s.profile_height, 0.1, 0.97);
  const std::string noise =
      r.string("noise", "flow3d", {"simplex3d", "flow3d", "simplex4d", "perlin4d"});
  s.noise = noise == "simplex3d"   ? FireNoise::kSimplex3d
            : noise == "flow3d"    ? FireNoise::kFlow3d
            : noise == "simplex4d" ? FireNoise::kSimplex4d
                                   : FireNoise::kPerlin4d;
  s.quality.octaves = static_cast<int>(r.integer("octaves", octaves, 1, kMaxOctaves));
  s.weight = r.number("weight", s.weight, 0, 4);
  s.gain = r.number("gain", s.gain, 0, 1);
  s.evolve = r.fixed("evolve", s.evolve.to_double(), 0, 10);
  s.displacement = static_cast<float>(r.number("displacement", s.displacement, 0, 4));
  s.intensity = static_cast<float>(r.number("intensity", s.intensity, 0, 100));
  s.sheet_edge = static_cast<float>(r.number("sheet_edge", s.sheet_edge, 0.01, 0.99));
  s.sheet_softness = static_cast<float>(r.number("sheet_softness", s.sheet_softness, 0.001, 2));
  s.rise_growth = static_cast<float>(r.number("rise_growth", s.rise_growth, 0, 1));
  s.wobble = static_cast<float>(r.number("wobble", s.wobble, 0, 2));
  s.stretch = r.number("stretch", s.stretch, 0.25, 8);
  s.breathing = static_cast<float>(r.number("breathing", s.breathing, 0, 2));
  s.tongues = r.number("tongues", s.tongues, 0.1, 32);
  s.tongue_gap = static_cast<float>(r.number("tongue_gap", s.tongue_gap, 0, 1));
  s.tongue_width = static_cast<float>(r.number("tongue_width", s.tongue_width, 0.01, 1));
  s.glow = static_cast<float>(r.number("glow", s.glow, 0, 1));
  s.tongue_roots = static_cast<float>(r.number("tongue_roots", s.tongue_roots, 0, 1));
  s.cooling = static_cast<float>(r.number("cooling", s.cooling, 0, 1));
  s.swell = static_cast<float>(r.number("swell", s.swell, 0, 0.9));
  s.swell_rate = r.fixed("swell_rate", s.swell_rate.to_double(), 0, 60);
  s.halo = static_cast<float>(r.number("halo", s.halo, 0, 1));
  s.halo_radius = static_cast<float>(r.number("halo_radius", s.halo_radius, 0.01, 0.25));
  s.shutter = r.number("shutter", s.shutter, 0, 0.25);
  s.occlude = r.boolean("occlude", s.occlude);
  s.tongue_stretch = r.number("tongue_stretch", s.tongue_stretch, 0.25, 32);
  s.tongue_base = static_cast<float>(r.number("tongue_base", s.tongue_base, 0.01, 1));
  s.fine_tongues = r.number("fine_tongues", s.fine_tongues, 0.1, 64);
  s.fine_gap = static_cast<float>(r.number("fine_gap", s.fine_gap, 0, 1));
  s.fine_width = static_cast<float>(r.number("fine_width", s.fine_width, 0.01, 1));
  s.fine_stretch = r.number("fine_stretch", s.fine_stretch, 0.25, 32);
  s.tongue_sway = r.number("tongue_sway", s.tongue_sway, 0, 8);
  s.tongue_comb = static_cast<float>(r.number("tongue_comb", s.tongue_comb, 0, 2));
  s.speed = r.fixed("speed", s.speed.to_double(), 0, 10);
  s.tongue_rise = r.fixed("tongue_rise", s.tongue_rise.to_double(), 0, 4);
  s.tongue_evolve = r.fixed("tongue_evolve", s.tongue_evolve.to_double(), 0, 4);
  s.frequency = r.number("frequency", s.frequency, 0.1, 32);
  s.flow_speed = r.fixed("flow_speed", s.flow_speed.to_double(), 0, 20);
  s.color = r.color("color", s.color);
  s.additive = r.string("blend", "additive", {"additive", "alpha"}) == "additive";
  s.obstacle = static_cast<float>(r.number("obstacle_height", 0, 0, 0.95));
  s.obstacle_relief = static_cast<float>(r.number("obstacle_relief", 0, 0, 0.5));
  s.wind_lean = r.fixed("wind_lean", s.wind_lean.to_double(), 0, 2);
  s.max_lean = r.fixed("max_lean", s.max_lean.to_double(), 0, 2);
  s.wind_drift = r.fixed("wind_drift", s.wind_drift.to_double(), 0, 4);
  s.quality.steps = static_cast<int>(r.integer("steps", s.quality.steps, 2, 256));
  s.quality.scale = static_cast<float>(r.number("render_scale", render_scale, 0.1, 1.0));
  s.auto_quality = r.string("quality", "fixed", {"fixed", "auto"}) == "auto";
  s.target_fps = r.number("target_fps", s.target_fps, 1, 10000);
  s.min_scale = static_cast<float>(r.number("min_render_scale", s.min_scale, 0.1, 1.0));
  if (s.occlude && s.quality.scale >= 0.999f)
    r.fail("occlude", "needs a render_scale below 1: the reduced-size fire is drawn as one sheet");
  if (s.shutter > 0 && s.quality.scale >= 0.999f)
    r.fail("shutter", "needs a render_scale below 1: the trail is kept in the reduced-size target");
  r.finish();
  return spec;
}

}  // namespace

std::string perlinfire_defines(FireNoise kind, FireShading shading) {
  char defines[320];
  std::snprintf(defines, sizeof defines,
                "#define PF_NOISE_KIND %d\n#define PF_SHADING %d\n"
                "#define PF_SIMPLEX_R2 %.9g\n"
                "#define PF_SIMPLEX3_SCALE %#.9g\n#define PF_SIMPLEX4_SCALE %#.9g\n"
                "#define PF_PERLIN4_SCALE %#.9g\n#define PF_SWELL_POINTS %d\n",
                static_cast<int>(kind), static_cast<int>(shading), NoiseConstants::kSimplexRadius2,
                NoiseConstants::kSimplex3Scale, NoiseConstants::kSimplex4Scale,
                NoiseConstants::kPerlin4Scale, kSwellPoints);
  return defines;
}

std::string perlinfire_fragment_source(std::string_view body, FireNoise kind, FireShading shading) {
  std::string src = compose_shader({"perlinfire_noise.frag", "fire_ramp.frag"},
                                   perlinfire_defines(kind, shading));
  // `body` is the third file: its lines numbered as in its own text, plus 200000.
  if (body.starts_with("#version")) {
    const auto nl = body.find('\n');
    body = nl == std::string_view::npos ? std::string_view{} : body.substr(nl + 1);
    src += "#line 200002\n";
  } else {
    src += "#line 200001\n";
  }
  src += body;
  return src;
}

const ElementKind& perlinfire_kind() {
  static const ElementKind kind{
      "perlinfire", "volumetric fire: simplex noise ray-marched through a swept profile", parse};
  return kind;
}

}  // namespace candela
