// libFuzzer target for the control socket's command parser: the bytes a
// client sends, cut into lines as ControlServer::serve cuts them (at '\n',
// at most kMaxLine bytes a line), each parsed as the kiosk parses it. Any
// line must give a command or an error of bounded length (issue 15: a 10 MB
// bad value was echoed whole; "wind 0x10 0" was taken as 16), and every wind
// command it accepts must drive the wind field for a few seconds without
// going past what its gusts and steady wind allow together; every volume and
// brightness it accepts is a level in [0, 1] (or -1, the question); `screen`
// is on, off or a question; `scene` a trimmed, non-empty name or path; the
// kiosk's other commands (reload, schedule, state, ping, help) take no
// arguments. Seeds for each command: tests/fuzz/corpus/control/; its words:
// tests/fuzz/control_command.dict.
//   build with clang: ninja -C build-fuzz control_command_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstdint>
#include <string_view>

#include "input/control_channel.h"
#include "scene/element.h"
#include "wind/wind_field.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace candela;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  WindSpec spec;
  WindField wind(spec);
  const Fixed limit = Fixed::from_int(60);  // the largest speed a command may ask for
  size_t start = 0;
  int events = 0;
  while (start < in.size()) {
    size_t nl = in.find('\n', start);
    if (nl == std::string_view::npos) nl = in.size();
    if (nl - start > ControlServer::kMaxLine) break;  // the server drops such a client
    const ControlCommand c = parse_control_command(in.substr(start, nl - start), spec);
    start = nl + 1;
    if (c.kind == ControlCommand::Kind::kError) {
      // Errors quote at most 40 characters of what was sent, plus the help text.
      if (c.error.empty() || c.error.size() > 400) __builtin_trap();
      continue;
    }
    // A volume or brightness is a level in [0, 1], or a question (exactly -1).
    if ((c.kind == ControlCommand::Kind::kVolume || c.kind == ControlCommand::Kind::kBrightness) &&
        !((c.volume >= 0 && c.volume <= 1) || c.volume == -1.0f))
      __builtin_trap();
    // screen: on (1), off (0) or a question (-1).
    if (c.kind == ControlCommand::Kind::kScreen && c.screen != 0 && c.screen != 1 && c.screen != -1)
      __builtin_trap();
    // scene: a name or path, trimmed, within the line, never empty.
    if (c.kind == ControlCommand::Kind::kScene) {
      const std::string& n = c.scene;
      if (n.empty() || n.size() > ControlServer::kMaxLine || n.find('\n') != std::string::npos ||
          n.front() == ' ' || n.front() == '\t' || n.back() == ' ' || n.back() == '\t' ||
          n.back() == '\r')
        __builtin_trap();
    }
    // Only the kinds that carry one have a scene name or a screen state.
    if (c.kind != ControlCommand::Kind::kScene && !c.scene.empty()) __builtin_trap();
    if (c.kind != ControlCommand::Kind::kScreen && c.screen != -1) __builtin_trap();
    if (c.kind != ControlCommand::Kind::kWind) continue;
    const Fixed ax = c.event.x < Fixed{} ? -c.event.x : c.event.x;
    const Fixed az = c.event.z < Fixed{} ? -c.event.z : c.event.z;
    if (ax > limit || az > limit) __builtin_trap();
    wind.push(c.event);
    if (++events > 64) break;  // enough to fill every gust slot and more
  }
  // Two seconds (a gust's length) of the wind these commands made, across the scene.
  StepContext step;
  step.dt = Fixed::from_ratio(1, 60);
  step.wind = &wind;
  for (int s = 0; s < 120; ++s) {
    step.step = static_cast<uint64_t>(s);
    step.time = step.dt * Fixed::from_int(s);
    wind.update(step);
    for (int p = -2; p <= 2; ++p) {
      // At most every gust slot and the steady wind at full speed, together.
      const WindSample w = wind.sample(Vec3{0.5f * p, 0.2f, 0.3f * p});
      const Fixed bound = limit * Fixed::from_int(WindField::kMaxGusts + 1);
      if (w.x > bound || -w.x > bound || w.z > bound || -w.z > bound) __builtin_trap();
    }
  }
  return 0;
}
