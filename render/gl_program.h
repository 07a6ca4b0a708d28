#pragma once
// A linked GLSL program built from the embedded shader sources (shaders/),
// with uniform locations looked up once. Include only inside render/.
#include <string>
#include <string_view>
#include <unordered_map>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace hs::render {

// The embedded text of shaders/<name>; empty if there is no such file.
std::string_view embeddedShader(std::string_view name);

class GlProgram {
 public:
  GlProgram() = default;
  // No GL in the destructor (the context may be gone): call release().
  void release();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  // Compiles shaders/<vert> and shaders/<frag> (common.glsl is inserted after
  // the #version line of the fragment shader). False with a log that names
  // the file and line on failure.
  bool build(std::string_view vert, std::string_view frag, std::string& error);
  void use() const { glUseProgram(id_); }
  GLuint id() const { return id_; }

  GLint loc(const char* name);
  void set(const char* name, int v) { glProgramUniform1i(id_, loc(name), v); }
  void set(const char* name, unsigned v) { glProgramUniform1ui(id_, loc(name), v); }
  void set(const char* name, bool v) { glProgramUniform1i(id_, loc(name), v ? 1 : 0); }
  void set(const char* name, float v) { glProgramUniform1f(id_, loc(name), v); }
  void set(const char* name, const glm::vec2& v) { glProgramUniform2f(id_, loc(name), v.x, v.y); }
  void set(const char* name, const glm::vec3& v) { glProgramUniform3f(id_, loc(name), v.x, v.y, v.z); }
  void set(const char* name, const glm::vec4& v) { glProgramUniform4f(id_, loc(name), v.x, v.y, v.z, v.w); }
  void set(const char* name, const glm::mat3& m) { glProgramUniformMatrix3fv(id_, loc(name), 1, GL_FALSE, &m[0][0]); }
  void set(const char* name, const glm::mat4& m) { glProgramUniformMatrix4fv(id_, loc(name), 1, GL_FALSE, &m[0][0]); }

 private:
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace hs::render
