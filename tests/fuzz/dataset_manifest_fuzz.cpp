// libFuzzer target for the dataset manifest reader (`candela-tool build`
// reads manifest.json before the frames): any text must either be refused
// with a ConfigError naming the manifest, or give a dataset whose clips tile
// its frames in order, whose labels lie inside their clip, and whose sizes
// the frame file check can multiply without overflow.
//   build with clang: ninja -C build-fuzz dataset_manifest_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "dataset.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace candela;
  try {
    bool linear = false;
    const tools::Dataset d = tools::parse_manifest({reinterpret_cast<const char*>(data), size},
                                                   "fuzz/manifest.json", &linear);
    int next = 0;
    for (const auto& c : d.clips) {
      if (c.first != next || c.count < 1 || !(c.fps > 0)) __builtin_trap();
      for (const auto& l : c.labels)
        if (l.from < c.first || l.to < l.from || l.to > c.first + c.count) __builtin_trap();
      next = c.first + c.count;
    }
    if (d.clips.empty() || next != d.frames() || d.width < 1 || d.height < 1) __builtin_trap();
    // frames x height x width bytes, as load_dataset sizes the frame file.
    const unsigned __int128 bytes = static_cast<unsigned __int128>(d.frame_pixels()) *
                                    static_cast<unsigned __int128>(d.frames());
    if (bytes != static_cast<unsigned __int128>(d.frame_pixels() * d.frames())) __builtin_trap();
  } catch (const ConfigError& e) {
    if (std::string_view(e.what()).find("fuzz/manifest.json") == std::string_view::npos)
      __builtin_trap();  // an error must name the file
  }
  return 0;
}
