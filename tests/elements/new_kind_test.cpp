// Follows firmware/elements/README.md ("Adding a new kind of flame") step by
// step to add a trivial kind, "flat_flame": a camera-facing rectangle whose
// colour is rendered offscreen in prepare() and shown by the flame pass.
// If the rules there were not enough (the screen not re-bound after
// prepare, the shared resource not one per scene or prepared out of order),
// these pixels and counts would be wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "gl/program.h"
#include "gl/render_target.h"
#include "gl/texture.h"
#include "params/params.h"
#include "scene/element.h"
#include "scene/scene_file.h"
#include "support/render_harness.h"
#include "support/scene_text.h"

namespace candela {
namespace {

constexpr int kW = 160, kH = 90;

// Step 3's shaders. A kind of the runtime keeps them in gles_shaders/ and
// uses Program::from_library; a test cannot add to the built-in library.
constexpr const char* kVert = R"(#version 300 es
uniform mat4 u_view_projection;
uniform vec3 u_origin;  // bottom centre, world
uniform vec2 u_size;    // width, height, world
out vec2 v_uv;
void main() {
  vec2 c = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  v_uv = c;
  vec3 p = u_origin + vec3((c.x - 0.5) * u_size.x, c.y * u_size.y, 0.0);
  gl_Position = u_view_projection * vec4(p, 1.0);
}
)";
constexpr const char* kFrag = R"(#version 300 es
precision mediump float;
uniform sampler2D u_image;
in vec2 v_uv;
out vec4 o_colour;
void main() { o_colour = texture(u_image, v_uv); }
)";

// Step 2: the settings, parsed without GL.
struct FlatFlameSettings {
  Vec3 colour{1.0f, 0.5f, 0.1f};
  float width = 0.2f, height = 0.4f;
  int flicker_steps = 30;  // the flame halves its brightness every other this many steps
};

// Step 7: what all flat flames of a scene share (the program and its vertex
// array), and counts the test checks.
class FlatFlameShared final : public SceneResource {
 public:
  FlatFlameShared()
      : program(Program::from_source("flat_flame.vert", kVert, "flat_flame.frag", kFrag)),
        vao(make_vertex_array()),
        u_vp(program.uniform("u_view_projection")),
        u_origin(program.uniform("u_origin")),
        u_size(program.uniform("u_size")),
        u_image(program.uniform("u_image")) {}
  void prepare(const FrameContext&) override {
    ++prepares;
    // After every element's prepare of this frame.
    if (element_prepares != members * prepares) out_of_order = true;
  }
  Program program;
  VertexArray vao;
  GLint u_vp, u_origin, u_size, u_image;
  int members = 0, prepares = 0, element_prepares = 0;
  bool out_of_order = false;
};

// The latest scene's shared resource (alive as long as its harness).
FlatFlameShared* g_shared = nullptr;

// Step 3: the element.
class FlatFlame final : public Element {
 public:
  FlatFlame(const FlatFlameSettings& s, Vec3 position, SceneResources& resources)
      : s_(s),
        position_(position),
        shared_(resources.get<FlatFlameShared>()),
        target_(RenderTarget::checked(8, 16, "flat_flame: image")) {
    ++shared_.members;
    g_shared = &shared_;
  }

  // Step 4: the animation, on the fixed step; no GL.
  void update(const StepContext& step) override {
    dim_ = (step.step / static_cast<uint64_t>(s_.flicker_steps)) % 2 == 1;
  }

