// Scene files: every kind of bad input gets a message naming the file, the
// key and what was expected.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/scene_file.h"

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

TEST(SceneConfig, EveryBuiltInSceneIsValid) {
  for (const char* name : {"default", "test-pattern"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW(load_builtin_scene(name));
  }
  EXPECT_THROW(load_builtin_scene("nope"), ConfigError);
}

}  // namespace
}  // namespace candela
