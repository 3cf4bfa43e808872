// The "candles" element's scene keys (candles.h shows them): the look, the
// candles one by one and on a grid. No GL: tests parse without a context.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "core/image.h"
#include "core/random.h"
#include "elements/candle/candles.h"
#include "params/params.h"

namespace candela {
namespace {

// The keys a candle and its group share (the group's are every candle's
// defaults): height, radius, wax, flame_scale; `c` holds the defaults.
void read_shape(ParamReader& r, CandleDesc& c) {
  c.height = static_cast<float>(r.number("height", c.height, 0.005, 2));
  c.radius = static_cast<float>(r.number("radius", c.radius, 0.003, 0.5));
  c.wax = r.color("wax", c.wax);
  c.flame_scale = static_cast<float>(r.number("flame_scale", c.flame_scale, 0.1, 10));
}

// Reads the per-candle keys shared by [[element.candle]] entries.
CandleDesc read_candle(ParamReader& r, const CandleDesc& def) {
  CandleDesc c = def;
  c.position = r.vec3("position", def.position);
  read_shape(r, c);
  c.seed = static_cast<uint64_t>(r.integer("seed", 0, 0, INT64_MAX));
  c.params = parse_candle_params(r, def.params);
  r.finish();
  return c;
}

// A deterministic candle layout for [element.grid]: rows of candles with
// seeded jitter and sizes.
void add_grid(ParamReader& g, const CandleDesc& def, std::vector<CandleDesc>& out) {
  const auto count = static_cast<int>(g.integer("count", 9, 1, 4096));
  const auto columns = static_cast<int>(g.integer("columns", 0, 0, 4096));
  const float spacing = static_cast<float>(g.number("spacing", 0.12, 0.01, 10));
  const Vec3 centre = g.vec3("center", {});
  const float jitter = static_cast<float>(g.number("jitter", 0.3, 0, 1));
  const float hmin = static_cast<float>(g.number("height_min", 0.07, 0.005, 2));
  const float hmax = static_cast<float>(g.number("height_max", 0.16, 0.005, 2));
  const float rmin = static_cast<float>(g.number("radius_min", 0.018, 0.003, 0.5));
  const float rmax = static_cast<float>(g.number("radius_max", 0.026, 0.003, 0.5));
  const auto seed = static_cast<uint64_t>(g.integer("seed", 1, 0, INT64_MAX));
  if (hmax < hmin) g.fail("height_max", "expected height_max >= height_min");
  if (rmax < rmin) g.fail("radius_max", "expected radius_max >= radius_min");
  g.finish();
  const int cols =
      columns > 0 ? columns : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  const int rows = (count + cols - 1) / cols;
  Pcg32 rng(seed, 0x67726964);
  for (int i = 0; i < count; ++i) {
    const int r = i / cols, c = i % cols;
    CandleDesc d = def;
    const float jx = (static_cast<float>(rng.unit_double()) - 0.5f) * jitter * spacing;
    const float jz = (static_cast<float>(rng.unit_double()) - 0.5f) * jitter * spacing;
    d.position = centre + Vec3{(static_cast<float>(c) - (cols - 1) * 0.5f) * spacing + jx, 0,
                               (static_cast<float>(r) - (rows - 1) * 0.5f) * spacing + jz};
    d.height = hmin + (hmax - hmin) * static_cast<float>(rng.unit_double());
    d.radius = rmin + (rmax - rmin) * static_cast<float>(rng.unit_double());
    out.push_back(d);
  }
}

std::unique_ptr<ElementSpec> parse_kind(ParamReader& r) { return parse_candles(r); }

}  // namespace

std::unique_ptr<CandlesSpec> parse_candles(ParamReader& r) {
  auto spec = std::make_unique<CandlesSpec>();
  FlameLook& look = spec->look;
  look.flame_height = static_cast<float>(r.number("flame_height", look.flame_height, 0.001, 5));
  look.mesh = static_cast<int>(r.integer("mesh", look.mesh, 1, 64));
  look.warp_a = static_cast<float>(r.number("warp_a", look.warp_a, 0.001, 1));
  look.warp_b = static_cast<float>(r.number("warp_b", look.warp_b, 0.5, 2));
  look.warp_p = static_cast<float>(r.number("warp_p", look.warp_p, 0, 1));
  look.glow_scale = static_cast<float>(r.number("glow_scale", look.glow_scale, 0, 20));
  look.glow_strength = static_cast<float>(r.number("glow_strength", look.glow_strength, 0, 10));
  look.glow_falloff = static_cast<float>(r.number("glow_falloff", look.glow_falloff, 0.01, 1000));
  const std::string still = r.path("still");
  look.layout.base = r.fixed("still_base", look.layout.base.to_double(), 0, 0.9);
  look.layout.tip = r.fixed("still_tip", look.layout.tip.to_double(), 0.1, 1);
  if (look.layout.tip <= look.layout.base) r.fail("still_tip", "expected still_tip > still_base");
  double aspect = 0.5;
  if (!still.empty()) {
    try {
      auto img = std::make_shared<Image>(read_png(still, 4));
      aspect = static_cast<double>(img->width) / img->height;
      look.still = std::move(img);
    } catch (const std::exception& e) {
      r.fail("still", std::string("expected an RGBA PNG flame still: ") + e.what());
    }
  }
  // Half-width of V1/V2 as a fraction of the still's width.
  look.layout.half_width =
      Fixed::from_double(r.number("still_half_width", 0.18, 0.01, 0.5) * aspect);

  CandleDesc def;
  def.params = parse_candle_params(r, CandleParams{});
  def.height = static_cast<float>(r.number("height", def.height, 0.005, 2));
  def.radius = static_cast<float>(r.number("radius", def.radius, 0.003, 0.5));
  def.wax = r.color("wax", def.wax);
  def.flame_scale = static_cast<float>(r.number("flame_scale", def.flame_scale, 0.1, 10));
  for (ParamReader& c : r.table_array("candle")) spec->candles.push_back(read_candle(c, def));
  if (r.has("grid")) {
    ParamReader g = r.table("grid");
    add_grid(g, def, spec->candles);
  }
  if (spec->candles.empty())
    r.fail("candle", "expected at least one [[element.candle]] or an [element.grid]");
  r.finish();
  return spec;
}

const ElementKind& candles_kind() {
  static const ElementKind kind{
      "candles", "candles with noise-morphed flames, glows and wax bodies (Ogawa et al.)",
      parse_kind};
  return kind;
}

}  // namespace candela
