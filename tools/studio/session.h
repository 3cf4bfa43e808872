// What the studio works on: the model (or why it failed to open), the
// timeline it plays (the model's frames clip after clip, or a story planned by
// the runtime's own planner), the playback, the edits with their undo
// history, and "save as scene". No GL: the views draw what this holds.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "look.h"
#include "story/story_file.h"

namespace candela {
struct EigenModel;
namespace story {
class StoryPlan;
}
}  // namespace candela

namespace candela::studio {

// Switches a joint's method, its steps to that method's default where the
// old value does not fit (bridge: 0 = automatic; grow: 20, at least 2).
void set_method(story::TransitionSpec& t, story::Method m);

class Session {
 public:
  // model: a .cmodel path or builtin:NAME; story: a story file, builtin:NAME
  // or empty. Never throws for a bad model or story: error() says why.
  Session(std::string model, std::string story);
  ~Session();

  bool ok() const { return model_ != nullptr; }
  const std::string& error() const { return error_; }
  bool story_failed() const { return story_failed_; }  // error() is the story's
  const EigenModel& model() const { return *model_; }
  const std::string& model_name() const { return model_name_; }
  const std::string& story_name() const { return story_name_; }
  bool has_story() const { return plan_ != nullptr; }

  // The story being composed (null: none) and its plan (the runtime's planner).
  const story::StoryDesc* story() const { return desc_.get(); }
  const story::StoryPlan* plan() const { return plan_.get(); }
  // A new story from the model's clips: one segment a clip (at most 64), each
  // entered by `grow`, looping. Records an undo step.
  bool new_story();
  // Every story edit goes through here: records an undo step, applies
  // `change` to a copy, re-plans it; false (status says why, the story stays
  // as it was) when the planner refuses it.
  // `gesture` (a widget's name): edits with the same gesture, one after
  // another, are one undo step (typing "20" into a field); end_gesture()
  // closes it (the UI calls it when no widget is active).
  bool edit_story(const std::function<void(story::StoryDesc&)>& change,
                  const std::string& gesture = {});
  void end_gesture() { gesture_.clear(); }
  // The largest seam ratio of the joints entering segment `seg` (its joint,
  // its repeats' and the loop's when it is the first), -1 when none.
  float joint_seam(int seg) const;
  // The story frame where segment `seg`'s first joint starts (-1: none).
  int joint_frame(int seg) const;
  // Plays from about two seconds before segment `seg`'s first joint.
  bool preview_joint(int seg);
  std::string story_text() const;
  // Writes story_text(); the story's name becomes the file (a saved scene names it).
  void save_story(const std::string& path);  // throws RuntimeError naming the file

  // The timeline: story frames, or the model's frames in order.
  int frames() const;
  int frame() const { return static_cast<int>(pos_); }
  int model_frame(int i) const;  // the model frame timeline frame i shows (-1: none)
  int clip_of_frame(int model_frame) const;
  double fps() const;
  void seek(int frame);
  void step(int frames);                   // pauses
  void seek_model_frame(int model_frame);  // the first timeline frame showing it
  bool playing = true;
  float speed = 1.0f;  // 0.05..8, as the element's `speed`
  void advance(double seconds);

  // The weights shown now: the timeline's (faded into the next frame over the
  // last quarter of a frame, as the runtime's crossfade) with the edits.
  std::span<const float> shown() const { return shown_; }
  std::span<const float> base() const { return base_; }
  float sigma(int k) const { return sigma_[static_cast<size_t>(k)]; }
  int shape_weights() const;  // how many offsets apply (<= kShapeWeights)

  const Edits& edits() const { return edits_; }
  // Every change to the edits goes through here (UI widgets and scripts).
  // begin_edit() records the state to undo to (the edits as they are, or as
  // they were before a widget changed them): once per gesture.
  void begin_edit() { begin_edit(edits_); }
  void begin_edit(const Edits& before);
  void set_offset(int k, float sigmas);
  void set_detail_scale(float s);
  void set_look(const Look& look);
  // Moves transfer stop k to `place` (0..1), kept between its neighbours.
  void set_stop_place(int k, float place);
  void reset_edits();  // records an undo step itself
  bool undo();
  size_t undo_depth() const { return undo_.size(); }

  std::string scene_text() const;
  void save_scene(const std::string& path) const;  // throws RuntimeError naming the file
  std::string status;  // the last thing done ("saved ..."), shown in the UI

 private:
  void update_shown();
  std::string story_text_of(const story::StoryDesc& d) const;
  bool replan(std::shared_ptr<const story::StoryDesc> desc);
  std::string model_name_, story_name_, error_;
  bool story_failed_ = false;
  std::shared_ptr<const EigenModel> model_;
  std::shared_ptr<const story::StoryDesc> desc_;  // a new copy for every edit (undo keeps old ones)
  std::unique_ptr<story::StoryPlan> plan_;
  std::vector<float> sigma_, base_, shown_;
  double pos_ = 0;
  Edits edits_;
  struct UndoStep {
    Edits edits;
    std::shared_ptr<const story::StoryDesc> story;
  };
  std::vector<UndoStep> undo_;
  std::string gesture_;  // the story gesture the last undo step belongs to
};

}  // namespace candela::studio
