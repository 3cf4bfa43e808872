// A linked GLSL ES program built from the shaders embedded from gles_shaders/.
// A compile error names the source file and line, like a C compiler would.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "gl/gles.h"

namespace candela {

// A shader from the embedded library (gles_shaders/NAME); throws
// RuntimeError("gles_shaders/NAME: not built in") if there is none.
std::string_view library_shader(std::string_view name);

// One stage's source put together from library shaders: "#version 300 es",
// then `defines` (any lines: "#define X 1\n", a precision statement), then
// each file in order without its own #version line. A "#line" before each
// file numbers its lines as in the file, plus 100000 times its place in
// `files`, so a compile error (Program) names the right file and line.
std::string compose_shader(std::initializer_list<std::string_view> files,
                           std::string_view defines = {});

class Program {
 public:
  Program() = default;
  // Both stages from the library, `defines` put into each after its #version
  // line (as compose_shader). Throws RuntimeError("gles_shaders/x.frag:12:
  // error: ...") on failure.
  static Program from_library(std::string_view vert_name, std::string_view frag_name,
                              std::string_view defines = {});
  // As above with a fragment stage made of several library files, in order
  // (a shared library of functions first, the file with main() last).
  static Program from_library(std::string_view vert_name,
                              std::initializer_list<std::string_view> frag_names,
                              std::string_view defines = {});
  static Program from_source(std::string_view vert_name, std::string_view vert_src,
                             std::string_view frag_name, std::string_view frag_src);
  Program(Program&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  ~Program();

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  // Looked up once at set-up; returns -1 for a uniform the compiler removed.
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }

 private:
  explicit Program(GLuint id) : id_(id) {}
  GLuint id_ = 0;
};

// Rewrites a driver's info log ("0:12(5): error: x") into "file:12:5: error: x".
std::string annotate_shader_log(std::string_view file, std::string_view log);

}  // namespace candela
