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
  EXPECT_NO_THROW(Program::from_library("test_pattern.vert", "test_pattern.frag"));
  EXPECT_THROW(Program::from_library("fullscreen.vert", "missing.frag"), RuntimeError);
}

// A stage put together from several files (compose_shader: "#line" with each file's offset
// before each) names the file and line the error is in.
TEST(ShaderErrors, ComposedStageNamesTheFileOfTheError) {
  DisplayOptions o;
  o.kind = "headless";
  o.width = o.height = 16;
  auto display = open_display(o);
  const char* vs = "#version 300 es\nvoid main() { gl_Position = vec4(0.0); }\n";
  const std::string fs =
      "#version 300 es\n#define X 1\n#line 2\nprecision mediump float;\nfloat f() { return 1.0; "
      "}\n#line 100002\nout vec4 c;\nvoid main() {\n  c = vec4(nope);\n}\n";
  try {
    Program::from_source("ok.vert", vs, "lib.frag + main.frag", fs);
    FAIL() << "compiled a broken shader";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("gles_shaders/main.frag:4:"), std::string::npos)
        << e.what();
  }
  // The library's files are put together that way, each keeping its line numbers.
  const std::string src =
      compose_shader({"fire_ramp.frag", "perlinfire_composite.frag"}, "#define PF_SHADING 1\n");
  EXPECT_EQ(src.rfind("#version 300 es\n#define PF_SHADING 1\n#line 2\n", 0), 0u);
  EXPECT_NE(src.find("\n#line 100002\n"), std::string::npos);
  EXPECT_NO_THROW(Program::from_library("fullscreen.vert",
                                        {"fire_ramp.frag", "perlinfire_composite.frag"},
                                        "#define PF_SHADING 1\nprecision highp float;\n"));
  EXPECT_THROW(compose_shader({"missing.frag"}), RuntimeError);
}

}  // namespace
}  // namespace candela
