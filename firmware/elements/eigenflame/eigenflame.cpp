#include "elements/eigenflame/eigenflame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>

#include "core/error.h"
#include "core/flicker.h"
#include "core/log.h"
#include "elements/eigenflame/flame_shape.h"
#include "embedded_models.h"
#include "flame_drivers/arp_driver.h"
#include "gl/program.h"
#include "model/flame_model.h"
#include "params/params.h"
#include "story/story_plan.h"
#include "story/story_player.h"
#include "wind/lean.h"
#include "wind/wind_field.h"

namespace candela {
namespace {

constexpr float kLabelLean = 0.05f;  // image widths a wind-left/right label adds to a frame's lean

// Each frame's lean: the intensity-weighted centroid x of its reconstruction,
// in image widths from the centre, relative to the calm frames' median.
// Linear in the weights, so per-component sums make this O(frames x E).
std::shared_ptr<EigenModel> derive(std::shared_ptr<const model::FlameModel> m, std::string source) {
  auto em = std::make_shared<EigenModel>();
  em->source = std::move(source);
  const int w = m->width(), e = m->components(), f = m->frames();
  const size_t px = m->mean.pixels();
  std::vector<double> m0(static_cast<size_t>(e) + 1), m1(static_cast<size_t>(e) + 1);
  for (int k = -1; k < e; ++k) {
    double s0 = 0, s1 = 0;
    for (size_t p = 0; p < px; ++p) {
      const double v = k < 0 ? m->mean.value(0, p) : m->eigen.value(k, p);
      const double x = (static_cast<double>(p % w) + 0.5) / w - 0.5;
      s0 += v;
      s1 += v * x;
    }
    m0[static_cast<size_t>(k + 1)] = s0;
    m1[static_cast<size_t>(k + 1)] = s1;
  }
  std::vector<double> lean(static_cast<size_t>(f));
  for (int i = 0; i < f; ++i) {
    const auto wt = m->weights_of(i);
    double s0 = m0[0], s1 = m1[0];
    for (int k = 0; k < e; ++k) s0 += wt[k] * m0[k + 1], s1 += wt[k] * m1[k + 1];
    // Within the image (+-0.5 widths) for a non-negative frame; a model whose
    // reconstruction goes negative could give any ratio: keep it in Q16.16's reach.
    lean[static_cast<size_t>(i)] = s0 > 1e-9 ? std::clamp(s1 / s0, -1.0, 1.0) : 0.0;
  }
  // The calm reference: frames labelled calm, else all frames.
  std::vector<double> calm;
  for (const auto& c : m->clips)
    for (const auto& l : c.labels)
      if (l.label == "calm")
        for (int i = l.from; i < l.to; ++i) calm.push_back(lean[static_cast<size_t>(i)]);
  if (calm.empty()) calm = lean;
  std::nth_element(calm.begin(), calm.begin() + static_cast<ptrdiff_t>(calm.size() / 2),
                   calm.end());
  const double ref = calm[calm.size() / 2];
  for (double& l : lean) l -= ref;
  for (const auto& c : m->clips)
    for (const auto& l : c.labels) {
      const double bias = l.label == "wind-right"  ? kLabelLean
                          : l.label == "wind-left" ? -kLabelLean
                                                   : 0;
      for (int i = l.from; i < l.to; ++i) lean[static_cast<size_t>(i)] += bias;
    }
  em->sigma = weight_sigmas(*m);
  em->lean.reserve(lean.size());
  for (double l : lean) em->lean.push_back(Fixed::from_double(l));
  em->model = std::move(m);
  return em;
}

// transfer = "#000000 #8a1800 #ff8020 #fff0c0": evenly spaced colour stops,
// dark to bright; "#000000@0 #8a1800@0.2 ...": each at its place (0..1 of
// the gray above the black level; all stops placed or none, rising).
std::vector<Vec3> parse_transfer(ParamReader& r, std::vector<float>& places) {
  std::vector<Vec3> stops;
  const std::string text = r.string("transfer", "");
  const std::string what =
      "expected colour stops \"#rrggbb #rrggbb ...\" or placed \"#rrggbb@0 #rrggbb@0.4 ... "
      "#rrggbb@1\" (places 0..1, rising), got \"";
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find_first_of(" ,", at);
    const std::string tok =
        text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    if (tok.empty()) continue;
    unsigned cr = 0, cg = 0, cb = 0;
    const size_t sep = tok.find('@');
    const std::string colour = tok.substr(0, sep);
    if (colour.size() != 7 || colour[0] != '#' ||
        std::sscanf(colour.c_str() + 1, "%2x%2x%2x", &cr, &cg, &cb) != 3)
      r.fail("transfer", what + echo_value(tok) + "\"");
    const bool placed = sep != std::string::npos;
    if (!stops.empty() && placed != !places.empty())
      r.fail("transfer", what + echo_value(tok) + "\": place all stops or none");
    if (placed) {
      const std::string place = tok.substr(sep + 1);
      char* rest = nullptr;
      const double p = place.empty() ? std::nan("") : std::strtod(place.c_str(), &rest);
      if (!std::isfinite(p) || *rest != '\0' || p < 0 || p > 1 ||
          (!places.empty() && p < places.back()))
        r.fail("transfer", what + echo_value(tok) + "\"");
      places.push_back(static_cast<float>(p));
    }
    stops.push_back({cr / 255.0f, cg / 255.0f, cb / 255.0f});
  }
  if (!text.empty() && stops.size() < 2) r.fail("transfer", "expected at least two colour stops");
  return stops;
}

// ---------------------------------------------------------------------------

class EigenFlame final : public Element {
 public:
  // `batch`: the scene's, shared with its other eigen-flames (null: one of its own).
  EigenFlame(const EigenFlameSettings& s, std::shared_ptr<const EigenModel> model, Vec3 position,
             uint64_t seed, EigenBatch* batch,
             std::shared_ptr<const story::StoryDesc> story = nullptr,
             std::shared_ptr<const story::StoryPlan> planned = nullptr, uint64_t planned_seed = 0)
      : s_(s),
        model_(std::move(model)),
        position_(position),
        own_batch_(batch == nullptr),
        flicker_(seed ^ 0x666c6963ULL) {
    const model::FlameModel& m = *model_->model;
    const double fps = m.clips.empty() ? 30.0 : m.clips.front().fps;
    // Model frames per animation step (60 steps per second; the step length is known in update).
    fps_ = Fixed::from_double(fps) * s.speed;
    FlameLookSettings look;
    const float hue = s.has_hue ? s.hue : m.colour.hue;
    const float sat = s.has_saturation ? s.saturation : m.colour.saturation;
    const float black = m.colour.black_level;
    look.ramp = s.transfer.size() >= 2 ? transfer_ramp(s.transfer, black, s.transfer_at)
                                       : hls_ramp(hue, sat, black, s.has_hue_top ? s.hue_top : hue);
    look.brightness = s.brightness;
    look.glow_radius = s.has_glow_radius ? s.glow_radius : std::max(0.02f, m.colour.glow_radius);
    look.glow_strength = s.has_glow_strength ? s.glow_strength : m.colour.glow_strength;
    look.edge_fade = s.edge_fade;
    look.foot_fade[0] = s.foot_fade[0];
    look.foot_fade[1] = s.foot_fade[1];
    const int e = s.components > 0 ? s.components : EigenReconstructor::kMaxComponents;

    if (s.driver == EigenDriver::kStory && story) {
      // The whole story planned now (its own seed, else the element's); the
      // runtime always loops it, through the first segment's transition.
      // Planned once: the parse's plan where its seed is this element's.
      const uint64_t story_seed = story->has_seed ? story->seed : seed;
      std::shared_ptr<const story::StoryPlan> plan = planned;
      if (!plan || planned_seed != story_seed)
        plan = std::make_shared<const story::StoryPlan>(
            story::plan_story(*story, m, story_seed, true));
      story_ = std::make_unique<story::StoryPlayer>(*plan, m.components(), Fixed::from_ratio(1, 2));
      renderer_ =
          std::make_unique<EigenRenderer>(image_stack_of(m.mean), image_stack_of(m.eigen), s.layout,
                                          e, look, edited(story_->weights()), batch);
    } else if (s.driver == EigenDriver::kArp && m.has_learning_flames) {
      const auto& L = m.flames;
      shape_ = std::make_unique<FlameShapeModel>(FlameShapeModel::from(m));
      arp_ = std::make_unique<ArpProcess>(ArpView::of(L), seed);
      prev_.fill(0);
      next_.fill(0);
      const auto st = arp_->state();
      std::copy(st.begin(), st.end(), prev_.begin());
      const auto s1 = arp_->step();
      std::copy(s1.begin(), s1.end(), next_.begin());
      shown_ = prev_;
      renderer_ = std::make_unique<EigenRenderer>(
          image_stack_of(L.mean), image_stack_of(L.eigen), s.layout, L.ne, look,
          std::span<const float>(shown_.data() + L.np + L.nw + 1, static_cast<size_t>(L.ne)),
          batch);
    } else {
      if (s.driver == EigenDriver::kArp)
        LOG_WARN("eigenflame: %s has no Learning Flames part; playing its motion graph instead",
                 model_->source.c_str());
      GraphWalker walker(m.graph, m.weights, m.components(), model_->lean, s.walk, seed);
      player_ = std::make_unique<GraphPlayer>(std::move(walker), m.weights, m.components(),
                                              Fixed::from_ratio(1, 2));
      renderer_ =
          std::make_unique<EigenRenderer>(image_stack_of(m.mean), image_stack_of(m.eigen), s.layout,
                                          e, look, edited(player_->weights()), batch);
      // The walk shows the model's own frames: each one's reconstruction kept,
      // as the scene's weight edits show it (else every edited frame differs
      // from its cached one in every component: the full sum each frame).
      // The edits are applied only where this flame's cache is the one made:
      // other flames of its model share the first one's.
      const int stride = m.components();
      if (stride > 0 && renderer_->wants_frame_cache()) {
        std::span<const float> frames = m.weights;
        std::vector<float> edited_frames;  // the cache keeps a copy
        if (!s_.weights.identity()) {
          edited_frames.resize(m.weights.size());
          const size_t n = static_cast<size_t>(stride);
          for (size_t at = 0; at + n <= m.weights.size(); at += n)
            apply_weight_edits(frames.subspan(at, n), model_->sigma, s_.weights,
                               std::span<float>(edited_frames).subspan(at, n));
          frames = edited_frames;
        }
        renderer_->cache_frames(frames, static_cast<int>(frames.size() / stride), stride);
      }
      renderer_->set_frame(player_->shown_frame());
    }
    // The images are on the GPU now: a built-in model's pages in the binary
    // are given back (its other flames share this upload; issue 36: the eigen
    // fireplace held 6.3 MB of them resident for its whole run).
    if (const size_t given = m.give_back_image_pages())
      LOG_DEBUG("eigenflame: %s: %.1f MB of the built-in model's images given back after upload",
                model_->source.c_str(), static_cast<double>(given) / (1 << 20));
    if (s.embers.enabled) {
      embers_ =
          Program::from_library("floor_quad.vert", {"value_noise.frag", "eigenflame_embers.frag"});
      embers_vao_ = make_vertex_array();
      ue_ = {embers_.uniform("u_view_projection"),
             embers_.uniform("u_centre"),
             embers_.uniform("u_half"),
             embers_.uniform("u_time"),
             embers_.uniform("u_colour"),
             embers_.uniform("u_noise_seed")};
      ember_seed_ = static_cast<float>(seed % 1000) / 1000.0f;
    }
  }

