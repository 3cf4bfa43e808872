// The shader's noise functions against the CPU reference: the same points,
// the same tables, rendered into a float target and read back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "core/random.h"
#include "display/display.h"
#include "elements/perlinfire/noise_tables.h"
#include "elements/perlinfire/perlinfire.h"
#include "embedded_shaders.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "elements/perlinfire/noise_reference.h"

namespace candela {
namespace {

constexpr int kGrid = 48;  // kGrid x kGrid points per render

// One output pixel per point: R simplex3d, G flow3d, B simplex4d, A perlin4d.
const char* kProbe = R"(#version 300 es
precision highp float;
uniform highp sampler2D u_points;
uniform vec2 u_flow_cs;
out vec4 o_value;
void main() {
  vec4 p = texelFetch(u_points, ivec2(gl_FragCoord.xy), 0);
  o_value = vec4(pf_snoise3(p.xyz), pf_snoise3_flow(p.xyz, u_flow_cs), pf_snoise4(p), pf_pnoise4(p));
}
)";

Texture table_texture(GLenum internal, GLenum format, GLenum type, const void* data) {
  Texture t = make_texture();
  glBindTexture(GL_TEXTURE_2D, t.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), 256, 256, 0, format, type, data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

class NoiseProbe : public ::testing::Test {
 protected:
  void SetUp() override {
    DisplayOptions o;
    o.kind = "headless";
    o.width = 16;
    o.height = 16;
    display_ = open_display(o);
    program_ =
        Program::from_source("fullscreen.vert", shaders::find("fullscreen.vert"), "noise probe",
                             perlinfire_fragment_source(kProbe, FireNoise::kSimplex3d));
    perm_ = table_texture(GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, tables_.perm2d().data());
    grad3_ = table_texture(GL_RGBA8_SNORM, GL_RGBA, GL_BYTE, tables_.grad3_rgba().data());
    grad4_ = table_texture(GL_RGBA8_SNORM, GL_RGBA, GL_BYTE, tables_.grad4_rgba().data());
    // A float target: 32-bit where EXT_color_buffer_float allows (llvmpipe does).
    const char* ext = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
    const bool f32 = ext && std::strstr(ext, "GL_EXT_color_buffer_float");
    target_ = make_texture();
    glBindTexture(GL_TEXTURE_2D, target_.get());
    glTexImage2D(GL_TEXTURE_2D, 0, f32 ? GL_RGBA32F : GL_RGBA16F, kGrid, kGrid, 0, GL_RGBA,
                 f32 ? GL_FLOAT : GL_HALF_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    fbo_ = make_framebuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target_.get(), 0);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER),
              static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
    vao_ = make_vertex_array();
    points_tex_ = make_texture();
  }

  // Random points, spread over negative and positive lattice cells and past
  // the tables' 256-cell wrap.
  void make_points(double spread, uint64_t seed) {
    Pcg32 rng(seed);
    points_.resize(kGrid * kGrid * 4);
    for (float& v : points_) v = static_cast<float>((rng.unit_double() * 2 - 1) * spread);
    glBindTexture(GL_TEXTURE_2D, points_tex_.get());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kGrid, kGrid, 0, GL_RGBA, GL_FLOAT, points_.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }

  std::vector<float> render(double flow_angle) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glViewport(0, 0, kGrid, kGrid);
    glDisable(GL_BLEND);
    program_.use();
    const std::pair<const char*, GLuint> textures[] = {{"u_perm", perm_.get()},
                                                       {"u_grad3", grad3_.get()},
                                                       {"u_grad4", grad4_.get()},
                                                       {"u_points", points_tex_.get()}};
    for (int i = 0; i < 4; ++i) {
      glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + i));
      glBindTexture(GL_TEXTURE_2D, textures[i].second);
      glUniform1i(program_.uniform(textures[i].first), i);
    }
    glUniform2f(program_.uniform("u_flow_cs"), static_cast<float>(std::cos(flow_angle)),
                static_cast<float>(std::sin(flow_angle)));
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> out(kGrid * kGrid * 4);
    glReadPixels(0, 0, kGrid, kGrid, GL_RGBA, GL_FLOAT, out.data());
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return out;
  }

  test::P3 p3(size_t i) const { return {points_[i * 4], points_[i * 4 + 1], points_[i * 4 + 2]}; }
  test::P4 p4(size_t i) const {
    return {points_[i * 4], points_[i * 4 + 1], points_[i * 4 + 2], points_[i * 4 + 3]};
  }

  NoiseTables tables_{12345};
  test::NoiseReference reference_{tables_};
  std::unique_ptr<Display> display_;
  Program program_;
  Texture perm_, grad3_, grad4_, target_, points_tex_;
  Framebuffer fbo_;
  VertexArray vao_;
  std::vector<float> points_;
};

