#include "story/story_file.h"

#include <cmath>

#include "core/error.h"
#include "core/file_read.h"
#include "embedded_stories.h"
#include "params/params.h"
#include "params/toml_text.h"

namespace candela::story {

const char* method_name(Method m) {
  switch (m) {
    case Method::kCut:
      return "cut";
    case Method::kLowpass:
      return "lowpass";
    case Method::kBridge:
      return "bridge";
    case Method::kGrow:
      return "grow";
  }
  return "?";
}

namespace {

TransitionSpec parse_transition(ParamReader& seg) {
  TransitionSpec t;
  t.key = seg.key_path("transition");
  if (!seg.has("transition")) return t;
  ParamReader r = seg.table("transition");
  const std::string method = r.string("method", "grow", {"cut", "lowpass", "bridge", "grow"});
  t.method = method == "cut"       ? Method::kCut
             : method == "lowpass" ? Method::kLowpass
             : method == "bridge"  ? Method::kBridge
                                   : Method::kGrow;
  // Each method's own keys only: a key another method reads is a mistake here.
  if (t.method == Method::kLowpass) {
    const Vec3 k = r.vec3("kernel", {t.kernel[0], t.kernel[1], t.kernel[2]});
    t.kernel = {k.x, k.y, k.z};
    for (float v : t.kernel)
      if (!(v >= 0 && v <= 1))
        r.fail("kernel", "expected three taps in 0..1 (the paper's [1/3, 1/3, 1/3])");
    if (std::fabs(t.kernel[0] + t.kernel[1] + t.kernel[2] - 1.0f) > 0.01f)
      r.fail("kernel", "expected taps that sum to 1 (a low-pass keeps the brightness)");
    t.components = static_cast<int>(r.integer("components", t.components, 1, 4096));
  } else if (t.method == Method::kBridge || t.method == Method::kGrow) {
    t.steps = static_cast<int>(r.integer("steps", t.method == Method::kGrow ? 20 : 0,
                                         t.method == Method::kGrow ? 2 : 0, kMaxTransitionSteps));
    t.theta_min = static_cast<float>(r.number("theta_min", 0, 0, 1e12));
    t.reject_tail = static_cast<int>(r.integer("reject_tail", t.reject_tail, 0, 1000));
  }
  r.finish();
  return t;
}

}  // namespace

StoryDesc load_story_text(std::string_view text, const std::string& name) {
  const toml::table root = parse_toml_text(text, name);
  StoryDesc s;
  s.file = name;
  ParamReader top(&root, name, "");
  s.model = top.string("model", "");
  if (s.model.empty())
    top.fail("model", "expected the model the story plays (a .cmodel file or builtin:fire)");
  s.has_seed = top.has("seed");
  s.seed = static_cast<uint64_t>(top.integer("seed", 1, 0, INT64_MAX));
  s.loop = top.boolean("loop", true);
  s.components = static_cast<int>(top.integer("components", s.components, 1, 4096));
  std::vector<ParamReader> segs = top.table_array("segment");
  top.finish();
  if (segs.empty()) top.fail("segment", "expected at least one [[segment]]");
  if (segs.size() > kMaxSegments)
    top.fail("segment", "expected at most " + std::to_string(kMaxSegments) + " segments, got " +
                            std::to_string(segs.size()));
  for (size_t i = 0; i < segs.size(); ++i) {
    ParamReader& r = segs[i];
    SegmentSpec g;
    g.key = "segment[" + std::to_string(i) + "]";
    const bool frames = r.has("clip") || r.has("from") || r.has("to");
    const int kinds = int{frames} + int{r.has("arp")} + int{r.has("walk")};
    if (kinds != 1)
      r.fail(kinds == 0 ? "clip" : (r.has("arp") ? "arp" : "walk"),
             "expected exactly one of clip/from/to (frames of the model), arp = SECONDS or walk = "
             "SECONDS");
    if (frames) {
      g.kind = SegmentKind::kFrames;
      g.clip = r.string("clip", "");
      g.from = static_cast<int>(r.integer("from", 0, 0, 1 << 24));
      g.to = static_cast<int>(r.integer("to", -1, 1, 1 << 24));
      if (g.to >= 0 && g.to - g.from < kMinSegmentFrames)
        r.fail("to", "expected at least " + std::to_string(kMinSegmentFrames) +
                         " frames after from = " + std::to_string(g.from) +
                         ", got to = " + std::to_string(g.to));
    } else {
      g.kind = r.has("arp") ? SegmentKind::kArp : SegmentKind::kWalk;
      g.seconds =
          r.number(g.kind == SegmentKind::kArp ? "arp" : "walk", 0, 0.1, kMaxSegmentSeconds);
    }
    g.repeat = static_cast<int>(r.integer("repeat", 1, 1, kMaxRepeat));
    g.transition = parse_transition(r);
    r.finish();
    s.segments.push_back(std::move(g));
  }
  return s;
}

StoryDesc load_story_file(const std::string& path) {
  return load_story_text(read_bounded_file(path, FileKind::kScene), path);
}

StoryDesc open_story(const std::string& name, const std::string& relative_to) {
  if (name.rfind("builtin:", 0) == 0) {
    const std::string text(stories::find(name.substr(8) + ".toml"));
    if (text.empty()) {
      std::string names;
      for (size_t i = 0; i < stories::count(); ++i) {
        std::string_view n = stories::name_at(i);
        if (n.ends_with(".toml")) n.remove_suffix(5);
        names += (names.empty() ? "builtin:" : ", builtin:") + std::string(n);
      }
      throw ConfigError("<built-in stories>", name,
                        "no such built-in story (built in: " + names + "; a file needs a path)");
    }
    return load_story_text(text, "<built-in story " + name.substr(8) + ">");
  }
  return load_story_file(relative_to.empty() ? name : resolve_relative(relative_to, name));
}

std::string story_model_path(const StoryDesc& story) {
  if (story.model.rfind("builtin:", 0) == 0) return story.model;
  return resolve_relative(story.file, story.model);
}

}  // namespace candela::story
