#include "script.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "panels.h"
#include "pca_view.h"
#include "session.h"
#include "story/story_file.h"

namespace candela::studio {
namespace {

bool number(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end && *end == '\0';
}

// Arity and number checks, so a typo fails at load, not halfway.
std::string check(const std::vector<std::string>& w) {
  const std::string& c = w[0];
  auto nums = [&](size_t from, size_t count) -> std::string {
    if (w.size() != from + count)
      return "expected " + std::to_string(from + count - 1) + " argument(s) after '" + c + "'";
    for (size_t i = from; i < w.size(); ++i) {
      double v;
      if (!number(w[i], v)) return "expected a number, got '" + w[i] + "'";
    }
    return {};
  };
  if (c == "pause" || c == "play" || c == "reset" || c == "undo" || c == "quit")
    return w.size() == 1 ? "" : "'" + c + "' takes no arguments";
  if (c == "wait" || c == "frame" || c == "speed") return nums(1, 1);
  if (c == "step") return w.size() == 1 ? "" : nums(1, 1);
  if (c == "set") {
    if (w.size() >= 2 && (w[1] == "weight" || w[1] == "stop")) return nums(2, 2);
    if (w.size() >= 2 && w[1] == "transfer") {
      if (w.size() == 3 && w[2] == "off") return {};
      if (w.size() < 4 || w.size() > 2 + 8)
        return "expected set transfer off | 2 to 8 #rrggbb[@PLACE] stops";
      for (size_t i = 2; i < w.size(); ++i) {
        unsigned r, g, b;
        const size_t sep = w[i].find('@');
        const std::string colour = w[i].substr(0, sep);
        double place = 0;
        if (colour.size() != 7 || std::sscanf(colour.c_str(), "#%2x%2x%2x", &r, &g, &b) != 3 ||
            (sep != std::string::npos && !number(w[i].substr(sep + 1), place)))
          return "expected a colour stop #rrggbb or #rrggbb@PLACE, got '" + w[i] + "'";
        if ((sep != std::string::npos) != (w[2].find('@') != std::string::npos))
          return "expected every stop placed (#rrggbb@PLACE) or none, got '" + w[i] + "'";
      }
      return {};
    }
    static const char* keys[] = {"detail",     "hue",         "hue_top",      "saturation",
                                 "brightness", "glow_radius", "glow_strength"};
    for (const char* k : keys)
      if (w.size() >= 2 && w[1] == k) return nums(2, 1);
    return "expected set weight|detail|hue|hue_top|saturation|brightness|glow_radius|"
           "glow_strength";
  }
  if (c == "drag" || c == "click") {
    if (w.size() < 2 || w[1] != "pca") return "expected '" + c + " pca X Y'";
    return nums(2, 2);
  }
  if (c == "story") {
    const std::string sub = w.size() >= 2 ? w[1] : "";
    if (sub == "new") return w.size() == 2 ? "" : "expected 'story new'";
    if (sub == "method") {
      static const std::vector<std::string> methods = {"cut", "lowpass", "bridge", "grow"};
      if (w.size() != 4 || std::find(methods.begin(), methods.end(), w[3]) == methods.end())
        return "expected 'story method SEGMENT cut|lowpass|bridge|grow'";
      double v;
      return number(w[2], v) ? "" : "expected a number, got '" + w[2] + "'";
    }
    if (sub == "set") {
      static const std::vector<std::string> keys = {"steps", "theta_min", "reject_tail",
                                                    "components", "repeat"};
      if (w.size() != 5 || std::find(keys.begin(), keys.end(), w[3]) == keys.end())
        return "expected 'story set SEGMENT steps|theta_min|reject_tail|components|repeat V'";
      double a, b;
      return number(w[2], a) && number(w[4], b) ? "" : "expected numbers in 'story set'";
    }
    if (sub == "kernel") return nums(2, 4);
    if (sub == "delete") return nums(2, 1);
    if (sub == "move") {
      double v;
      return w.size() == 4 && number(w[2], v) && (w[3] == "left" || w[3] == "right")
                 ? ""
                 : "expected 'story move SEGMENT left|right'";
    }
    if (sub == "loop")
      return w.size() == 3 && (w[2] == "on" || w[2] == "off") ? "" : "expected 'story loop on|off'";
    if (sub == "add") {
      double v;
      if (w.size() == 4 && (w[2] == "walk" || w[2] == "arp"))
        return number(w[3], v) ? "" : "expected a number of seconds, got '" + w[3] + "'";
      if ((w.size() == 4 || w.size() == 6) && w[2] == "clip")
        return w.size() == 4 || (number(w[4], v) && number(w[5], v))
                   ? ""
                   : "expected 'story add clip NAME [FROM TO]'";
      return "expected 'story add clip NAME [FROM TO]' or 'story add walk|arp SECONDS'";
    }
    return "expected story new|method|set|kernel|add|delete|move|loop";
  }
  if (c == "preview")
    return w.size() == 3 && w[1] == "joint" ? nums(2, 1) : "expected 'preview joint SEGMENT'";
  if (c == "show") return w.size() == 2 && w[1] == "reports" ? "" : "expected 'show reports'";
  if (c == "resize" || c == "x-press" || c == "x-release" || c == "x-move") return nums(1, 2);
  if (c == "x-wheel") return nums(1, 3);
  if (c == "x-key") return w.size() == 2 ? "" : "expected 'x-key [ctrl+]KEYSYM'";
  if (c == "zoom") {
    if (w.size() < 2 || w[1] != "pca") return "expected 'zoom pca STEPS'";
    return nums(2, 1);
  }
  if (c == "screenshot" || c == "dump" || c == "save-scene" || c == "save-story")
    return w.size() == 2 ? "" : "expected '" + c + " FILE'";
  return "unknown command '" + c + "'";
}

float f(const std::string& s) { return std::strtof(s.c_str(), nullptr); }

// `story ...`: the timeline's edits, through the same Session calls as its widgets.
bool story_command(Session& s, const std::vector<std::string>& w) {
  const std::string& sub = w[1];
  if (sub == "new") return s.new_story();
  if (!s.story()) {
    s.status = "no story (story new starts one from the model's clips)";
    return false;
  }
  const int j = w.size() > 2 ? static_cast<int>(f(w[2])) : -1;
  const int n = s.story() ? static_cast<int>(s.story()->segments.size()) : 0;
  if ((sub == "method" || sub == "set" || sub == "kernel" || sub == "delete" || sub == "move") &&
      (j < 0 || j >= n)) {
    s.status = "no segment " + w[2] + " (the story has " + std::to_string(n) + ")";
    return false;
  }
  const size_t u = static_cast<size_t>(j);
  return s.edit_story([&](story::StoryDesc& d) {
    if (sub == "method") {
      set_method(d.segments[u].transition, w[3] == "cut"       ? story::Method::kCut
                                           : w[3] == "lowpass" ? story::Method::kLowpass
                                           : w[3] == "bridge"  ? story::Method::kBridge
                                                               : story::Method::kGrow);
    } else if (sub == "set") {
      story::TransitionSpec& t = d.segments[u].transition;
      const float v = f(w[4]);
      if (w[3] == "steps") t.steps = static_cast<int>(v);
      if (w[3] == "theta_min") t.theta_min = v;
      if (w[3] == "reject_tail") t.reject_tail = static_cast<int>(v);
      if (w[3] == "components") t.components = static_cast<int>(v);
      if (w[3] == "repeat") d.segments[u].repeat = static_cast<int>(v);
    } else if (sub == "kernel") {
      d.segments[u].transition.kernel = {f(w[3]), f(w[4]), f(w[5])};
    } else if (sub == "delete") {
      d.segments.erase(d.segments.begin() + j);
    } else if (sub == "move") {
      const int k = w[3] == "left" ? j - 1 : j + 1;
      if (k >= 0 && k < n) std::swap(d.segments[u], d.segments[static_cast<size_t>(k)]);
    } else if (sub == "loop") {
      d.loop = w[2] == "on";
    } else if (sub == "add") {
      story::SegmentSpec g;
      if (w[2] == "clip") {
        g.clip = w[3];
        if (w.size() == 6) g.from = static_cast<int>(f(w[4])), g.to = static_cast<int>(f(w[5]));
      } else {
        g.kind = w[2] == "walk" ? story::SegmentKind::kWalk : story::SegmentKind::kArp;
        g.seconds = f(w[3]);
      }
      d.segments.push_back(g);
    }
  });
}

}  // namespace

Script Script::load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RuntimeError(path + ": cannot read the script");
  Script s;
  s.file_ = path;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    const size_t first = text.find_first_not_of(" \t");
    if (first != std::string::npos && text[first] == '#') continue;  // a comment line
    std::istringstream words(text);
    ScriptCommand c;
    c.line = n;
    for (std::string w; words >> w;) c.words.push_back(w);
    if (c.words.empty()) continue;
    const std::string why = check(c.words);
    if (!why.empty()) throw RuntimeError(path + ":" + std::to_string(n) + ": " + why);
    s.commands_.push_back(std::move(c));
  }
  return s;
}

