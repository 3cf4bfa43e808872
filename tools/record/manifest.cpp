#include "manifest.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>

#include "core/json_parse.h"

namespace candela::record {

using Json = nlohmann::ordered_json;

namespace {

// A whole number as an integer (30, not 30.0), anything else as it is.
Json number(double v) {
  if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 1e15) return static_cast<int64_t>(v);
  return v;
}

// Text that is already JSON (a control's value, the preview's report); kept
// as a string if it is not valid JSON.
Json embedded(const std::string& text) {
  std::optional<Json> j = try_parse_json<Json>(text, nullptr);
  return j ? std::move(*j) : Json(text);
}

// The frames array, written directly: it holds every frame recorded (108000
// after an hour at 30 fps) and is rewritten every second from the capture
// thread, where building it as a JSON tree costs about 8 times as long. Only
// numbers and fixed ASCII names: nothing to escape.
void append_frames(std::string& out, const std::vector<WrittenFrame>& frames) {
  out.reserve(out.size() + frames.size() * 80 + 64);
  out += '[';
  char b[128];
  for (size_t i = 0; i < frames.size(); ++i) {
    const int n = std::snprintf(b, sizeof b,
                                "%s{\"file\":\"frames/%08u.png\",\"sequence\":%u,"
                                "\"timestamp_ns\":%lld}",
                                i ? "," : "", frames[i].sequence, frames[i].sequence,
                                static_cast<long long>(frames[i].timestamp_ns));
    out.append(b, static_cast<size_t>(n));
  }
  out += ']';
}

}  // namespace

std::string manifest_text(const RecordingInfo& info, const RecordingState& state) {
  Json m;
  m["format"] = "candela-recording";
  m["version"] = 1;
  m["clip"] = info.clip;
  m["backend"] = info.backend;
  m["device"] = info.device;
  m["card"] = info.card;
  m["driver"] = info.driver;
  m["started"] = info.started;
  m["width"] = info.width;
  m["height"] = info.height;
  m["pixel_format"] = info.pixel_format;
  m["png"] = info.color ? "rgb8" : "gray8";
  m["fps"] = number(info.fps);
  m["requested_fps"] = info.requested_fps;
  m["measured_fps"] = number(std::round(state.measured_fps * 1000) / 1000);
  Json locked = Json::object();
  for (const auto& l : info.locked) locked[l.name] = l.outcome;
  m["locked"] = std::move(locked);
  Json controls = Json::object();
  for (const auto& c : info.controls)
    controls[c.name] = {
        {"id", c.id}, {"value", embedded(c.value_json)}, {"default", embedded(c.default_json)}};
  m["controls"] = std::move(controls);
  m["frame_count"] = state.frames.size();
  Json tail;
  tail["dropped"] = {{"count", state.dropped.size()}, {"sequences", state.dropped}};
  tail["preview"] =
      state.preview_json.empty() ? Json{{"mode", "off"}} : embedded(state.preview_json);
  tail["complete"] = state.final_write && state.complete;
  tail["end_reason"] = state.final_write ? state.end_reason : "recording";
  // Invalid UTF-8 (a camera name) is replaced, not thrown on.
  const auto dump = [](const Json& j) {
    return j.dump(-1, ' ', false, Json::error_handler_t::replace);
  };
  // {head..., "frames": [...], tail...}
  std::string text = dump(m);
  text.pop_back();  // the head's closing brace
  text += ",\"frames\":";
  append_frames(text, state.frames);
  text += ',';
  text.append(dump(tail), 1);  // without the tail's opening brace
  text += '\n';
  return text;
}

std::string utc_now() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace candela::record
