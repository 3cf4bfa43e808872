// Scene files: every kind of bad input gets a message naming the file, the
// key and what was expected.
#include "scene/scene_file.h"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/scene.h"

namespace candela {
namespace {

// Loads `text` and returns the ConfigError it raised (fails if none).
ConfigError error_of(const std::string& text, const std::string& name = "bad.toml") {
  try {
    load_scene_text(text, name);
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return ConfigError("", "", "");
}

TEST(SceneConfig, MissingFileNamesThePath) {
  try {
    load_scene_file("/nonexistent/scene.toml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/scene.toml");
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
  }
}

TEST(SceneConfig, SyntaxErrorNamesLine) {
  const auto e = error_of("seed = 1\n[display\nwidth = 3\n");
  EXPECT_EQ(e.file(), "bad.toml");
  EXPECT_NE(e.key().find("line 2"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("syntax"), std::string::npos) << e.what();
}

TEST(SceneConfig, WrongTypeNamesKeyAndExpectation) {
  const auto e = error_of("[display]\nwidth = \"wide\"\n");
  EXPECT_EQ(e.key(), "display.width");
  EXPECT_NE(e.expected().find("expected an integer"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("\"wide\""), std::string::npos) << e.what();
}

TEST(SceneConfig, UnknownKeyIsRejected) {
  const auto e = error_of("[camera]\nfov = 40\nzoom = 2\n");
  EXPECT_EQ(e.key(), "camera.zoom");
  EXPECT_NE(e.expected().find("unknown key"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("fov"), std::string::npos) << "lists the known keys: " << e.what();
}

TEST(SceneConfig, UnknownTopLevelTableIsRejected) {
  const auto e = error_of("[displya]\nwidth = 3\n");
  EXPECT_EQ(e.key(), "displya");
}

TEST(SceneConfig, OutOfRangeValueNamesRange) {
  const auto e = error_of("[camera]\nfov = 400\n");
  EXPECT_EQ(e.key(), "camera.fov");
  EXPECT_NE(e.expected().find("[5, 150]"), std::string::npos) << e.what();
  EXPECT_NE(e.expected().find("400"), std::string::npos) << e.what();
}

TEST(SceneConfig, BadColourIsExplained) {
  const auto e = error_of("[background]\ncolor = \"#12345\"\n");
  EXPECT_EQ(e.key(), "background.color");
  EXPECT_NE(e.expected().find("#rrggbb"), std::string::npos) << e.what();
  const auto e2 = error_of("[background]\ncolor = [0.1, 2.0, 0.1]\n");
  EXPECT_NE(e2.expected().find("[0, 1]"), std::string::npos) << e2.what();
}

TEST(SceneConfig, ElementErrorsNameTheElementIndex) {
  const auto e =
      error_of("[[element]]\nkind = \"test_pattern\"\n[[element]]\nkind = \"volcano\"\n");
  EXPECT_EQ(e.key(), "element[1].kind");
  EXPECT_NE(e.expected().find("test_pattern"), std::string::npos)
      << "lists the kinds: " << e.what();
  const auto e2 = error_of("[[element]]\nkind = \"test_pattern\"\nperiod_steps = 1\n");
  EXPECT_EQ(e2.key(), "element[0].period_steps");
  const auto e3 = error_of("[[element]]\nposition = [0, 0, 0]\n");
  EXPECT_EQ(e3.key(), "element[0].kind");
  const auto e4 = error_of("[[element]]\nkind = \"test_pattern\"\nposition = [0, 0]\n");
  EXPECT_EQ(e4.key(), "element[0].position");
  EXPECT_NE(e4.expected().find("3 numbers"), std::string::npos) << e4.what();
}

TEST(SceneConfig, ElementMustBeAnArrayOfTables) {
  const auto e = error_of("element = 3\n");
  EXPECT_EQ(e.key(), "element");
}

TEST(SceneConfig, ValidSceneLoadsWithItsValues) {
  const SceneDesc s = load_scene_text(
      "seed = 7\n[display]\nwidth = 640\nheight = 360\n[background]\ncolor = \"#ff8000\"\n"
      "[camera]\nfov = 50\n[[element]]\nkind = \"test_pattern\"\nname = \"bars\"\nposition = [1, "
      "2, 3]\n",
      "good.toml");
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 360);
  EXPECT_NEAR(s.background.x, 1.0f, 1e-6);
  EXPECT_NEAR(s.background.y, 128 / 255.0f, 1e-6);
  EXPECT_FLOAT_EQ(s.camera.fov_deg, 50);
  ASSERT_EQ(s.elements.size(), 1u);
  EXPECT_EQ(s.elements[0].name, "bars");
  EXPECT_FLOAT_EQ(s.elements[0].spec->position.z, 3);
}

// Issue 15 (2): toml++ recursed once per part of a dotted key or header; 50,000
// parts overflowed its stack. Refused before parsing, naming the line.
TEST(SceneConfig, DeepNestingIsRefusedBeforeParsing) {
  const std::string deep = "a" + [] {
    std::string s;
    for (int i = 0; i < 50000; ++i) s += ".a";
    return s;
  }();
  for (const std::string& text : {"seed = 1\n" + deep + " = 1\n", "\n\n[" + deep + "]\n",
                                  "[[" + deep + "]]\n", "x = " + std::string(50000, '[')}) {
    const auto e = error_of(text);
    EXPECT_EQ(e.file(), "bad.toml");
    EXPECT_EQ(e.key().rfind("line ", 0), 0u) << e.what();
    EXPECT_NE(e.expected().find("too deep"), std::string::npos) << e.what();
  }
  // What real scenes nest is fine, and dots in strings, comments and floats are not nesting.
  const SceneDesc s = load_scene_text(
      "# a.b.c.d.e.f.g.h.i.j.k.l.m.n.o.p.q.r.s.t.u.v.w.x.y.z.a.b.c.d.e.f.g.h\n"
      "[camera]\nposition = [0.5, 0.25, 2.5]\n[[element]]\nkind = \"test_pattern\"\n"
      "name = \"...................................................\"\n",
      "ok.toml");
  EXPECT_FLOAT_EQ(s.camera.position.x, 0.5f);
}

// Issue 15 (7): integers beyond 2^53 read as 0 in number keys, which is in many ranges.
TEST(SceneConfig, HugeIntegersInNumberKeysAreRangeChecked) {
  const auto e = error_of("[wind]\nspeed = 9007199254740993\n");
  EXPECT_EQ(e.key(), "wind.speed");
  EXPECT_NE(e.expected().find("got 9007199254740993"), std::string::npos) << e.what();
  const auto v = error_of("[camera]\nposition = [0, 9007199254740993, 2]\n");
  EXPECT_EQ(v.key(), "camera.position");
}

// Issue 15 (11): degenerate scenes that used to pass.
TEST(SceneConfig, DegenerateCameraAndDisplayAreRefused) {
  EXPECT_EQ(error_of("[camera]\nposition = [1, 1, 1]\ntarget = [1, 1, 1]\n").key(),
            "camera.target");
  EXPECT_EQ(error_of("[camera]\nposition = [0, 2, 0]\ntarget = [0, 0, 0]\n").key(),
            "camera.target");
  EXPECT_EQ(error_of("[camera]\nposition = [0, -2, 0]\ntarget = [0, 0, 0]\n").key(),
            "camera.target");
  EXPECT_EQ(error_of("[display]\nwidth = 100\n").key(), "display.height");
  EXPECT_EQ(error_of("[display]\nheight = 100\n").key(), "display.width");
  EXPECT_EQ(error_of("[display]\nwidth = 1\nheight = 1\n").key(), "display.width");
  EXPECT_EQ(error_of("[display]\nwidth = 640\nheight = 8\n").key(), "display.height");
  // Looking down steeply but not straight down is fine.
  EXPECT_NO_THROW(load_scene_text("[camera]\nposition = [0, 2, 0.1]\ntarget = [0, 0, 0]\n", "ok"));
}

TEST(SceneConfig, ReducedRenderSizeIsBounded) {
  const SceneDesc s =
      load_scene_text("[display]\nrender_scale = 0.5\nrender_max_height = 540\n", "ok.toml");
  EXPECT_FLOAT_EQ(s.render_scale, 0.5f);
  EXPECT_EQ(s.render_max_height, 540);
  const SceneDesc plain = load_scene_text("", "plain.toml");
  EXPECT_FLOAT_EQ(plain.render_scale, 1.0f);  // the screen's size unless asked
  EXPECT_EQ(plain.render_max_height, 0);
  for (const char* bad : {"render_scale = 0.1", "render_scale = 2", "render_scale = \"half\""}) {
    SCOPED_TRACE(bad);
    const auto e = error_of(std::string("[display]\n") + bad + "\n");
    EXPECT_EQ(e.key(), "display.render_scale");
  }
  const auto tiny = error_of("[display]\nrender_max_height = 50\n");
  EXPECT_EQ(tiny.key(), "display.render_max_height");
  EXPECT_NE(tiny.expected().find("120"), std::string::npos) << tiny.what();
  EXPECT_EQ(error_of("[display]\nrender_max_height = -1\n").key(), "display.render_max_height");
}

// The size a scene is drawn at: the tighter of the scale and the row limit,
// the screen's aspect kept, never above the screen's size.
TEST(ScaledRender, SizeIsTheTighterLimit) {
  EXPECT_EQ(scaled_render_size({1920, 1080}, 1.0f, 540), (RenderSize{960, 540}));
  EXPECT_EQ(scaled_render_size({1280, 720}, 1.0f, 540), (RenderSize{960, 540}));
  EXPECT_EQ(scaled_render_size({640, 360}, 1.0f, 540), (RenderSize{640, 360}));
  EXPECT_EQ(scaled_render_size({1920, 1080}, 0.5f, 0), (RenderSize{960, 540}));
  EXPECT_EQ(scaled_render_size({3840, 2160}, 0.5f, 720), (RenderSize{1280, 720}));
  EXPECT_EQ(scaled_render_size({1920, 1080}, 0.25f, 720), (RenderSize{480, 270}));
  EXPECT_EQ(scaled_render_size({800, 600}, 1.0f, 0), (RenderSize{800, 600}));
  EXPECT_EQ(scaled_render_size({3, 2}, 0.25f, 0), (RenderSize{1, 1}));
}

TEST(SceneConfig, WindDirectionIsOnlyADirection) {
  // 40000 overflowed the Q16.16 maths of the wind field; now it is normalised.
  const SceneDesc s = load_scene_text("[wind]\ndirection = [40000, 0, 30000]\n", "w.toml");
  EXPECT_FLOAT_EQ(s.wind.direction.x, 0.8f);
  EXPECT_FLOAT_EQ(s.wind.direction.z, 0.6f);
  EXPECT_EQ(error_of("[wind]\ndirection = [0, 1, 0]\n").key(), "wind.direction");
}

TEST(SceneConfig, ElementCountIsBounded) {
  std::string many;
  for (int i = 0; i < 65; ++i) many += "[[element]]\nkind = \"test_pattern\"\n";
  const auto e = error_of(many);
  EXPECT_EQ(e.key(), "element");
  EXPECT_NE(e.expected().find("at most 64"), std::string::npos) << e.what();
}

TEST(SceneConfig, LongBadValuesAreNotEchoedWhole) {
  const auto e = error_of("[background]\ncolor = \"" + std::string(10 << 20, 'x') + "\"\n");
  EXPECT_EQ(e.key(), "background.color");
  EXPECT_LT(std::string(e.what()).size(), 300u) << std::string(e.what()).substr(0, 300);
  EXPECT_NE(e.expected().find("10485760 characters"), std::string::npos);
  // Nor a long unknown key, or a long element kind.
  const auto k = error_of("[camera]\n" + std::string(100000, 'k') + " = 1\n");
  EXPECT_LT(std::string(k.what()).size(), 300u);
  const auto kind = error_of("[[element]]\nkind = \"" + std::string(100000, 'q') + "\"\n");
  EXPECT_EQ(kind.key(), "element[0].kind");
  EXPECT_LT(std::string(kind.what()).size(), 300u);
}

TEST(SceneConfig, AnEmptySceneIsAProblem) {
  const SceneDesc s = load_scene_text("seed = 2\n", "empty.toml");
  const auto p = scene_problems(s);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].rfind("empty.toml: element: the scene has no [[element]]", 0), 0u) << p[0];
  EXPECT_TRUE(scene_problems(load_builtin_scene("default")).empty());
}

// Issue 15 (6): a SIGTERM while the scene is built stops the building.
TEST(SceneConfig, BuildingStopsWhenAskedTo) {
  const SceneDesc s = load_scene_text(
      "[[element]]\nkind = \"test_pattern\"\n[[element]]\nkind = \"test_pattern\"\n", "two.toml");
  std::atomic<bool> stop{true};
  Scene scene(s, 0, &stop);  // elements need GL to be made; none is attempted
  EXPECT_EQ(scene.element_count(), 0u);
  EXPECT_EQ(scene.failed_elements(), 0u);
}

TEST(SceneConfig, EveryBuiltInSceneIsValid) {
  for (const char* name : {"default", "test-pattern"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(load_builtin_scene(name));
  }
  EXPECT_THROW(load_builtin_scene("nope"), ConfigError);
}

}  // namespace
}  // namespace candela
