// libFuzzer target for story files: any text must either be refused with a
// ConfigError or load and plan (against the story tests' two-clip model:
// clips "T1", "middle", "T2"), never crash, hang or run past its bounds.
// Runs the reader and the whole planner (walks, every transition, the loop).
//   build with clang: ninja -C build-fuzz story_reader_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "story/story_file.h"
#include "story/story_plan.h"
#include "story/story_test_model.h"  // tests/story/

namespace candela::stories {
std::string_view find(std::string_view) { return {}; }
std::size_t count() { return 0; }
std::string_view name_at(std::size_t) { return {}; }
}  // namespace candela::stories

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const candela::model::FlameModel model = candela::test::two_clip_model();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const candela::story::StoryDesc story = candela::story::load_story_text(text, "<fuzz>");
    const candela::story::StoryPlan plan = candela::story::plan_story(story, model, 1, true);
    if (plan.frames() < 1 || plan.frames() > candela::story::kMaxStoryFrames) __builtin_trap();
    for (const auto& j : plan.joints())
      if (!(j.seam_ratio >= 0)) __builtin_trap();  // NaN or negative: a broken measure
  } catch (const candela::ConfigError&) {
  }
  return 0;
}
