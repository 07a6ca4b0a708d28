#pragma once
// Where the frame graph's textures and buffers come from (DESIGN.md:
// transient targets are pooled). A texture released by one pass is handed
// to the next pass or eye that asks for the same size and format, in the
// same frame or a later one. Whatever no pass used for kIdleFramesKept
// frames in a row is freed, so memory follows what recent frames need and a
// viewport alternating mono and stereo (or a shot cut between two cameras)
// does not reallocate each frame. Buffers come in size classes (eight per
// octave), so a buffer whose size drifts a little from frame to frame (the
// A-buffer's node pool) is reused instead of remade.
//
// The pool is also the registry of what the renderer holds on the GPU: every
// texture and buffer it made, with its byte size and the name of the
// resource that last used it. Tests and `render --stats` read the registry,
// not counters the passes keep about themselves.
#include <cstddef>
#include <cstdint>
#include <functional>
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
  int depth = 1;               // > 1: a 3D texture (a grading LUT, a volume); last, as code fills the rest in order

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

// The bytes a buffer of `bytes` is made with: the next of eight steps per
// octave (at most 12.5% more), at least 256.
size_t bufferSizeClass(size_t bytes);

// Sampler state, separate from the texture (one texture read filtered and
// unfiltered, a shadow map compared and raw).
struct SamplerDesc {
  GLenum minFilter = GL_LINEAR;
  GLenum magFilter = GL_LINEAR;
  GLenum wrap = GL_CLAMP_TO_EDGE;  // S, T and R
  GLenum compareFunc = GL_NONE;    // GL_NONE: no depth comparison
  float maxAnisotropy = 1.0f;
  auto operator<=>(const SamplerDesc&) const = default;
};

// Bytes per texel of a sized format (0 for one this file does not know).
size_t bytesPerTexel(GLenum format);

struct PoolAllocation {
  std::string name;       // the resource that last used it ("hdr_color[left]")
  bool texture = true;    // else a buffer
  size_t bytes = 0;
  bool inUse = false;     // acquired and not yet released
  bool persistent = false;  // held across frames by its owner (shadow atlas, environment maps)
  int idleFrames = 0;     // frames since a pass last used it (kept up to kIdleFramesKept)
  // Every resource it served in the frame it was last used in, in order
  // (pooled memory is shared: light_cull_stats, then oit_counters).
  std::vector<std::string> users{};
};

class ResourcePool {
 public:
  static constexpr int kIdleFramesKept = 3;

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

  // A persistent resource of the frame graph, found by `key`: made when
  // missing or when `desc` differs (then *fresh is set), freed by endFrame
  // after `lifetimeFrames` frames that did not ask for it.
  GLuint namedTexture(const std::string& key, const TextureDesc& desc, int lifetimeFrames, bool* fresh);
  GLuint namedBuffer(const std::string& key, const BufferDesc& desc, int lifetimeFrames, bool* fresh);

  // A framebuffer with these attachments (mip `level`; `layer` >= 0
  // attaches one layer of an array texture), made once and kept while its
  // textures live.
  GLuint framebuffer(const std::vector<GLuint>& colors, GLuint depth, int layer = -1, int level = 0);
  // A sampler object with this state, made once.
  GLuint sampler(const SamplerDesc& desc);

  // Readback behind a fence (FrameGraph::readback): the copy of `bytes`
  // from `buffer` at `offset` is queued now; `deliver` runs from
  // pollReadbacks once the GPU has finished it.
  void queueReadback(GLuint buffer, size_t offset, size_t bytes,
                     std::function<void(const void*, size_t)> deliver);
  // Delivers the readbacks whose fence has signalled (all of them, waiting,
  // with `wait`). Returns how many it delivered.
  size_t pollReadbacks(bool wait = false);
  size_t pendingReadbacks() const { return readbacks_.size(); }

  // A frame's end: what no pass used for kIdleFramesKept frames in a row is
  // freed (and a named resource past its lifetime).
  void endFrame();
  void clear();
  ~ResourcePool();
  // GL textures and buffers made since the pool began (tests: reuse means
  // this does not grow).
  size_t allocationsMade() const { return allocationsMade_; }

  std::vector<PoolAllocation> registry() const;
  size_t bytes() const;
  // Bytes of pooled targets no pass used in the last frame (kept for reuse).
  size_t idleBytes() const;
  // Texture descriptions by id, for passes that need the size of an import.
  const TextureDesc* describe(GLuint texture) const;

 private:
  struct TextureEntry {
    gl::Texture texture;
    TextureDesc desc;
    std::string name;
    bool inUse = false, usedThisFrame = false, persistent = false;
    int idleFrames = 0;
    std::string key;        // a named (frame-graph persistent) resource
    int lifetimeFrames = 0;
    std::vector<std::string> users;  // this frame's (or the last used one's)
    uint64_t usersFrame = 0;
  };
  struct BufferEntry {
    gl::Buffer buffer;
    BufferDesc desc;        // as asked
    size_t classBytes = 0;  // as made (bufferSizeClass)
    std::string name;
    bool inUse = false, usedThisFrame = false, persistent = false;
    int idleFrames = 0;
    std::string key;
    int lifetimeFrames = 0;
    std::vector<std::string> users;
    uint64_t usersFrame = 0;
  };
  struct FramebufferKey {
    std::vector<GLuint> colors;
    GLuint depth = 0;
    int layer = -1;
    int level = 0;
    auto operator<=>(const FramebufferKey&) const = default;
  };
  struct Readback {
    gl::Buffer staging;
    GLsync fence = nullptr;
    size_t bytes = 0;
    std::function<void(const void*, size_t)> deliver;
  };
  void dropFramebuffersOf(GLuint texture);
  void noteUser(std::vector<std::string>& users, uint64_t& usersFrame, const std::string& name) const;
  GLuint makeTexture(const TextureDesc& desc, const std::string& name);
  GLuint makeBuffer(const BufferDesc& desc, const std::string& name);

  std::map<GLuint, TextureEntry> textures_;
  std::map<GLuint, BufferEntry> buffers_;
  std::map<FramebufferKey, gl::Framebuffer> framebuffers_;
  std::map<SamplerDesc, gl::Sampler> samplers_;
  std::vector<Readback> readbacks_;
  size_t allocationsMade_ = 0;
  uint64_t frame_ = 1;  // endFrame counts
};

}  // namespace hs::render
