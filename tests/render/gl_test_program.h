#pragma once
// A GL program from sources a test writes itself (probes, busy shaders), for
// checks that must not go through the renderer's own shader library: 0 on
// failure, with the compiler's or linker's log in `log`.
#include <string>
#include <utility>
#include <vector>

#include <epoxy/gl.h>

namespace hs::test {

inline GLuint linkProgram(const std::vector<std::pair<GLenum, std::string>>& stages, std::string* log = nullptr) {
  const GLuint p = glCreateProgram();
  for (const auto& [type, src] : stages) {
    const GLuint sh = glCreateShader(type);
    const char* c = src.c_str();
    glShaderSource(sh, 1, &c, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok && log) {
      char text[4096] = {};
      glGetShaderInfoLog(sh, sizeof text, nullptr, text);
      *log += text;
    }
    glAttachShader(p, sh);
    glDeleteShader(sh);
  }
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok) return p;
  if (log) {
    char text[4096] = {};
    glGetProgramInfoLog(p, sizeof text, nullptr, text);
    *log += text;
  }
  glDeleteProgram(p);
  return 0;
}

// The full-screen triangle's vertex shader (as shaders/fullscreen.vert draws it).
inline const char* kFullscreenTriangleVs =
    "#version 450 core\n"
    "void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0); }\n";

}  // namespace hs::test
