// The built-in flame still, drawn procedurally (no footage): a teardrop with
// a blue base, a bright yellow-white core and an orange rim, transparent
// around it. Laid out to match the default StillLayout.
#pragma once

#include "core/image.h"
#include "elements/candle/candle_params.h"

namespace candela {

// RGBA, rows top to bottom, `height` high and height/2 wide.
Image make_flame_still(int height = 256, const StillLayout& layout = {});

}  // namespace candela
