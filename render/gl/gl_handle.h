#pragma once
// Owning handles for OpenGL objects: one type per kind, move-only, deleting
// their object when they go. Every GL object of the renderer lives in one.
//
// GL objects belong to a context. The renderer's owners destroy it with its
// context current (Renderer::shutdown, the two backends do). A handle that
// dies without a current context deletes nothing harmful: with GLVND (what
// Debian's Mesa and NVIDIA drivers use) a GL call without a current context
// goes to a no-op dispatch table, so the worst case is a name that leaks
// with its context, which frees it anyway.
#include <utility>

#include <epoxy/gl.h>

namespace hs::render::gl {

template <class Traits>
class Handle {
 public:
  Handle() = default;
  explicit Handle(GLuint id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) Traits::destroy(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

struct BufferTraits {
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
  static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct VertexArrayTraits {
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct SamplerTraits {
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
struct ProgramTraits {
  static void destroy(GLuint id) { glDeleteProgram(id); }
};

using Buffer = Handle<BufferTraits>;
using Texture = Handle<TextureTraits>;
using Framebuffer = Handle<FramebufferTraits>;
using Renderbuffer = Handle<RenderbufferTraits>;
using VertexArray = Handle<VertexArrayTraits>;
using Query = Handle<QueryTraits>;
using Sampler = Handle<SamplerTraits>;
using ProgramObject = Handle<ProgramTraits>;

// Creation in one line (DSA: the objects exist at once).
inline Buffer createBuffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return Buffer(id);
}
inline Texture createTexture(GLenum target) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  return Texture(id);
}
inline Framebuffer createFramebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return Framebuffer(id);
}
inline Renderbuffer createRenderbuffer() {
  GLuint id = 0;
  glCreateRenderbuffers(1, &id);
  return Renderbuffer(id);
}
inline VertexArray createVertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArray(id);
}
inline Query createQuery(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return Query(id);
}
inline Sampler createSampler() {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  return Sampler(id);
}

}  // namespace hs::render::gl
