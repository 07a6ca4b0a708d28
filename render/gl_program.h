#pragma once
// A linked GLSL program (render/gl/shader_library.h builds and keeps them),
// with uniform locations looked up once. Per-frame and per-view values
// reach shaders through uniform buffers (render/frame_blocks.h); the
// setters here are for values of one pass or one draw. Include only inside
// render/.
#include <string>
#include <string_view>
#include <unordered_map>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace hs::render {

namespace gl {
struct ProgramDesc;
}

// The embedded text of shaders/<name>; empty if there is no such file.
std::string_view embeddedShader(std::string_view name);

class GlProgram {
 public:
  GlProgram() = default;
  ~GlProgram() { release(); }
  void release();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  // Compiles and links the stages `desc` names (vertex + fragment, or
  // compute). False with the compiler's log, naming files and lines.
  bool build(const gl::ProgramDesc& desc, std::string& error);
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
  void set(const char* name, const glm::ivec2& v) { glProgramUniform2i(id_, loc(name), v.x, v.y); }
  void set(const char* name, const glm::mat3& m) { glProgramUniformMatrix3fv(id_, loc(name), 1, GL_FALSE, &m[0][0]); }
  void set(const char* name, const glm::mat4& m) { glProgramUniformMatrix4fv(id_, loc(name), 1, GL_FALSE, &m[0][0]); }

 private:
  GLuint id_ = 0;
  std::unordered_map<std::string, GLint> locations_;
};

}  // namespace hs::render
