// A shader that fails to compile is reported as file:line, like a compiler.
#include <gtest/gtest.h>

#include "core/error.h"
#include "display/display.h"
#include "gl/program.h"

namespace candela {
namespace {

TEST(ShaderErrors, MesaLogIsRewrittenToFileAndLine) {
  const std::string out = annotate_shader_log(
      "gles_shaders/x.frag", "0:12(5): error: `foo' undeclared\n0:14(1): warning: bar\n");
  EXPECT_EQ(
      out,
      "gles_shaders/x.frag:12:5: error: `foo' undeclared\ngles_shaders/x.frag:14:1: warning: bar");
}

TEST(ShaderErrors, RealCompileErrorNamesFileAndLine) {
  DisplayOptions o;
  o.kind = "headless";
  o.width = o.height = 16;
  auto display = open_display(o);
  const char* vs = "#version 300 es\nvoid main() { gl_Position = vec4(0.0); }\n";
  const char* fs =
      "#version 300 es\nprecision mediump float;\nout vec4 c;\nvoid main() {\n  c = nope;\n}\n";
  try {
    Program::from_source("ok.vert", vs, "broken.frag", fs);
    FAIL() << "compiled a broken shader";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("gles_shaders/broken.frag:5:"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(Program::from_library("fullscreen.vert", "test_pattern.frag"));
  EXPECT_THROW(Program::from_library("fullscreen.vert", "missing.frag"), RuntimeError);
}

}  // namespace
}  // namespace candela