  void update(const StepContext& step) override {
    // The wind this flame feels sets the lean it should show (first-order lag).
    WindSample w{};
    if (step.wind) w = step.wind->sample(position_);
    const Fixed k = lag_gain(step.dt, s_.lean_response);
    lean_ = lean_toward(lean_, w.x, s_.wind_lean, s_.max_lean, k);
    wind_x_ += (w.x - wind_x_) * k;  // the wind the flame has caught up with (arp bending)
    time_ = step.time;
    light_ = s_.flicker.raw > 0 ? Fixed::from_int(1) + s_.flicker * flicker_.flutter(step.time)
                                : Fixed::from_int(1);
    const Fixed per_step = fps_ * step.dt;
    if (story_) {
      story_->set_rate(per_step);
      story_->set_crossfade(s_.crossfade);
      story_->step();
      edited(story_->weights());
    } else if (player_) {
      player_->set_rate(per_step);
      player_->set_crossfade(s_.crossfade);
      player_->step(lean_);
      edited(player_->weights());
      renderer_->set_frame(player_->shown_frame());
    } else if (arp_) {
      phase_ += per_step;
      while (phase_ >= Fixed::from_int(1)) {
        phase_ -= Fixed::from_int(1);
        prev_ = next_;
        const auto st = arp_->step();
        std::copy(st.begin(), st.end(), next_.begin());
      }
      // The state shown between two model frames (display only: float is fine).
      const float t = fade(phase_, s_.crossfade);
      for (int i = 0; i < shape_->dim(); ++i) shown_[i] = prev_[i] + (next_[i] - prev_[i]) * t;
    }
  }

