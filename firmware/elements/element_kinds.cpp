// Every kind of scene element the runtime knows. Add a kind here.
#include "elements/candle/candles.h"
#include "elements/eigenflame/eigenflame.h"
#include "elements/hearth/hearth.h"
#include "elements/perlinfire/perlinfire.h"
#include "elements/test_pattern/test_pattern.h"
#include "scene/element.h"

namespace candela {

std::span<const ElementKind> element_kinds() {
  static const ElementKind kKinds[] = {
      test_pattern_kind(),
      candles_kind(),
      perlinfire_kind(),
      eigenflame_kind(),
      hearth_kind(),
  };
  return kKinds;
}

}  // namespace candela
