#include "render/gl_program.h"

#include <vector>

namespace hs::render {
namespace {

// Splices common.glsl in after the #version line.
std::string withCommon(std::string_view src) {
  const std::string_view common = embeddedShader("common.glsl");
  const size_t eol = src.find('\n');
  if (eol == std::string_view::npos) return std::string(src);
  std::string out(src.substr(0, eol + 1));
  out += common;
  // Keep error line numbers pointing at the original file.
  out += "\n#line 2\n";
  out += src.substr(eol + 1);
  return out;
}

GLuint compile(GLenum type, std::string_view name, std::string& error) {
  const std::string_view raw = embeddedShader(name);
  if (raw.empty()) {
    error = "shader source shaders/" + std::string(name) + " is not in this build";
    return 0;
  }
  const std::string src = type == GL_FRAGMENT_SHADER ? withCommon(raw) : std::string(raw);
  const GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(size_t(std::max(len, 1)));
    glGetShaderInfoLog(s, len, nullptr, log.data());
    error = "shaders/" + std::string(name) + ": " + log.data();
    glDeleteShader(s);
    return 0;
  }
  return s;
}

}  // namespace

void GlProgram::release() {
  if (id_) glDeleteProgram(id_);
  id_ = 0;
  locations_.clear();
}

bool GlProgram::build(std::string_view vert, std::string_view frag, std::string& error) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vert, error);
  if (!vs) return false;
  const GLuint fs = compile(GL_FRAGMENT_SHADER, frag, error);
  if (!fs) {
    glDeleteShader(vs);
    return false;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::vector<char> log(size_t(std::max(len, 1)));
    glGetProgramInfoLog(id_, len, nullptr, log.data());
    error = "linking " + std::string(vert) + " + " + std::string(frag) + ": " + log.data();
    glDeleteProgram(id_);
    id_ = 0;
    return false;
  }
  return true;
}

GLint GlProgram::loc(const char* name) {
  auto it = locations_.find(name);
  if (it == locations_.end()) it = locations_.emplace(name, glGetUniformLocation(id_, name)).first;
  return it->second;
}

}  // namespace hs::render
