// The "candles" scene element: a group of candles, each a CandleRig with a
// wax body, a morphed flame still and a glow, all drawn instanced (one draw
// call per kind of thing, however many candles). Glows go first, then
// bodies, then flames, as the candle paper orders them. candles_spec.cpp
// reads the keys below; candle_body_mesh.cpp makes the wax body's mesh;
// candles.cpp stages the instances (prepare) and draws them.
//
//   [[element]]
//   kind = "candles"
//   flame_height = 0.055          # metres per still height
//   still = "my_flame.png"        # optional RGBA still; default: drawn by code
//   [element.calm] / [element.breeze] / [element.wick] / [element.pendulum] / [element.extinguish]
//   [[element.candle]]            # one per candle (same sub-tables override per candle)
//   position = [0, 0, 0]; height = 0.12; radius = 0.022; wax = "#efe6d4"; flame_scale = 1; seed = 7
//   [element.grid]                # or/and: many candles on a jittered grid
//   count = 100; columns = 10; spacing = 0.1
#pragma once

#include <memory>
#include <vector>

#include "elements/candle/candle_params.h"
#include "elements/candle/candle_rig.h"
#include "gl/math.h"
#include "scene/element.h"

namespace candela {

struct CandleDesc {
  Vec3 position;  // bottom centre of the wax, world metres
  float height = 0.12f;
  float radius = 0.022f;
  Vec3 wax{0.94f, 0.90f, 0.83f};
  float flame_scale = 1.0f;
  uint64_t seed = 0;  // 0: from the element's seed and the candle's index
  CandleParams params;
};

class CandlesSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext& context) const override;
  // Scene budget (scene/element.h): one unit per 512 candles begun.
  unsigned cost() const override { return 1 + static_cast<unsigned>(candles.size() / 512); }
  std::vector<CandleDesc> candles;
  FlameLook look;
};

// Parses a "candles" element (for tests: without GL).
std::unique_ptr<CandlesSpec> parse_candles(ParamReader& reader);
// Seeds the candles of a group from the element's seed, as create() does.
uint64_t candle_seed(uint64_t element_seed, size_t index);

const ElementKind& candles_kind();

}  // namespace candela
