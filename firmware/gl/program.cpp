#include "gl/program.h"

#include <regex>
#include <string>
#include <vector>

#include "core/error.h"
#include "embedded_shaders.h"

namespace candela {
namespace {

// "a.frag + b.frag" -> {"gles_shaders/a.frag", "gles_shaders/b.frag"}: the
// files of a composed stage, by source-string number (compose_shader).
std::vector<std::string> files_of(std::string_view name) {
  std::vector<std::string> out;
  size_t at = 0;
  while (true) {
    const size_t plus = name.find(" + ", at);
    out.push_back("gles_shaders/" + std::string(name.substr(at, plus - at)));
    if (plus == std::string_view::npos) break;
    at = plus + 3;
  }
  return out;
}

std::string_view drop_version_line(std::string_view src) {
  if (!src.starts_with("#version")) return src;
  const auto nl = src.find('\n');
  return nl == std::string_view::npos ? std::string_view{} : src.substr(nl + 1);
}

std::string joined_names(std::initializer_list<std::string_view> files) {
  std::string name;
  for (const auto f : files) name += (name.empty() ? "" : " + ") + std::string(f);
  return name;
}

// compose_shader numbers file i's lines from i * kLinesPerFile, so a line
// number names its file (drivers do not all report #line's source number).
constexpr long kLinesPerFile = 100000;

std::string annotate(const std::vector<std::string>& files, std::string_view log) {
  // Mesa: "0:12(5): error: ..."; others: "ERROR: 0:12: ...".
  static const std::regex mesa(R"(^\s*\d+:(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex generic(R"(^\s*(ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$)");
  // "file:line" of a reported line number.
  const auto where = [&](const std::string& n) {
    const long line = std::stol(n);
    const size_t i = static_cast<size_t>(line / kLinesPerFile);
    return (i < files.size() ? files[i] : files.front()) + ":" +
           std::to_string(i < files.size() ? line % kLinesPerFile : line);
  };
  std::string out;
  size_t start = 0;
  const std::string text(log.substr(0, log.find('\0')));
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    std::smatch m;
    if (std::regex_match(line, m, mesa)) {
      out += where(m[1].str()) + ":" + m[2].str() + ": " + m[3].str() + "\n";
    } else if (std::regex_match(line, m, generic)) {
      out += where(m[2].str()) + ": " + m[1].str() + ": " + m[3].str() + "\n";
    } else if (!line.empty()) {
      out += files.front() + ": " + line + "\n";
    }
    start = end + 1;
  }
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out.empty() ? files.front() + ": shader failed to compile (no log)" : out;
}

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
    throw RuntimeError(annotate(files_of(name), log));
  }
  return s;
}

}  // namespace

std::string annotate_shader_log(std::string_view file, std::string_view log) {
  return annotate({std::string(file)}, log);
}

std::string_view library_shader(std::string_view name) {
  const auto s = shaders::find(name);
  if (s.empty()) throw RuntimeError("gles_shaders/" + std::string(name) + ": not built in");
  return s;
}

std::string compose_shader(std::initializer_list<std::string_view> files,
                           std::string_view defines) {
  std::string src = "#version 300 es\n";
  src += defines;
  if (!src.ends_with('\n')) src += '\n';
  int index = 0;
  for (const auto f : files) {
    const std::string_view text = library_shader(f);
    // The file's second line (after its #version) is its line 2 (plus the
    // file's offset: annotate() reads the file back from the line number).
    src += "#line " +
           std::to_string(index++ * kLinesPerFile + (text.starts_with("#version") ? 2 : 1)) + "\n";
    src += drop_version_line(text);
    if (!src.ends_with('\n')) src += '\n';
  }
  return src;
}

Program Program::from_library(std::string_view vert_name, std::string_view frag_name,
                              std::string_view defines) {
  return from_library(vert_name, {frag_name}, defines);
}

Program Program::from_library(std::string_view vert_name,
                              std::initializer_list<std::string_view> frag_names,
                              std::string_view defines) {
  if (defines.empty() && frag_names.size() == 1)  // the files exactly as written
    return from_source(vert_name, library_shader(vert_name), *frag_names.begin(),
                       library_shader(*frag_names.begin()));
  return from_source(vert_name, compose_shader({vert_name}, defines), joined_names(frag_names),
                     compose_shader(frag_names, defines));
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
