#include "session.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "elements/eigenflame/eigenflame.h"
#include "model/flame_model.h"
#include "story/story_file.h"
#include "story/story_plan.h"

namespace candela::studio {
namespace {

constexpr size_t kUndoDepth = 256;

std::shared_ptr<const EigenModel> open_model(const std::string& name) {
  if (name.rfind("builtin:", 0) == 0) return builtin_eigen_model(name.substr(8));
  return load_eigen_model(name);
}

// A name as a scene anywhere can find it: builtin:NAME as it is, a file absolute.
std::string scene_path(const std::string& name) {
  if (name.rfind("builtin:", 0) == 0) return name;
  return std::filesystem::absolute(name).lexically_normal().string();
}

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The shortest text that reads back as the same float: the scene plays
// exactly the value the studio showed.
std::string num(float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

void set_method(story::TransitionSpec& t, story::Method m) {
  if (m == story::Method::kBridge && t.method != m) t.steps = 0;
  if (m == story::Method::kGrow && t.steps < 2) t.steps = 20;
  t.method = m;
}

Session::Session(std::string model, std::string story)
    : model_name_(std::move(model)), story_name_(std::move(story)) {
  try {
    model_ = open_model(model_name_);
  } catch (const std::exception& e) {
    const std::string what = e.what();
    error_ = what.find(model_name_) == std::string::npos ? model_name_ + ": " + what : what;
    return;
  }
  const model::FlameModel& m = *model_->model;
  if (!story_name_.empty()) {
    try {
      const story::StoryDesc desc = story::open_story(story_name_);
      const std::string named = story::story_model_path(desc);
      if (named != model_name_)
        status = "the story names " + named + "; planned against " + model_name_ +
                 " (a saved scene plays the story's own model)";
      // The runtime always loops a story (through the first segment's transition).
      plan_ = std::make_unique<story::StoryPlan>(story::plan_story(desc, m, desc.seed, true));
      desc_ = std::make_shared<const story::StoryDesc>(desc);
    } catch (const std::exception& e) {
      const std::string what = e.what();
      error_ = what.find(story_name_) == std::string::npos ? story_name_ + ": " + what : what;
      story_failed_ = true;
      model_.reset();
      return;
    }
  }
  // Each weight's spread over the model's frames: the sliders' unit (the element's too).
  sigma_ = model_->sigma;
  const int e = m.components();
  base_.assign(static_cast<size_t>(e), 0.0f);
  shown_ = base_;
  edits_.look.hue = m.colour.hue;
  edits_.look.saturation = m.colour.saturation;
  edits_.look.glow_radius = std::max(0.02f, m.colour.glow_radius);
  edits_.look.glow_strength = m.colour.glow_strength;
  update_shown();
}

Session::~Session() = default;

int Session::frames() const {
  if (!model_) return 0;
  return plan_ ? plan_->frames() : model_->model->frames();
}

int Session::model_frame(int i) const {
  if (!model_ || frames() == 0) return -1;
  i = ((i % frames()) + frames()) % frames();
  return plan_ ? plan_->model_frame(i) : i;
}

int Session::clip_of_frame(int f) const {
  if (!model_ || f < 0) return -1;
  return model_->model->clip_of(f);
}

double Session::fps() const {
  if (!model_) return 30;
  if (plan_) return plan_->fps();
  const auto& clips = model_->model->clips;
  return clips.empty() ? 30.0 : clips.front().fps;
}

int Session::shape_weights() const {
  return ok() ? std::min(WeightEdits::kShapeWeights, model_->model->components()) : 0;
}

void Session::seek(int frame) {
  if (frames() == 0) return;
  pos_ = ((frame % frames()) + frames()) % frames();
  update_shown();
}

void Session::step(int n) {
  playing = false;
  seek(this->frame() + n);
}

void Session::seek_model_frame(int mf) {
  for (int i = 0; i < frames(); ++i)
    if (model_frame(i) == mf) {
      seek(i);
      return;
    }
}

void Session::advance(double seconds) {
  if (!ok()) return;
  if (playing && frames() > 0) {
    pos_ += seconds * fps() * std::clamp(speed, 0.05f, 8.0f);
    pos_ = std::fmod(pos_, static_cast<double>(frames()));
    if (pos_ < 0) pos_ += frames();
  }
  update_shown();
}

void Session::update_shown() {
  if (!ok()) return;
  const int e = model_->model->components();
  const int i = frame(), j = (i + 1) % frames();
  const float* a = plan_ ? plan_->weights_of(i) : model_->model->weights_of(i).data();
  const float* b = plan_ ? plan_->weights_of(j) : model_->model->weights_of(j).data();
  const double phase = pos_ - i;
  const float t = static_cast<float>(std::clamp((phase - 0.75) / 0.25, 0.0, 1.0));
  const int ne = plan_ ? std::min(e, plan_->components()) : e;
  for (int k = 0; k < e; ++k) {
    const size_t u = static_cast<size_t>(k);
    base_[u] = k < ne ? a[k] + (b[k] - a[k]) * t : 0.0f;
  }
  apply_weight_edits(base_, sigma_, edits_.weights, shown_);
}

void Session::begin_edit(const Edits& before) {
  gesture_.clear();
  if (!undo_.empty() && undo_.back().edits == before && undo_.back().story == desc_) return;
  undo_.push_back({before, desc_});
  if (undo_.size() > kUndoDepth) undo_.erase(undo_.begin());
}

void Session::set_offset(int k, float sigmas) {
  if (k < 0 || k >= shape_weights()) return;
  edits_.weights.offset_sigma[static_cast<size_t>(k)] =
      std::clamp(sigmas, -WeightEdits::kMaxOffset, WeightEdits::kMaxOffset);
  update_shown();
}

void Session::set_detail_scale(float s) {
  edits_.weights.detail_scale = std::clamp(s, 0.0f, WeightEdits::kMaxDetailScale);
  update_shown();
}

void Session::set_look(const Look& l) {
  edits_.look.hue = std::clamp(l.hue, 0.0f, 360.0f);
  edits_.look.has_hue_top = l.has_hue_top;
  edits_.look.hue_top = std::clamp(l.hue_top, 0.0f, 360.0f);
  edits_.look.saturation = std::clamp(l.saturation, 0.0f, 1.0f);
  edits_.look.brightness = std::clamp(l.brightness, 0.0f, 16.0f);
  edits_.look.glow_radius = std::clamp(l.glow_radius, 0.0f, 1.0f);
  edits_.look.glow_strength = std::clamp(l.glow_strength, 0.0f, 8.0f);
  edits_.look.transfer = l.transfer;
  if (edits_.look.transfer.size() > Look::kMaxStops) edits_.look.transfer.resize(Look::kMaxStops);
  if (edits_.look.transfer.size() == 1) edits_.look.transfer.clear();
  for (auto& c : edits_.look.transfer)
    for (float& v : c) v = std::clamp(v, 0.0f, 1.0f);
  // Each stop's place: as many as the stops (else evenly spaced), rising, in 0..1.
  auto& at = edits_.look.transfer_at;
  at = l.transfer_at;
  if (at.size() != edits_.look.transfer.size()) at = Look::even_places(edits_.look.transfer.size());
  for (size_t i = 0; i < at.size(); ++i) at[i] = std::clamp(at[i], i > 0 ? at[i - 1] : 0.0f, 1.0f);
}

void Session::set_stop_place(int k, float place) {
  auto& at = edits_.look.transfer_at;
  if (k < 0 || static_cast<size_t>(k) >= at.size()) return;
  const size_t u = static_cast<size_t>(k);
  at[u] = std::clamp(place, u > 0 ? at[u - 1] : 0.0f, u + 1 < at.size() ? at[u + 1] : 1.0f);
}

void Session::reset_edits() {
  begin_edit();
  edits_.weights = WeightEdits{};
  update_shown();
}

bool Session::undo() {
  gesture_.clear();
  if (undo_.empty()) return false;
  edits_ = undo_.back().edits;
  if (undo_.back().story != desc_) {
    if (undo_.back().story) {
      replan(undo_.back().story);
    } else {  // back to no story: the model's clips
      desc_.reset();
      plan_.reset();
      seek(frame());
    }
  }
  undo_.pop_back();
  update_shown();
  return true;
}

bool Session::replan(std::shared_ptr<const story::StoryDesc> desc) {
  try {
    // The runtime always loops a story (through the first segment's transition).
    auto plan = std::make_unique<story::StoryPlan>(
        story::plan_story(*desc, *model_->model, desc->seed, true));
    plan_ = std::move(plan);
    desc_ = std::move(desc);
  } catch (const std::exception& e) {
    status = e.what();
    return false;
  }
  seek(frame());  // wraps into the new length
  return true;
}

bool Session::new_story() {
  if (!ok()) return false;
  const model::FlameModel& m = *model_->model;
  auto d = std::make_shared<story::StoryDesc>();
  d->file = "<new story>";
  d->model = model_name_;
  for (const auto& c : m.clips) {
    if (d->segments.size() >= story::kMaxSegments) break;
    story::SegmentSpec g;
    g.clip = c.name;
    d->segments.push_back(g);
  }
  if (d->segments.empty()) {
    story::SegmentSpec g;
    g.to = m.frames();
    d->segments.push_back(g);
  }
  return edit_story([&](story::StoryDesc& s) { s = *d; });
}

bool Session::edit_story(const std::function<void(story::StoryDesc&)>& change,
                         const std::string& gesture) {
  if (!ok()) return false;
  auto d =
      desc_ ? std::make_shared<story::StoryDesc>(*desc_) : std::make_shared<story::StoryDesc>();
  change(*d);
  if (d->segments.empty()) {
    status = "a story needs at least one segment";
    return false;
  }
  // Read back from the text "Save story" writes: validated as the story
  // reader validates a file (and keyed by place: "segment[2].transition").
  std::shared_ptr<const story::StoryDesc> read;
  try {
    read = std::make_shared<const story::StoryDesc>(
        story::load_story_text(story_text_of(*d), "<studio story>"));
  } catch (const std::exception& e) {
    status = e.what();
    return false;
  }
  const auto before = desc_;
  const Edits edits = edits_;
  if (!replan(read)) return false;
  const bool same_gesture = !gesture.empty() && gesture == gesture_;
  gesture_ = gesture;
  if (same_gesture && !undo_.empty()) return true;  // the step before the gesture holds
  if (!undo_.empty() && undo_.back().edits == edits && undo_.back().story == before) return true;
  undo_.push_back({edits, before});
  if (undo_.size() > kUndoDepth) undo_.erase(undo_.begin());
  return true;
}

float Session::joint_seam(int seg) const {
  if (!plan_) return -1;
  const std::string key = "segment[" + std::to_string(seg) + "].transition";
  float worst = -1;
  for (const auto& j : plan_->joints())
    if (j.key == key) worst = std::max(worst, j.seam_ratio);
  return worst;
}

int Session::joint_frame(int seg) const {
  if (!plan_) return -1;
  const std::string key = "segment[" + std::to_string(seg) + "].transition";
  for (const auto& j : plan_->joints())
    if (j.key == key) return j.first;
  return -1;
}

bool Session::preview_joint(int seg) {
  const int at = joint_frame(seg);
  if (at < 0) return false;
  seek(at - static_cast<int>(std::lround(2 * fps())));
  playing = true;
  return true;
}

std::string Session::story_text() const { return desc_ ? story_text_of(*desc_) : std::string{}; }

std::string Session::story_text_of(const story::StoryDesc& d) const {
  std::string s = "# Written by candela-tool studio.\n# candela-tool story THIS_FILE --no-render\n";
  s += "model = " + toml_string(scene_path(model_name_)) + "\n";
  if (d.has_seed) s += "seed = " + std::to_string(d.seed) + "\n";
  s += std::string("loop = ") + (d.loop ? "true" : "false") + "\n";
  s += "components = " + std::to_string(d.components) + "\n";
  for (const auto& g : d.segments) {
    s += "\n[[segment]]\n";
    if (g.kind == story::SegmentKind::kFrames) {
      if (!g.clip.empty()) s += "clip = " + toml_string(g.clip) + "\n";
      if (g.clip.empty() || g.from != 0) s += "from = " + std::to_string(g.from) + "\n";
      if (g.to >= 0) s += "to = " + std::to_string(g.to) + "\n";
    } else {
      s += std::string(g.kind == story::SegmentKind::kArp ? "arp" : "walk") + " = " +
           num(static_cast<float>(g.seconds)) + "\n";
    }
    if (g.repeat != 1) s += "repeat = " + std::to_string(g.repeat) + "\n";
    const story::TransitionSpec& t = g.transition;
    s += "transition = { method = \"" + std::string(story::method_name(t.method)) + "\"";
    if (t.method == story::Method::kLowpass)
      s += ", kernel = [" + num(t.kernel[0]) + ", " + num(t.kernel[1]) + ", " + num(t.kernel[2]) +
           "], components = " + std::to_string(t.components);
    if (t.method == story::Method::kBridge || t.method == story::Method::kGrow)
      s += ", steps = " + std::to_string(t.steps) + ", theta_min = " + num(t.theta_min) +
           ", reject_tail = " + std::to_string(t.reject_tail);
    s += " }\n";
  }
  return s;
}

void Session::save_story(const std::string& path) {
  if (!desc_) throw RuntimeError(path + ": no story to save (start one: New story)");
  write_atomic(path, story_text());
  story_name_ = path;
}

std::string Session::scene_text() const {
  const Look& l = edits_.look;
  std::string s;
  s += "# Written by candela-tool studio (" + model_name_ +
       (story_name_.empty() ? "" : ", story " + story_name_) + ").\n";
  s += "# candela --scene THIS_FILE\nseed = 1\n\n[background]\ncolor = \"#000000\"\n\n";
  s += "[camera]\nposition = [0.0, 0.32, 1.7]\ntarget = [0.0, 0.3, 0.0]\nfov = 40\n\n";
  s += "[[element]]\nkind = \"eigenflame\"\n";
  if (!story_name_.empty())
    s += "story = " + toml_string(scene_path(story_name_)) + "\n";
  else
    s += "model = " + toml_string(scene_path(model_name_)) + "\n";
  s += "position = [0.0, 0.0, 0.0]\nheight = 0.62\n";
  s += "speed = " + num(std::clamp(speed, 0.05f, 8.0f)) + "\n";
  s += "hue = " + num(l.hue) + "\n";
  if (l.has_hue_top) s += "hue_top = " + num(l.hue_top) + "\n";
  s += "saturation = " + num(l.saturation) + "\n";
  s += "brightness = " + num(l.brightness) + "\n";
  s += "glow_radius = " + num(l.glow_radius) + "\n";
  s += "glow_strength = " + num(l.glow_strength) + "\n";
  if (l.transfer.size() >= 2) {
    // Evenly spaced stops as the plain list; else each with its place (#rrggbb@0.25).
    const bool placed = !l.evenly_spaced();
    std::string stops;
    for (size_t i = 0; i < l.transfer.size(); ++i) {
      const auto& c = l.transfer[i];
      char hex[8];
      std::snprintf(hex, sizeof hex, "#%02x%02x%02x", static_cast<int>(std::lround(c[0] * 255)),
                    static_cast<int>(std::lround(c[1] * 255)),
                    static_cast<int>(std::lround(c[2] * 255)));
      stops += (stops.empty() ? "" : " ") + std::string(hex);
      if (placed) stops += "@" + num(l.transfer_at[i]);
    }
    s += "transfer = \"" + stops + "\"  # used instead of hue and saturation\n";
  }
  // The weight edits (standard deviations of each weight; the sliders' values).
  int last = -1;
  for (int k = 0; k < shape_weights(); ++k)
    if (edits_.weights.offset_sigma[static_cast<size_t>(k)] != 0) last = k;
  if (last >= 0) {
    s += "weight_offsets = [";
    for (int k = 0; k <= last; ++k)
      s += (k ? ", " : "") + num(edits_.weights.offset_sigma[static_cast<size_t>(k)]);
    s += "]\n";
  }
  if (edits_.weights.detail_scale != 1)
    s += "detail_scale = " + num(edits_.weights.detail_scale) + "\n";
  return s;
}

void Session::save_scene(const std::string& path) const {
  if (!ok()) throw RuntimeError(path + ": no model open, nothing to save");
  write_atomic(path, scene_text());
}

}  // namespace candela::studio
