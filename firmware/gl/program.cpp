#include "gl/program.h"

#include <regex>
#include <string>

#include "core/error.h"

namespace candela::shaders {
std::string_view find(std::string_view name);
}

namespace candela {
namespace {

GLuint compile(GLenum type, std::string_view name, std::string_view src) {
  const GLuint s = glCreateShader(type);
  const char* p = src.data();
  const auto len = static_cast<GLint>(src.size());
  glShaderSource(s, 1, &p, &len);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &n);
    std::string log(static_cast<size_t>(n > 0 ? n : 1), '\0');
    glGetShaderInfoLog(s, n, nullptr, log.data());
    glDeleteShader(s);
    throw RuntimeError(annotate_shader_log(std::string("gles_shaders/") + std::string(name), log));
  }
  return s;
}

}  // namespace

std::string annotate_shader_log(std::string_view file, std::string_view log) {
  // Mesa: "0:12(5): error: ..."; others: "ERROR: 0:12: ...".
  static const std::regex mesa(R"(^\s*\d+:(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex generic(R"(^\s*(ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$)");
  std::string out;
  size_t start = 0;
  const std::string text(log.substr(0, log.find('\0')));
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    std::smatch m;
    if (std::regex_match(line, m, mesa)) {
      out += std::string(file) + ":" + m[1].str() + ":" + m[2].str() + ": " + m[3].str() + "\n";
    } else if (std::regex_match(line, m, generic)) {
      out += std::string(file) + ":" + m[2].str() + ": " + m[1].str() + ": " + m[3].str() + "\n";
    } else if (!line.empty()) {
      out += std::string(file) + ": " + line + "\n";
    }
    start = end + 1;
  }
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out.empty() ? std::string(file) + ": shader failed to compile (no log)" : out;
}

Program Program::from_library(std::string_view vert_name, std::string_view frag_name) {
  const auto vs = shaders::find(vert_name);
  const auto fs = shaders::find(frag_name);
  if (vs.empty()) throw RuntimeError("gles_shaders/" + std::string(vert_name) + ": not built in");
  if (fs.empty()) throw RuntimeError("gles_shaders/" + std::string(frag_name) + ": not built in");
  return from_source(vert_name, vs, frag_name, fs);
}

Program Program::from_source(std::string_view vert_name, std::string_view vert_src,
                             std::string_view frag_name, std::string_view frag_src) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vert_name, vert_src);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, frag_name, frag_src);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint p = glCreateProgram();
  glAttachShader(p, vs);
  glAttachShader(p, fs);
  glLinkProgram(p);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &n);
    std::string log(static_cast<size_t>(n > 0 ? n : 1), '\0');
    glGetProgramInfoLog(p, n, nullptr, log.data());
    glDeleteProgram(p);
    throw RuntimeError("gles_shaders/" + std::string(vert_name) + " + " + std::string(frag_name) +
                       ": link failed: " + log.c_str());
  }
  return Program(p);
}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

}  // namespace candela
