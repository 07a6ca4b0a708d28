#include "render/gl_program.h"

#include <vector>

#include "render/gl/shader_library.h"

namespace hs::render {
namespace {

std::string infoLog(GLuint object, bool program) {
  GLint len = 0;
  if (program) glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
  else glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
  std::vector<char> log(size_t(std::max(len, 1)), '\0');
  if (program) glGetProgramInfoLog(object, len, nullptr, log.data());
  else glGetShaderInfoLog(object, len, nullptr, log.data());
  return log.data();
}

GLuint compile(GLenum type, const std::string& file, const std::vector<std::string>& defines, std::string& error,
               std::string_view generated = {}) {
  std::string src;
  std::vector<std::string> files;
  if (!gl::preprocessShader(file, defines, src, files, error, generated)) return 0;
  const GLuint s = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(s, 1, &p, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    // Messages say "N:line(col)": N is the source number of #line.
    std::string legend;
    for (size_t i = 0; i < files.size(); ++i) legend += (i ? ", " : "") + std::to_string(i) + " = shaders/" + files[i];
    error = "shaders/" + file + " (sources " + legend + "): " + infoLog(s, false);
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

bool GlProgram::build(const gl::ProgramDesc& desc, std::string& error) {
  release();
  std::vector<GLuint> stages;
  auto add = [&](GLenum type, const std::string& file) {
    if (file.empty()) return true;
    const GLuint s = compile(type, file, desc.defines, error,
                             type == GL_VERTEX_SHADER ? std::string_view() : std::string_view(desc.generated));
    if (!s) return false;
    stages.push_back(s);
    return true;
  };
  const bool compiled = desc.compute.empty()
                            ? add(GL_VERTEX_SHADER, desc.vertex) && add(GL_FRAGMENT_SHADER, desc.fragment)
                            : add(GL_COMPUTE_SHADER, desc.compute);
  if (!compiled) {
    for (GLuint s : stages) glDeleteShader(s);
    return false;
  }
  id_ = glCreateProgram();
  for (GLuint s : stages) glAttachShader(id_, s);
  glLinkProgram(id_);
  for (GLuint s : stages) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    error = "linking " + desc.name() + ": " + infoLog(id_, true);
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