  // Step 5: the offscreen pass; the screen is the scene's to re-bind.
  void prepare(const FrameContext&) override {
    ++shared_.element_prepares;
    const float k = dim_ ? 0.5f : 1.0f;
    target_.bind();
    glViewport(0, 0, target_.width(), target_.height());
    glClearColor(s_.colour.x * k, s_.colour.y * k, s_.colour.z * k, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }

  // Step 6: the flame pass draws into the bound screen framebuffer only.
  void draw(const FrameContext& f, DrawPass pass) override {
    if (pass != DrawPass::kFlame) return;
    shared_.program.use();
    glUniformMatrix4fv(shared_.u_vp, 1, GL_FALSE, f.view_projection.m);
    glUniform3f(shared_.u_origin, position_.x, position_.y, position_.z);
    glUniform2f(shared_.u_size, s_.width, s_.height);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, target_.texture());
    glUniform1i(shared_.u_image, 0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(shared_.vao.get());
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glBindVertexArray(0);
  }

 private:
  FlatFlameSettings s_;
  Vec3 position_;
  FlatFlameShared& shared_;
  RenderTarget target_;
  bool dim_ = false;
};

class FlatFlameSpec final : public ElementSpec {
 public:
  std::unique_ptr<Element> create(const SceneContext& context) const override {
    return std::make_unique<FlatFlame>(settings, position, *context.resources);
  }
  FlatFlameSettings settings;
};

std::unique_ptr<ElementSpec> parse_flat_flame(ParamReader& r) {
  auto spec = std::make_unique<FlatFlameSpec>();
  FlatFlameSettings& s = spec->settings;
  s.colour = r.color("colour", s.colour);
  s.width = static_cast<float>(r.number("width", s.width, 0.01, 10));
  s.height = static_cast<float>(r.number("height", s.height, 0.01, 10));
  s.flicker_steps = static_cast<int>(r.integer("flicker_steps", s.flicker_steps, 1, 100000));
  r.finish();
  return spec;
}

// Step 8: the kind, handed to the scene reader (the runtime's kinds are
// listed in firmware/elements/element_kinds.cpp).
const ElementKind kFlatFlame{"flat_flame", "a flat-colour test flame", parse_flat_flame};

SceneDesc scene(const std::string& elements) {
  const std::string text = test::black_room(0.0, 0.2, 1.5, 0.0, 0.2, 0.0, 40) + elements;
  return load_scene_text(text, "<flat flame>", {&kFlatFlame, 1});
}

// Where a world point lands on the frame read back (rows top down), with
// the camera of scene() as Scene::draw() sets it up.
std::pair<int, int> pixel_of(Vec3 p) {
  const Mat4 view = Mat4::look_at({0.0f, 0.2f, 1.5f}, {0.0f, 0.2f, 0.0f}, {0, 1, 0});
  const Mat4 proj =
      Mat4::perspective(40 * 3.14159265f / 180.0f, static_cast<float>(kW) / kH, 0.02f, 100.0f);
  const Vec4 c = (proj * view) * Vec4{p.x, p.y, p.z, 1.0f};
  const float x = (c.x / c.w * 0.5f + 0.5f) * kW, y = (c.y / c.w * 0.5f + 0.5f) * kH;
  return {static_cast<int>(x), kH - 1 - static_cast<int>(y)};
}

void expect_colour(const test::Frame& f, std::pair<int, int> at, Vec3 want) {
  const test::Rgba c = f.at(at.first, at.second);
  SCOPED_TRACE("pixel " + std::to_string(at.first) + "," + std::to_string(at.second));
  EXPECT_NEAR(c.r, want.x * 255, 2.0);
  EXPECT_NEAR(c.g, want.y * 255, 2.0);
  EXPECT_NEAR(c.b, want.z * 255, 2.0);
}

// Step 9: its pixels, headless.
TEST(NewKind, TheOffscreenColourIsWhatTheFlamePassShows) {
  test::RenderHarness h(scene(R"(
[[element]]
kind = "flat_flame"
position = [0.0, 0.0, 0.0]
colour = "#ff8010"
)"),
                        kW, kH);
  h.run(10);  // steps 0..9: bright
  const test::Frame f = h.read();
  const Vec3 orange{1.0f, 128 / 255.0f, 16 / 255.0f};
  expect_colour(f, pixel_of({0.0f, 0.2f, 0.0f}), orange);   // the flame's middle
  expect_colour(f, pixel_of({0.0f, 0.02f, 0.0f}), orange);  // near its base
  expect_colour(f, pixel_of({0.2f, 0.2f, 0.0f}), {});       // beside it: the background
  expect_colour(f, {2, 2}, {});

  // prepare() runs every frame: the colour follows update()'s flicker.
  h.run(30);  // 40 frames: step 39 is dim
  expect_colour(h.read(), pixel_of({0.0f, 0.2f, 0.0f}), orange * 0.5f);
}

TEST(NewKind, FlamesShareOneResourcePreparedOncePerFrameAfterThem) {
  test::RenderHarness h(scene(R"(
[[element]]
kind = "flat_flame"
position = [-0.3, 0.0, 0.0]
colour = "#ff0000"
[[element]]
kind = "flat_flame"
position = [0.3, 0.0, 0.0]
colour = "#0000ff"
)"),
                        kW, kH);
  h.run(5);
  const test::Frame f = h.read();
  expect_colour(f, pixel_of({-0.3f, 0.2f, 0.0f}), {1, 0, 0});
  expect_colour(f, pixel_of({0.3f, 0.2f, 0.0f}), {0, 0, 1});
  expect_colour(f, pixel_of({0.0f, 0.2f, 0.0f}), {});
  ASSERT_NE(g_shared, nullptr);
  EXPECT_EQ(g_shared->members, 2);       // one resource for both flames
  EXPECT_EQ(g_shared->prepares, 5 + 1);  // each frame run, and the one read
  EXPECT_EQ(g_shared->element_prepares, 2 * (5 + 1));
  EXPECT_FALSE(g_shared->out_of_order);
}

TEST(NewKind, BadSettingsNameTheirKey) {
  try {
    scene("[[element]]\nkind = \"flat_flame\"\nheight = -1\n");
    FAIL() << "accepted height = -1";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].height");
  }
  try {
    scene("[[element]]\nkind = \"flat_flame\"\ncolor = \"#ffffff\"\n");
    FAIL() << "accepted an unknown key";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "element[0].color");
  }
}

}  // namespace
}  // namespace candela