TEST_F(NoiseProbe, ShaderNoiseMatchesTheCpuReference) {
  const char* names[] = {"simplex3d", "flow3d", "simplex4d", "perlin4d"};
  for (double spread : {4.0, 300.0}) {
    make_points(spread, static_cast<uint64_t>(spread));
    const double angle = 0.7;
    const std::vector<float> gpu = render(angle);
    double max_diff[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < static_cast<size_t>(kGrid * kGrid); ++i) {
      const double cpu[4] = {reference_.simplex3(p3(i)), reference_.simplex3_flow(p3(i), angle),
                             reference_.simplex4(p4(i)), reference_.perlin4(p4(i))};
      for (int k = 0; k < 4; ++k)
        max_diff[k] =
            std::max(max_diff[k], std::fabs(cpu[k] - gpu[i * 4 + static_cast<size_t>(k)]));
    }
    for (int k = 0; k < 4; ++k) {
      SCOPED_TRACE(std::string(names[k]) + ", spread " + std::to_string(spread));
      EXPECT_LE(max_diff[k], 1e-3);
    }
  }
}

TEST_F(NoiseProbe, ValuesStayInRangeWithMeanNearZero) {
  make_points(40.0, 7);
  const std::vector<float> gpu = render(1.3);
  const size_t n = static_cast<size_t>(kGrid * kGrid);
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    double sum = 0, sq = 0, lo = 1e9, hi = -1e9;
    for (size_t i = 0; i < n; ++i) {
      const double v = gpu[i * 4 + static_cast<size_t>(k)];
      sum += v;
      sq += v * v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GE(lo, -1.05);
    EXPECT_LE(hi, 1.05);
    EXPECT_NEAR(sum / n, 0.0, 0.05);
    const double rms = std::sqrt(sq / n);
    EXPECT_GT(rms, 0.15);  // noise, not a constant
    EXPECT_LT(rms, 0.5);
    EXPECT_GT(hi - lo, 1.0);  // uses most of its range
  }
}

TEST_F(NoiseProbe, FlowNoiseChangesSmoothlyWithTime) {
  make_points(10.0, 3);
  // 1.5 rad/s (the element's default spin) at 60 steps per second.
  const double step = 1.5 / 60.0;
  std::vector<float> prev = render(0.0);
  double max_rate = 0, mean_rate = 0;
  const int steps = 24;
  const size_t n = static_cast<size_t>(kGrid * kGrid);
  for (int s = 1; s <= steps; ++s) {
    const std::vector<float> cur = render(s * step);
    for (size_t i = 0; i < n; ++i) {
      const double rate = std::fabs(cur[i * 4 + 1] - prev[i * 4 + 1]) / step;
      max_rate = std::max(max_rate, rate);
      mean_rate += rate / (n * steps);
    }
    prev = cur;
  }
  // |d noise / d angle| is bounded by the gradients' length times the
  // kernel sums (about 1.6 here); a jump would show up as ~1/step = 40.
  EXPECT_LT(max_rate, 3.0);
  EXPECT_GT(mean_rate, 0.05);  // and it does move
  // The spatial noise (no flow) does not change with the angle at all.
  const std::vector<float> a = render(0.0), b = render(2.0);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(a[i * 4], b[i * 4]);
}

}  // namespace
}  // namespace candela
