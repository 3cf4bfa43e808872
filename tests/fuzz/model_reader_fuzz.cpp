// libFuzzer target for the model-file reader and the players built from what
// it accepts: any byte string must either be refused with a ModelError or
// load as a model that the graph walk (GraphWalker, GraphPlayer), the
// Learning Flames ARP and its shape model play without crashing, dividing by
// zero or overflowing (issue 15: a valid-CRC model crashed GraphWalker).
//   build with clang: ninja -C build-fuzz model_reader_fuzz (tests/fuzz/run-fuzz.sh)
//   run: build-fuzz/tests/fuzz/model_reader_fuzz CORPUS -max_total_time=60
#include <algorithm>
#include <cstdint>
#include <vector>

#include "elements/eigenflame/flame_shape.h"
#include "flame_drivers/arp_driver.h"
#include "flame_drivers/graph_walker.h"
#include "model/flame_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace candela;
  try {
    auto file = model::ModelFile::from_bytes({data, data + size}, "fuzz");
    auto m = model::FlameModel::from(file);
    // Touch what the runtime would: a reconstruction and the graph.
    std::vector<float> out(m.mean.pixels());
    if (m.frames() > 0) m.reconstruct(m.weights_of(0), out);
    for (int i = 0; i < m.frames(); ++i) (void)m.graph.successors_of(i);
    // The graph player, as the eigen-flame element builds it (lean from the
    // first weight, clamped as the element's derivation clamps it).
    std::vector<Fixed> lean(static_cast<size_t>(m.frames()));
    for (int i = 0; i < m.frames(); ++i)
      lean[static_cast<size_t>(i)] =
          Fixed::from_double(std::clamp(static_cast<double>(m.weights_of(i)[0]) * 1e-3, -1.0, 1.0));
    WalkSettings s;
    s.max_stretch = 4;
    s.window = 64;
    GraphWalker walker({m.graph.offsets, m.graph.successors, m.graph.cost}, m.weights,
                       m.components(), lean, s, 7);
    GraphPlayer player(std::move(walker), m.weights, m.components(), Fixed::from_ratio(1, 2));
    for (int i = 0; i < 200; ++i) {
      player.set_rate(Fixed::from_ratio(1 + i % 5, 3));
      player.step(Fixed::from_ratio((i % 7) - 3, 20));
    }
    if (m.has_learning_flames) {
      ArpProcess arp(ArpView::of(m.flames), 11);
      const FlameShapeModel shape = FlameShapeModel::from(m);
      FlamePose pose;
      for (int i = 0; i < 50; ++i) shape.pose(arp.step(), 0.1f, pose);
    }
  } catch (const model::ModelError&) {
  }
  return 0;
}
