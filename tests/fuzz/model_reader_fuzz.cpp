// libFuzzer target for the model-file reader: any byte string must either
// load as a valid model or be refused with a ModelError, never crash or hang.
//   build with clang: ninja -C build model_reader_fuzz
//   run: build/tests/fuzz/model_reader_fuzz build/tests/fuzz/corpus -max_total_time=60
#include <cstdint>
#include <vector>

#include "model/flame_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    auto file = candela::model::ModelFile::from_bytes({data, data + size}, "fuzz");
    auto m = candela::model::FlameModel::from(file);
    // Touch what the runtime would: a reconstruction and the graph.
    std::vector<float> out(m.mean.pixels());
    if (m.frames() > 0) m.reconstruct(m.weights_of(0), out);
    for (int i = 0; i < m.frames(); ++i) (void)m.graph.successors_of(i);
  } catch (const candela::model::ModelError&) {
  }
  return 0;
}