  // Sound: the wind at the flames (a gust's whoosh); the fire's own sound
  // comes from the hearth it burns on.
  void add_sound_cue(SoundCue& cue) const override { cue.wind = std::max(cue.wind, abs(wind_x_)); }

  // The clock and lean, the frame the walk or story shows, and the weights
  // drawn (floats, but from integer choices and IEEE arithmetic alone).
  void hash_state(StateHash& hash) const override {
    for (Fixed v : {fps_, lean_, phase_, time_, wind_x_}) hash.add(v);
    if (story_) {
      hash.add(story_->frame());
      hash.add(story_->weights());
    } else if (player_) {
      hash.add(player_->shown_frame());
      hash.add(player_->weights());
    } else if (arp_) {
      const auto d = static_cast<size_t>(shape_->dim());
      hash.add(std::span<const float>(prev_.data(), d));
      hash.add(std::span<const float>(next_.data(), d));
    }
    hash.add(std::span<const float>(edited_));
  }

  // The flame's offscreen work (reconstruction, glow, sprite) is its
  // batch's: in a scene, the scene prepares the shared batch once per frame
  // for all its eigen-flames (a SceneResource); made without one, the flame
  // prepares its own.
  void prepare(const FrameContext&) override {
    if (own_batch_) renderer_->prepare();
  }

  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass == DrawPass::kBody && embers_.id()) draw_embers(f);
    if (pass != (s_.in_front ? DrawPass::kOverlay : DrawPass::kFlame)) return;
    FlamePose pose;
    pose_now(pose);
    renderer_->composite(f.view, f.view_projection, pose);
  }

  // The flame's billboard (its glow's margin included) and the ember bed.
  bool drawn_bounds(const FrameContext& f, Box3& box) const override {
    FlamePose pose;
    pose_now(pose);
    renderer_->add_bounds(f.view, pose, box);
    if (embers_.id()) {
      const Vec3 c = embers_centre();
      const float hw = s_.embers.width * 0.5f, hd = s_.embers.depth * 0.5f;
      box.add(c + Vec3{-hw, 0, -hd});
      box.add(c + Vec3{hw, 0, hd});
    }
    return true;
  }

 private:
  // The weights the renderer shows: the driver's own, or with the scene's
  // weight edits applied (the studio's function) into edited_.
  std::span<const float> edited(std::span<const float> base) {
    if (s_.weights.identity()) return base;
    edited_.resize(base.size());  // the same size every frame: no reallocation after the first
    apply_weight_edits(base, model_->sigma, s_.weights, edited_);
    return edited_;
  }

  // The pose the flame pass draws this frame.
  void pose_now(FlamePose& pose) const {
    pose.origin = position_;
    pose.height = s_.height;
    pose.widen = s_.widen;
    pose.light = light_.to_float();
    if (shape_) {
      pose.deform = true;
      shape_->pose({shown_.data(), static_cast<size_t>(shape_->dim())},
                   wind_x_.to_float() * s_.wind_bend.to_float(), pose);
    }
  }

  // The ember bed's quad (floor_quad.vert) lies just above the floor.
  Vec3 embers_centre() const { return {position_.x, position_.y + 0.002f, position_.z}; }

  void draw_embers(const FrameContext& f) {
    embers_.use();
    glUniformMatrix4fv(ue_[0], 1, GL_FALSE, f.view_projection.m);
    const Vec3 c = embers_centre();
    glUniform3f(ue_[1], c.x, c.y, c.z);
    glUniform2f(ue_[2], s_.embers.width * 0.5f, s_.embers.depth * 0.5f);
    glUniform1f(ue_[3], static_cast<float>(time_.to_double()));
    glUniform3f(ue_[4], s_.embers.colour.x, s_.embers.colour.y, s_.embers.colour.z);
    glUniform1f(ue_[5], ember_seed_);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glBindVertexArray(embers_vao_.get());
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_BLEND);
  }

  EigenFlameSettings s_;
  std::shared_ptr<const EigenModel> model_;
  Vec3 position_;
  bool own_batch_;
  Fixed fps_, lean_, phase_, time_, wind_x_, light_ = Fixed::from_int(1);
  Flicker flicker_;
  std::unique_ptr<GraphPlayer> player_;
  std::unique_ptr<story::StoryPlayer> story_;
  std::unique_ptr<ArpProcess> arp_;
  std::unique_ptr<FlameShapeModel> shape_;
  std::array<float, ArpProcess::kMaxDim> prev_{}, next_{}, shown_{};
  std::vector<float> edited_;
  std::unique_ptr<EigenRenderer> renderer_;
  Program embers_;
  VertexArray embers_vao_;
  std::array<GLint, 6> ue_{};
  float ember_seed_ = 0;
};

}  // namespace