ScriptFrame Script::run_frame(Session& s, PcaView& pca) {
  ScriptFrame out;
  for (auto& up : key_ups_) out.x_input.push_back(up);
  key_ups_.clear();
  if (wait_ > 0) {
    --wait_;
    return out;
  }
  while (at_ < commands_.size()) {
    const ScriptCommand& c = commands_[at_++];
    const auto& w = c.words;
    const std::string& cmd = w[0];
    if (cmd == "wait") {
      wait_ = std::max(0, static_cast<int>(f(w[1])) - 1);
      if (static_cast<int>(f(w[1])) > 0) break;
    } else if (cmd == "pause") {
      s.playing = false;
    } else if (cmd == "play") {
      s.playing = true;
    } else if (cmd == "step") {
      s.step(w.size() > 1 ? static_cast<int>(f(w[1])) : 1);
    } else if (cmd == "frame") {
      s.seek(static_cast<int>(f(w[1])));
    } else if (cmd == "speed") {
      s.speed = f(w[1]);
    } else if (cmd == "set") {
      s.begin_edit();
      if (w[1] == "weight") {
        s.set_offset(static_cast<int>(f(w[2])), f(w[3]));
      } else if (w[1] == "stop") {
        s.set_stop_place(static_cast<int>(f(w[2])), f(w[3]));
      } else if (w[1] == "detail") {
        s.set_detail_scale(f(w[2]));
      } else {
        Look l = s.edits().look;
        const float v = f(w[2]);
        if (w[1] == "hue") l.hue = v;
        if (w[1] == "hue_top") l.hue_top = v, l.has_hue_top = true;
        if (w[1] == "saturation") l.saturation = v;
        if (w[1] == "brightness") l.brightness = v;
        if (w[1] == "glow_radius") l.glow_radius = v;
        if (w[1] == "glow_strength") l.glow_strength = v;
        if (w[1] == "transfer") {
          l.transfer.clear();
          l.transfer_at.clear();
          for (size_t i = 2; i < w.size() && w[2] != "off"; ++i) {
            unsigned r = 0, g = 0, b = 0;
            std::sscanf(w[i].c_str(), "#%2x%2x%2x", &r, &g, &b);
            l.transfer.push_back({r / 255.0f, g / 255.0f, b / 255.0f});
            const size_t sep = w[i].find('@');
            if (sep != std::string::npos) l.transfer_at.push_back(f(w[i].substr(sep + 1)));
          }
        }
        s.set_look(l);
      }
    } else if (cmd == "reset") {
      s.reset_edits();
    } else if (cmd == "undo") {
      s.undo();
    } else if (cmd == "drag") {
      pca.rotate(f(w[2]), f(w[3]));
    } else if (cmd == "show") {
      out.show_reports = true;
    } else if (cmd == "resize") {
      out.resize_w = std::clamp(static_cast<int>(f(w[1])), 200, 8192);
      out.resize_h = std::clamp(static_cast<int>(f(w[2])), 150, 8192);
    } else if (cmd == "x-press" || cmd == "x-release" || cmd == "x-move" || cmd == "x-wheel") {
      ScriptFrame::XInput in;
      in.kind = cmd == "x-press"     ? ScriptFrame::XInput::kPress
                : cmd == "x-release" ? ScriptFrame::XInput::kRelease
                : cmd == "x-move"    ? ScriptFrame::XInput::kMove
                                     : ScriptFrame::XInput::kWheel;
      in.x = static_cast<int>(f(w[1]));
      in.y = static_cast<int>(f(w[2]));
      if (w.size() > 3) in.steps = static_cast<int>(f(w[3]));
      out.x_input.push_back(in);
    } else if (cmd == "x-key") {
      ScriptFrame::XInput in;
      in.kind = ScriptFrame::XInput::kKey;
      in.key = w[1];
      if (in.key.rfind("ctrl+", 0) == 0) {
        in.ctrl = true;
        in.key = in.key.substr(5);
      }
      out.x_input.push_back(in);
      in.kind = ScriptFrame::XInput::kKeyUp;
      key_ups_.push_back(in);
      break;  // the release goes with the next frame
    } else if (cmd == "zoom") {
      pca.zoom(f(w[2]));
    } else if (cmd == "click") {
      const int mf = pca.pick(ImVec2(f(w[2]), f(w[3])));
      if (mf >= 0) {
        s.seek_model_frame(mf);
        s.playing = false;
      }
    } else if (cmd == "screenshot") {  // of this frame: later commands wait for the next one
      out.screenshots.push_back(w[1]);
      break;
    } else if (cmd == "dump") {
      out.dumps.push_back(w[1]);
      break;
    } else if (cmd == "save-scene") {
      if (!save_scene_reporting(s, w[1]))
        throw RuntimeError(file_ + ":" + std::to_string(c.line) + ": save-scene: " + s.status);
    } else if (cmd == "story") {
      if (!story_command(s, w))
        throw RuntimeError(file_ + ":" + std::to_string(c.line) + ": " + w[0] + " " + w[1] + ": " +
                           s.status);
    } else if (cmd == "preview") {
      if (!s.preview_joint(static_cast<int>(f(w[2]))))
        throw RuntimeError(file_ + ":" + std::to_string(c.line) + ": no joint enters segment " +
                           w[2]);
    } else if (cmd == "save-story") {
      if (!save_story_reporting(s, w[1]))
        throw RuntimeError(file_ + ":" + std::to_string(c.line) + ": save-story: " + s.status);
    } else if (cmd == "quit") {
      out.quit = true;
      break;
    }
  }
  return out;
}

}  // namespace candela::studio
