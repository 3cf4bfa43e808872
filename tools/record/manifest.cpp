#include "manifest.h"

#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>

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
  Json j = Json::parse(text, nullptr, /*allow_exceptions=*/false);
  return j.is_discarded() ? Json(text) : j;
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
  Json frames = Json::array();
  for (const auto& w : state.frames)
    frames.push_back({{"file", "frames/" + PngWriterPool::file_name(w.sequence)},
                      {"sequence", w.sequence},
                      {"timestamp_ns", w.timestamp_ns}});
  m["frames"] = std::move(frames);
  m["dropped"] = {{"count", state.dropped.size()}, {"sequences", state.dropped}};
  m["preview"] = state.preview_json.empty() ? Json{{"mode", "off"}} : embedded(state.preview_json);
  m["complete"] = state.final_write && state.complete;
  m["end_reason"] = state.final_write ? state.end_reason : "recording";
  // Invalid UTF-8 (a camera name) is replaced, not thrown on.
  return m.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
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
