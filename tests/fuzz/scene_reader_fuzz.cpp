// libFuzzer target for the scene reader: any text must either be refused with
// a ConfigError or load as a scene, never crash, hang or overflow the stack
// (issue 15: deep dotted keys overflowed toml++'s). It runs the whole reader
// (nesting pre-scan, toml++, display/camera/wind/input validation) with one
// stand-in element kind that asks ParamReader for every type of value, so it
// needs no GL and no element code.
//   build with clang: ninja -C build-fuzz scene_reader_fuzz (tests/fuzz/run-fuzz.sh)
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "core/error.h"
#include "params/params.h"
#include "scene/scene_file.h"

namespace candela {
namespace {
class FuzzSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext&) const override { return nullptr; }
};
std::unique_ptr<ElementSpec> parse_fuzz(ParamReader& r) {
  (void)r.number("n", 1, -10, 10);
  (void)r.fixed("f", 1, 0, 100);
  (void)r.integer("i", 0, 0, 1000);
  (void)r.boolean("b", false);
  (void)r.string("s", "a", {"a", "b"});
  (void)r.vec3("v", {});
  (void)r.color("c", {});
  (void)r.path("p");
  ParamReader t = r.table("t");
  (void)t.number("n", 0, 0, 1);
  t.finish();
  for (ParamReader& e : r.table_array("e")) {
    (void)e.integer("k", 0, -5, 5);
    e.finish();
  }
  r.finish();
  return std::make_unique<FuzzSpec>();
}
}  // namespace

std::span<const ElementKind> element_kinds() {
  static const ElementKind kinds[] = {{"fuzz", "stand-in", parse_fuzz}};
  return kinds;
}
}  // namespace candela

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto scene = candela::load_scene_text(
        std::string_view(reinterpret_cast<const char*>(data), size), "/tmp/fuzz.toml");
    (void)candela::scene_problems(scene);
  } catch (const candela::ConfigError&) {
  }
  return 0;
}
