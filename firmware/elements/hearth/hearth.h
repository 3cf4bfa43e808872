// `hearth`: what a fire stands on. Logs (bark, charred sides with glowing
// cracks, end grain), a bed of embers that glow and pulse, and the fire's
// flickering light on both. Drawn in the body pass, so the flames of any
// fire element (perlinfire, eigenflame) are drawn over it.
#pragma once

#include "scene/element.h"

namespace candela {

const ElementKind& hearth_kind();

}  // namespace candela
