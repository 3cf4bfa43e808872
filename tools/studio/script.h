// Scripted input (--script FILE): one command a line, run at the start of a
// frame through the same Session / PcaView calls the widgets make, so tests
// drive the studio as a user does. A line starting with '#' is a comment.
//
//   wait N                    let N frames pass
//   pause | play | step [N] | frame N | speed X
//   set weight K SIGMAS       offset of weight K (0-based), standard deviations
//   set detail SCALE          scale of the detail weights (K >= 50)
//   set hue|saturation|brightness|glow_radius|glow_strength V
//   set transfer #rrggbb #rrggbb ... | set transfer off   the transfer function (2-8 stops)
//   reset | undo              reset the weight edits / undo the last edit
//   drag pca DX DY            rotate the PCA view as a mouse drag of DX, DY pixels
//   zoom pca STEPS            as the mouse wheel
//   click pca X Y             click at X, Y pixels from the view's top left (jump there)
//   x-press X Y | x-release X Y | x-move X Y    real X events (the left button, the
//                             pointer) sent to the window: the whole path a user's take;
//                             ImGui sees one state a frame, so put `wait 1` between them
//   x-wheel X Y STEPS         wheel clicks (negative: towards the user)
//   x-key [ctrl+]KEYSYM       a key pressed, released a frame later (XStringToKeysym
//                             names: z, space, Left)
//   show reports              open the Reports section (its first tab)
//   resize W H                resize the window (as a user dragging its corner)
//   story new                 a story from the model's clips (one segment a clip)
//   story method SEG cut|lowpass|bridge|grow    the joint entering segment SEG (0-based)
//   story set SEG steps|theta_min|reject_tail|components|repeat V
//   story kernel SEG A B C    the lowpass taps
//   story add clip NAME [FROM TO] | story add walk|arp SECONDS   a segment at the end
//   story delete SEG | story move SEG left|right | story loop on|off
//                             (each re-planned; one the story reader refuses stops the script)
//   preview joint SEG         play from two seconds before segment SEG's joint
//   save-story FILE.toml      as the "Save story" button
//   screenshot FILE.png       the whole window, once this frame is drawn (the
//                             commands after it run in the next frame)
//   dump FILE                 the UI state as "key = value" lines, as screenshot
//   save-scene FILE.toml      as the "Save scene" button
//   quit
#pragma once

#include <string>
#include <vector>

namespace candela::studio {

class Session;
class PcaView;

struct ScriptCommand {
  int line = 0;
  std::vector<std::string> words;
};

// What a frame's commands ask of the frame loop.
struct ScriptFrame {
  std::vector<std::string> screenshots, dumps;
  int resize_w = 0, resize_h = 0;  // > 0: resize the window
  bool show_reports = false;
  // X events to send now, in order (the window backend reads them at the next poll)
  struct XInput {
    enum Kind { kPress, kRelease, kMove, kWheel, kKey, kKeyUp } kind;
    int x = 0, y = 0, steps = 0;
    std::string key;
    bool ctrl = false;
  };
  std::vector<XInput> x_input;
  bool quit = false;
};

class Script {
 public:
  // Reads and checks every line; throws RuntimeError "FILE:LINE: ..." .
  static Script load(const std::string& path);
  bool empty() const { return commands_.empty(); }
  bool done() const { return at_ >= commands_.size() && wait_ == 0; }
  // Runs the commands due this frame (up to the next wait). Throws
  // RuntimeError "FILE:LINE: ..." for a command that fails (save-scene).
  ScriptFrame run_frame(Session& session, PcaView& pca);

 private:
  std::string file_;
  std::vector<ScriptCommand> commands_;
  size_t at_ = 0;
  int wait_ = 0;
  std::vector<ScriptFrame::XInput> key_ups_;  // x-key's release, a frame after its press
};

}  // namespace candela::studio
