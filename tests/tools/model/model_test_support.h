// Shared by the model-builder tests: small datasets ingested from the real clips.
#pragma once

#include <string>

#include "ingest.h"

namespace candela::tools::test {

inline std::string clip_dir(const std::string& name) {
  return std::string(CANDELA_FLAMES_DIR) + "/" + name;
}

// A real clip, ingested small (every `step`-th frame) so tests stay fast.
inline Dataset small_dataset(const std::string& clip, int width, int height, int step,
                             int max_frames = 0) {
  IngestOptions o;
  o.width = width;
  o.height = height;
  return ingest({read_source(clip_dir(clip), max_frames, step)}, o);
}

}  // namespace candela::tools::test
