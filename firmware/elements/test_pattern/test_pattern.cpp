#include "elements/test_pattern/test_pattern.h"

#include <array>
#include <cstdint>

#include "gl/program.h"
#include "gl/texture.h"
#include "params/params.h"

namespace candela {
namespace {

// The frame counter's eight digits (frames modulo 10^8, leading zeros shown)
// as seven-segment masks, segments a..g as bits 0..6.
std::array<GLint, 8> counter_segments(uint64_t frame) {
  static constexpr GLint kMask[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F};
  std::array<GLint, 8> out{};
  for (int i = 7; i >= 0; --i, frame /= 10) out[static_cast<size_t>(i)] = kMask[frame % 10];
  return out;
}

class TestPattern final : public Element {
 public:
  explicit TestPattern(int steps_per_period)
      : steps_per_period_(steps_per_period),
        program_(Program::from_library("fullscreen.vert", "test_pattern.frag")),
        vao_(make_vertex_array()),
        u_resolution_(program_.uniform("u_resolution")),
        u_phase_(program_.uniform("u_phase")),
        u_segments_(program_.uniform("u_segments")) {}

  void update(const StepContext& s) override {
    phase_ = test_pattern_phase(s.step, steps_per_period_);
  }
  void hash_state(StateHash& hash) const override { hash.add(phase_); }

  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass != DrawPass::kBackground) return;
    program_.use();
    glUniform2f(u_resolution_, static_cast<float>(f.width), static_cast<float>(f.height));
    glUniform1f(u_phase_, static_cast<float>(phase_));
    glUniform1iv(u_segments_, 8, counter_segments(f.frame).data());
    glBindVertexArray(vao_.get());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

 private:
  int steps_per_period_;
  double phase_ = 0;
  Program program_;
  VertexArray vao_;
  GLint u_resolution_, u_phase_, u_segments_;
};

class TestPatternSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext&) const override {
    return std::make_unique<TestPattern>(steps_per_period);
  }
  int steps_per_period = 120;
};

std::unique_ptr<ElementSpec> parse(ParamReader& r) {
  auto spec = std::make_unique<TestPatternSpec>();
  spec->steps_per_period = static_cast<int>(r.integer("period_steps", 120, 2, 1000000));
  r.finish();
  return spec;
}

}  // namespace

const ElementKind& test_pattern_kind() {
  static const ElementKind kind{"test_pattern", "colour bars, frame counter and a moving marker",
                                parse};
  return kind;
}

}  // namespace candela