std::shared_ptr<const EigenModel> load_eigen_model(const std::string& path) {
  auto m = std::make_shared<const model::FlameModel>(model::FlameModel::load(path));
  return derive(std::move(m), path);
}

std::shared_ptr<const EigenModel> builtin_eigen_model(const std::string& name) {
  static std::mutex mu;
  static std::map<std::string, std::shared_ptr<const EigenModel>> cached;
  std::lock_guard<std::mutex> lock(mu);
  // The default model is the candle model: one file, two names.
  const std::string file = name == "candle" ? "default" : name;
  auto& slot = cached[file];
  if (!slot) {
    const auto bytes = eigen_models::find(file + ".cmodel");
    if (bytes.empty())
      throw ConfigError("<built-in models>", name,
                        "no such built-in model (built in: default, candle, fire)");
    const std::string source = "<built-in " + file + ">";
    // Read where the binary holds it: a copy would cost the model's size again.
    auto m = std::make_shared<const model::FlameModel>(
        model::FlameModel::from(model::ModelFile::from_static(bytes, source)));
    slot = derive(std::move(m), source);
  }
  return slot;
}

std::shared_ptr<const EigenModel> default_eigen_model() { return builtin_eigen_model("default"); }

std::unique_ptr<Element> EigenFlameSpec::create(const SceneContext& context) const {
  EigenBatch* batch = context.resources ? &context.resources->get<EigenBatch>() : nullptr;
  try {
    return std::make_unique<EigenFlame>(settings, model, position, context.seed, batch, story,
                                        story_plan, story_plan_seed);
  } catch (const std::exception& e) {
    // A model the reader accepted but this GPU cannot hold (texture size, ...):
    // play the built-in one rather than leave the flame out.
    const auto fallback = default_eigen_model();
    if (model == fallback) throw;
    LOG_ERROR(
        "%s: eigenflame: model %s cannot be played here (%s); using the built-in default model",
        context.scene_file.c_str(), model->source.c_str(), e.what());
    return std::make_unique<EigenFlame>(settings, fallback, position, context.seed, batch);
  }
}

