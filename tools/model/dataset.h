// A dataset: aligned, background-free gray flame frames of one common size
// from one or more clips, plus a manifest. On disk (a folder):
//   manifest.json  width, height, frames, clips [{name, source, first, count,
//                  fps, labels [{from, to, label}]}], multi_plume [frame...],
//                  intensity "srgb", ingest options
//   frames.u8      frames x height x width bytes: luma with the background
//                  removed, sRGB-encoded 0..255 (as the footage and the screen
//                  are; "linear" datasets of older tools are encoded on load)
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "model/flame_model.h"

namespace candela::tools {

struct Dataset {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;  // frames x height x width
  std::vector<model::ClipInfo> clips;
  // 1 where a frame shows two or more disjoint plumes: the Learning Flames
  // model cannot represent it and leaves it out (EigenFires keeps it).
  std::vector<uint8_t> multi_plume;
  nlohmann::json options = nlohmann::json::object();  // how it was ingested

  int frames() const { return static_cast<int>(multi_plume.size()); }
  size_t frame_pixels() const { return static_cast<size_t>(width) * height; }
  const uint8_t* frame(int i) const { return pixels.data() + frame_pixels() * i; }
};

void save_dataset(const Dataset& d, const std::string& dir);
// Linear 0..1 to an 8-bit sRGB-encoded value (how datasets store intensity).
uint8_t encode_srgb8(float linear);
// Validates the manifest and the frame file (ConfigError naming file and key).
Dataset load_dataset(const std::string& dir);
// The manifest's text alone, validated as load_dataset does (`file` names it
// in errors): the dataset without its pixels; *linear tells whether the
// frames hold linear luma (older datasets) rather than sRGB.
Dataset parse_manifest(std::string_view text, const std::string& file, bool* linear = nullptr);

// Picks every `step`-th frame and/or resamples to `frames` frames by blending
// neighbours (used to make large benchmark sets from short clips).
Dataset resample_dataset(const Dataset& d, int frames);

nlohmann::json clips_to_json(const std::vector<model::ClipInfo>& clips);

}  // namespace candela::tools
