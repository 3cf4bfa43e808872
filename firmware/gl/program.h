// A linked GLSL ES program built from the shaders embedded from gles_shaders/.
// A compile error names the source file and line, like a C compiler would.
#pragma once

#include <string>
#include <string_view>

#include "gl/gles.h"

namespace candela {

class Program {
 public:
  Program() = default;
  // Throws RuntimeError("gles_shaders/x.frag:12: error: ...") on failure.
  static Program from_library(std::string_view vert_name, std::string_view frag_name);
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