void EigenFlameSpec::prepare_for(uint64_t element_seed) {
  if (!story || !story_plan) return;  // no story, or one that did not plan (story_error)
  const uint64_t seed = story->has_seed ? story->seed : element_seed;
  if (seed == story_plan_seed) return;
  try {
    story_plan = std::make_shared<const story::StoryPlan>(
        story::plan_story(*story, *model->model, seed, true));
    story_plan_seed = seed;
  } catch (const std::exception&) {
    // Planned once already without error (its errors do not depend on the
    // seed); create() plans again and reports whatever it is.
  }
}

std::string EigenFlameSpec::problem() const {
  if (!story_error.empty())
    return story_error + "; playing the graph walk of " + model->source + " instead";
  return model_error.empty() ? model_error : model_error + "; using the built-in default model";
}

std::unique_ptr<EigenFlameSpec> parse_eigenflame(ParamReader& r) {
  auto spec = std::make_unique<EigenFlameSpec>();
  EigenFlameSettings& s = spec->settings;
  const std::string model_name = r.string("model", "");
  const std::string story_name = r.string("story", "");
  s.height = static_cast<float>(r.number("height", s.height, 0.001, 100));
  s.widen = static_cast<float>(r.number("widen", s.widen, 0.1, 10));
  {
    const std::string d =
        r.string("driver", story_name.empty() ? "graph" : "story", {"graph", "arp", "story"});
    s.driver = d == "arp"     ? EigenDriver::kArp
               : d == "story" ? EigenDriver::kStory
                              : EigenDriver::kGraph;
    if (s.driver == EigenDriver::kStory && story_name.empty())
      r.fail("story", "expected a story file (story = \"tour.toml\") for driver = \"story\"");
    if (!story_name.empty() && s.driver != EigenDriver::kStory)
      r.fail("driver", "expected \"story\" (or no driver) with story = \"" + story_name + "\"");
    if (!story_name.empty() && !model_name.empty())
      r.fail("model", "expected no model with story = \"" + story_name +
                          "\" (the story file names its model)");
  }
  s.components =
      static_cast<int>(r.integer("components", 0, 0, EigenReconstructor::kMaxComponents));
  s.layout = r.string("layout", "packed", {"packed", "layered"}) == "layered"
                 ? StackLayout::kLayered
                 : StackLayout::kPacked;
  s.speed = r.fixed("speed", 1.0, 0.05, 8.0);
  s.crossfade = r.fixed("crossfade", s.crossfade.to_double(), 0, 1);
  s.edge_fade = static_cast<float>(r.number("edge_fade", s.edge_fade, 0, 0.5));
  if (r.has("foot_fade")) {
    const auto foot = r.numbers("foot_fade", 0, 1, 2);
    if (foot.size() != 2 || !(foot[0] < foot[1]))
      r.fail("foot_fade",
             "expected [from, to]: two heights in the image, 0 (its bottom) to 1 (its top), from "
             "lower than to");
    s.foot_fade[0] = static_cast<float>(foot[0]);
    s.foot_fade[1] = static_cast<float>(foot[1]);
  }
  s.in_front = r.boolean("in_front", s.in_front);
  s.has_hue = r.has("hue");
  s.hue = static_cast<float>(r.number("hue", s.hue, 0, 360));
  s.has_hue_top = r.has("hue_top");
  s.hue_top = static_cast<float>(r.number("hue_top", s.hue_top, 0, 360));
  s.has_saturation = r.has("saturation");
  s.saturation = static_cast<float>(r.number("saturation", s.saturation, 0, 1));
  s.transfer = parse_transfer(r, s.transfer_at);
  {
    const auto offsets = r.numbers("weight_offsets", -EigenWeightEdits::kMaxOffset,
                                   EigenWeightEdits::kMaxOffset, EigenWeightEdits::kShapeWeights);
    for (size_t k = 0; k < offsets.size(); ++k)
      s.weights.offset_sigma[k] = static_cast<float>(offsets[k]);
    s.weights.detail_scale = static_cast<float>(
        r.number("detail_scale", s.weights.detail_scale, 0, EigenWeightEdits::kMaxDetailScale));
    if (s.driver == EigenDriver::kArp && !s.weights.identity())
      r.fail(r.has("weight_offsets") ? "weight_offsets" : "detail_scale",
             "expected no weight edits with driver = \"arp\" (its weights are the Learning "
             "Flames model's own; graph and story drivers take them)");
  }
  s.brightness = static_cast<float>(r.number("brightness", s.brightness, 0, 16));
  s.flicker = r.fixed("flicker", s.flicker.to_double(), 0, 1);
  s.has_glow_radius = r.has("glow_radius");
  s.glow_radius = static_cast<float>(r.number("glow_radius", s.glow_radius, 0, 1));
  s.has_glow_strength = r.has("glow_strength");
  s.glow_strength = static_cast<float>(r.number("glow_strength", s.glow_strength, 0, 8));
  {
    ParamReader g = r.table("graph");
    s.walk.max_stretch = static_cast<int>(g.integer("max_stretch", s.walk.max_stretch, 1, 100000));
    s.walk.window = static_cast<int>(g.integer("window", s.walk.window, 1, 1000000));
    s.walk.jump_chance = g.fixed("jump_chance", s.walk.jump_chance.to_double(), 0, 1);
    s.walk.steer_chance = g.fixed("steer_chance", s.walk.steer_chance.to_double(), 0, 1);
    s.walk.lean_tolerance = g.fixed("lean_tolerance", s.walk.lean_tolerance.to_double(), 0.001, 1);
    g.finish();
  }
  {
    ParamReader w = r.table("wind");
    s.wind_lean = w.fixed("lean", s.wind_lean.to_double(), 0, 2);
    s.max_lean = w.fixed("max_lean", s.max_lean.to_double(), 0, 2);
    s.lean_response = w.fixed("response", s.lean_response.to_double(), 0.01, 100);
    s.wind_bend = w.fixed("bend", s.wind_bend.to_double(), 0, 4);
    w.finish();
  }
  if (r.has("embers")) {
    ParamReader e = r.table("embers");
    s.embers.enabled = true;
    s.embers.width = static_cast<float>(e.number("width", s.embers.width, 0.01, 100));
    s.embers.depth = static_cast<float>(e.number("depth", s.embers.depth, 0.01, 100));
    s.embers.colour = e.color("colour", s.embers.colour);
    e.finish();
  }
  r.finish();

  // A story: read, its model opened and the story planned now (so `candela
  // --check` reports what is wrong); on failure the element walks the graph
  // of the story's model if that opened, else of the built-in model.
  if (!story_name.empty()) {
    try {
      auto desc = std::make_shared<story::StoryDesc>(story::open_story(story_name, r.file()));
      const std::string mp = story::story_model_path(*desc);
      try {
        spec->model =
            mp.rfind("builtin:", 0) == 0 ? builtin_eigen_model(mp.substr(8)) : load_eigen_model(mp);
      } catch (const std::exception& e) {
        throw ConfigError(desc->file, "model", e.what());
      }
      // Planned now, to find its errors (none depends on the seed) and to be
      // played by create() where the element's seed is the story's.
      spec->story_plan = std::make_shared<const story::StoryPlan>(
          story::plan_story(*desc, *spec->model->model, desc->seed, true));
      spec->story_plan_seed = desc->seed;
      spec->story = std::move(desc);
    } catch (const std::exception& e) {
      spec->story_error = r.key_path("story") + ": " + e.what();
      s.driver = EigenDriver::kGraph;
    }
  }
  // The model: validated now (so `candela --check` reports it); on failure the
  // element plays the built-in model instead.
  if (!model_name.empty()) {
    try {
      // "builtin:NAME": a model embedded in the runtime (firmware/models/NAME.cmodel).
      if (model_name.rfind("builtin:", 0) == 0)
        spec->model = builtin_eigen_model(model_name.substr(8));
      else
        spec->model = load_eigen_model(resolve_relative(r.file(), model_name));
    } catch (const std::exception& e) {
      spec->model_error = r.key_path("model") + ": " + e.what();  // logged by Scene, --check fails
    }
  }
  if (!spec->model) spec->model = default_eigen_model();
  if (s.driver == EigenDriver::kArp && !spec->model->model->has_learning_flames)
    LOG_WARN(
        "%s: %s: model %s has no Learning Flames part; driver \"arp\" will play its motion graph",
        r.file().c_str(), r.key_path("driver").c_str(), spec->model->source.c_str());
  return spec;
}

const ElementKind& eigenflame_kind() {
  static const ElementKind k{
      "eigenflame", "a flame played from an EigenFires / Learning Flames model, on the GPU",
      [](ParamReader& r) -> std::unique_ptr<ElementSpec> { return parse_eigenflame(r); }};
  return k;
}

}  // namespace candela
