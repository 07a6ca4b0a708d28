#pragma once
// Where the frame graph's textures and buffers come from (DESIGN.md:
// transient targets are pooled). A texture released by one pass is handed
// to the next pass or eye that asks for the same size and format, in the
// same frame or the next one; whatever no pass of a frame used is freed at
// the end of that frame, so memory follows what the current frame needs.
//
// The pool is also the registry of what the renderer holds on the GPU: every
// texture and buffer it made, with its byte size and the name of the
// resource that last used it. Tests and `render --stats` read the registry,
// not counters the passes keep about themselves.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "render/gl/gl_handle.h"

namespace hs::render {

struct TextureDesc {
  int width = 0;
  int height = 0;
  GLenum format = GL_RGBA16F;  // a sized internal format
  int samples = 1;             // > 1: multisampled
  int layers = 1;              // > 1: a 2D array (cascades, eyes, layers)
  int levels = 1;              // mipmap levels
  bool cube = false;           // a cube map (layers counts cube faces x 6 for arrays)
  bool array = false;          // a 2D array even with one layer (shaders sample it as one: one shadow cascade)

  GLenum target() const;
  size_t bytes() const;
  bool operator==(const TextureDesc&) const = default;
  auto operator<=>(const TextureDesc&) const = default;
};

struct BufferDesc {
  size_t bytes = 0;
  bool operator==(const BufferDesc&) const = default;
  auto operator<=>(const BufferDesc&) const = default;
};

// Bytes per texel of a sized format (0 for one this file does not know).
size_t bytesPerTexel(GLenum format);

struct PoolAllocation {
  std::string name;       // the resource that last used it ("hdr_color[left]")
  bool texture = true;    // else a buffer
  size_t bytes = 0;
  bool inUse = false;     // acquired and not yet released
  bool persistent = false;  // held across frames by its owner (shadow atlas, environment maps)
};

class ResourcePool {
 public:
  ResourcePool() = default;
  ResourcePool(const ResourcePool&) = delete;
  ResourcePool& operator=(const ResourcePool&) = delete;

  // A texture of `desc`, reused if a free one exists. Linear filtering and
  // clamp to edge are set on new textures; passes set what else they need.
  GLuint acquireTexture(const TextureDesc& desc, const std::string& name);
  void releaseTexture(GLuint texture);
  GLuint acquireBuffer(const BufferDesc& desc, const std::string& name);
  void releaseBuffer(GLuint buffer);
  // A texture or buffer its owner keeps across frames (released with
  // releaseTexture/releaseBuffer when the owner no longer needs it). Listed
  // in the registry as persistent.
  GLuint persistentTexture(const TextureDesc& desc, const std::string& name);
  GLuint persistentBuffer(const BufferDesc& desc, const std::string& name);

  // A framebuffer with these attachments (level 0; `layer` >= 0 attaches one
  // layer of an array texture), made once and kept while its textures live.
  GLuint framebuffer(const std::vector<GLuint>& colors, GLuint depth, int layer = -1);

  // Frees what no pass used since the last call (a frame's end).
  void endFrame();
  void clear();

  std::vector<PoolAllocation> registry() const;
  size_t bytes() const;
  // Texture descriptions by id, for passes that need the size of an import.
  const TextureDesc* describe(GLuint texture) const;

 private:
  struct TextureEntry {
    gl::Texture texture;
    TextureDesc desc;
    std::string name;
    bool inUse = false, usedThisFrame = false, persistent = false;
  };
  struct BufferEntry {
    gl::Buffer buffer;
    BufferDesc desc;
    std::string name;
    bool inUse = false, usedThisFrame = false, persistent = false;
  };
  struct FramebufferKey {
    std::vector<GLuint> colors;
    GLuint depth = 0;
    int layer = -1;
    auto operator<=>(const FramebufferKey&) const = default;
  };
  void dropFramebuffersOf(GLuint texture);

  std::map<GLuint, TextureEntry> textures_;
  std::map<GLuint, BufferEntry> buffers_;
  std::map<FramebufferKey, gl::Framebuffer> framebuffers_;
};

}  // namespace hs::render
