// What burns under a fire, as a camera sees it: logs and a bed of coals,
// drawn into a radiance canvas (linear light, rows top-down) around the
// simulated flames. Real footage of a fire always shows them: the front log
// hides where the tongues leave the wood, lit from above by the flames;
// charred wood glows in a net of cracks; coals glow and pulse under the
// logs. Without them a simulated fire is flames floating on black.
#pragma once

#include <cstdint>
#include <vector>

namespace candela::fluid {

// A log seen side-on: a capsule between two canvas points, pixels.
struct Log {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  double radius = 10.0;
  bool in_front = true;  // in front of the flames (hides them) or behind (they add over it)
  uint64_t grain = 0;    // seeds its bark and cracks (with the bed's seed)
};

struct FuelBed {
  std::vector<Log> logs;
  double coal_top = 0.0;    // canvas rows below this show the coal bed (0 = no coals)
  double coal_size = 6.0;   // typical coal, pixels
  double char_glow = 0.35;  // brightness of the glowing cracks in charred wood, linear
  double coal_glow = 0.35;  // brightness of a glowing coal, linear
  double light = 1.0;       // how strongly the flames light the wood
  uint64_t seed = 1;
};

// A fuel bed for a canvas of the given size: a long front log across the
// bottom, two shorter ones behind it (unless `back_logs` is false), coals
// under them; seeded. Without the back logs the flames reach down to the
// front log: a scene that fades a model image's foot out above that log
// (the eigen fireplace) would otherwise show the back logs' lit tops through
// its flames as one straight band.
FuelBed hearth_fuel_bed(int width, int height, uint64_t seed, bool back_logs = true);

// Composites the bed with the flames' light already in `canvas`: logs behind
// the flames first (the flames' light adds over them), then the front logs
// over the flames; coals below. `time` (s) drives the glow's slow pulsing.
void draw_fuel_bed(const FuelBed& bed, double time, int width, int height,
                   std::vector<float>& canvas);

}  // namespace candela::fluid
