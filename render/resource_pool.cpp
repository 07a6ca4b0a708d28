#include "render/resource_pool.h"

#include <algorithm>

namespace hs::render {

GLenum TextureDesc::target() const {
  if (depth > 1) return GL_TEXTURE_3D;
  if (cube) return layers > 1 ? GL_TEXTURE_CUBE_MAP_ARRAY : GL_TEXTURE_CUBE_MAP;
  if (samples > 1) return layers > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_MULTISAMPLE;
  return layers > 1 || array ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
}

size_t bytesPerTexel(GLenum format) {
  switch (format) {
    case GL_R8: case GL_R8UI: return 1;
    case GL_RG8: case GL_R16F: case GL_R16: case GL_DEPTH_COMPONENT16: return 2;
    case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_R32UI: case GL_R32I: case GL_RG16F:
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_DEPTH_COMPONENT24: case GL_R11F_G11F_B10F:
    case GL_RGB10_A2: return 4;
    case GL_RGBA16F: case GL_RGBA16: case GL_RG32F: case GL_RG32UI: return 8;
    case GL_RGB32F: return 12;  // grading LUTs (color_lut.h)
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 0;
  }
}

size_t TextureDesc::bytes() const {
  size_t texels = 0;
  int w = width, h = height, d = std::max(depth, 1);
  for (int l = 0; l < std::max(levels, 1); ++l) {
    texels += size_t(std::max(w, 1)) * size_t(std::max(h, 1)) * size_t(std::max(d, 1));
    w /= 2;
    h /= 2;
    d /= 2;
  }
  return texels * bytesPerTexel(format) * size_t(std::max(samples, 1)) * size_t(std::max(layers, 1)) *
         (cube ? 6u : 1u);
}

size_t bufferSizeClass(size_t bytes) {
  if (bytes <= 256) return 256;
  // The octave [2^k, 2^(k+1)) in eight equal steps of 2^(k-3).
  int k = 0;
  while ((size_t(2) << k) <= bytes) ++k;  // 2^k <= bytes < 2^(k+1)
  const size_t step = size_t(1) << (k - 3);
  return (bytes + step - 1) / step * step;
}

void ResourcePool::noteUser(std::vector<std::string>& users, uint64_t& usersFrame, const std::string& name) const {
  if (usersFrame != frame_) {
    users.clear();
    usersFrame = frame_;
  }
  if (std::find(users.begin(), users.end(), name) == users.end()) users.push_back(name);
}

ResourcePool::~ResourcePool() {
  for (Readback& r : readbacks_)
    if (r.fence) glDeleteSync(r.fence);
}

GLuint ResourcePool::acquireTexture(const TextureDesc& desc, const std::string& name) {
  for (auto& [id, e] : textures_)
    if (!e.inUse && !e.persistent && e.desc == desc) {
      e.inUse = e.usedThisFrame = true;
      e.name = name;
      noteUser(e.users, e.usersFrame, name);
      return id;
    }
  return makeTexture(desc, name);
}

GLuint ResourcePool::makeTexture(const TextureDesc& desc, const std::string& name) {
  ++allocationsMade_;
  gl::Texture t = gl::createTexture(desc.target());
  const GLuint id = t.id();
  const int levels = std::max(desc.levels, 1);
  switch (desc.target()) {
    case GL_TEXTURE_2D_MULTISAMPLE:
      glTextureStorage2DMultisample(id, desc.samples, desc.format, desc.width, desc.height, GL_TRUE);
      break;
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY:
      glTextureStorage3DMultisample(id, desc.samples, desc.format, desc.width, desc.height, desc.layers, GL_TRUE);
      break;
    case GL_TEXTURE_2D_ARRAY:
      glTextureStorage3D(id, levels, desc.format, desc.width, desc.height, desc.layers);
      break;
    case GL_TEXTURE_CUBE_MAP_ARRAY:
      glTextureStorage3D(id, levels, desc.format, desc.width, desc.height, desc.layers * 6);
      break;
    case GL_TEXTURE_3D:
      glTextureStorage3D(id, levels, desc.format, desc.width, desc.height, desc.depth);
      break;
    default:  // 2D and cube maps
      glTextureStorage2D(id, levels, desc.format, desc.width, desc.height);
  }
  if (desc.samples <= 1) {
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  }
  TextureEntry e;
  e.texture = std::move(t);
  e.desc = desc;
  e.name = name;
  e.inUse = e.usedThisFrame = true;
  noteUser(e.users, e.usersFrame, name);
  textures_.emplace(id, std::move(e));
  return id;
}

void ResourcePool::releaseTexture(GLuint texture) {
  auto it = textures_.find(texture);
  if (it == textures_.end()) return;
  if (it->second.persistent) {
    dropFramebuffersOf(texture);
    textures_.erase(it);
    return;
  }
  it->second.inUse = false;
}

GLuint ResourcePool::persistentTexture(const TextureDesc& desc, const std::string& name) {
  // Made like a pooled one, then never handed to anyone else.
  TextureDesc d = desc;
  const GLuint id = acquireTexture(d, name);
  TextureEntry& e = textures_.at(id);
  e.persistent = true;
  return id;
}

GLuint ResourcePool::acquireBuffer(const BufferDesc& desc, const std::string& name) {
  const size_t cls = bufferSizeClass(desc.bytes);
  for (auto& [id, e] : buffers_)
    if (!e.inUse && !e.persistent && e.classBytes == cls) {
      e.inUse = e.usedThisFrame = true;
      e.name = name;
      e.desc = desc;
      noteUser(e.users, e.usersFrame, name);
      return id;
    }
  return makeBuffer(desc, name);
}

GLuint ResourcePool::makeBuffer(const BufferDesc& desc, const std::string& name) {
  ++allocationsMade_;
  gl::Buffer b = gl::createBuffer();
  const GLuint id = b.id();
  const size_t cls = bufferSizeClass(desc.bytes);
  glNamedBufferStorage(id, GLsizeiptr(cls), nullptr, GL_DYNAMIC_STORAGE_BIT);
  BufferEntry e;
  e.buffer = std::move(b);
  e.desc = desc;
  e.classBytes = cls;
  e.name = name;
  e.inUse = e.usedThisFrame = true;
  noteUser(e.users, e.usersFrame, name);
  buffers_.emplace(id, std::move(e));
  return id;
}

void ResourcePool::releaseBuffer(GLuint buffer) {
  auto it = buffers_.find(buffer);
  if (it == buffers_.end()) return;
  if (it->second.persistent) {
    buffers_.erase(it);
    return;
  }
  it->second.inUse = false;
}

GLuint ResourcePool::persistentBuffer(const BufferDesc& desc, const std::string& name) {
  const GLuint id = makeBuffer(desc, name);
  buffers_.at(id).persistent = true;
  return id;
}

namespace {
// The entry named `key` in `entries` if its description is still `desc`;
// else the old one dropped (drop(id)) and nothing found. Shared by named
// textures and buffers.
template <class Entries, class Desc, class Drop>
GLuint findNamed(Entries& entries, const std::string& key, const Desc& desc, int lifetimeFrames, Drop drop) {
  for (auto it = entries.begin(); it != entries.end(); ++it) {
    auto& e = it->second;
    if (e.key != key) continue;
    if (e.desc == desc) {
      e.usedThisFrame = true;
      e.lifetimeFrames = lifetimeFrames;
      return it->first;
    }
    drop(it->first);
    entries.erase(it);  // a new description: the caller makes it again
    break;
  }
  return 0;
}

template <class Entry>
void markNamed(Entry& e, const std::string& key, int lifetimeFrames) {
  e.persistent = true;
  e.inUse = false;
  e.key = key;
  e.lifetimeFrames = lifetimeFrames;
}
}  // namespace

GLuint ResourcePool::namedTexture(const std::string& key, const TextureDesc& desc, int lifetimeFrames, bool* fresh) {
  GLuint id = findNamed(textures_, key, desc, lifetimeFrames, [this](GLuint t) { dropFramebuffersOf(t); });
  if (fresh) *fresh = id == 0;
  if (id) return id;
  id = makeTexture(desc, key);
  markNamed(textures_.at(id), key, lifetimeFrames);
  return id;
}

GLuint ResourcePool::namedBuffer(const std::string& key, const BufferDesc& desc, int lifetimeFrames, bool* fresh) {
  GLuint id = findNamed(buffers_, key, desc, lifetimeFrames, [](GLuint) {});
  if (fresh) *fresh = id == 0;
  if (id) return id;
  id = makeBuffer(desc, key);
  markNamed(buffers_.at(id), key, lifetimeFrames);
  return id;
}

GLuint ResourcePool::sampler(const SamplerDesc& d) {
  if (auto it = samplers_.find(d); it != samplers_.end()) return it->second.id();
  GLuint id = 0;
  glCreateSamplers(1, &id);
  gl::Sampler s(id);
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(d.minFilter));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(d.magFilter));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GLint(d.wrap));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GLint(d.wrap));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_R, GLint(d.wrap));
  if (d.compareFunc != GL_NONE) {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, GLint(d.compareFunc));
  }
  if (d.maxAnisotropy > 1.0f) glSamplerParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, d.maxAnisotropy);
  samplers_.emplace(d, std::move(s));
  return id;
}

void ResourcePool::queueReadback(GLuint buffer, size_t offset, size_t bytes,
                                 std::function<void(const void*, size_t)> deliver) {
  Readback r;
  r.staging = gl::createBuffer();
  r.bytes = bytes;
  r.deliver = std::move(deliver);
  glNamedBufferStorage(r.staging.id(), GLsizeiptr(std::max<size_t>(bytes, 4)), nullptr,
                       GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
  if (bytes) glCopyNamedBufferSubData(buffer, r.staging.id(), GLintptr(offset), 0, GLsizeiptr(bytes));
  r.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  readbacks_.push_back(std::move(r));
}

size_t ResourcePool::pollReadbacks(bool wait) {
  size_t delivered = 0;
  for (auto it = readbacks_.begin(); it != readbacks_.end();) {
    // Flush on waiting so the fence is sure to reach the GPU.
    const GLenum s = glClientWaitSync(it->fence, wait ? GL_SYNC_FLUSH_COMMANDS_BIT : 0,
                                      wait ? GLuint64(10'000'000'000) : 0);
    if (s != GL_ALREADY_SIGNALED && s != GL_CONDITION_SATISFIED) {
      ++it;
      continue;
    }
    glDeleteSync(it->fence);
    Readback r = std::move(*it);
    it = readbacks_.erase(it);
    const void* p = r.bytes ? glMapNamedBufferRange(r.staging.id(), 0, GLsizeiptr(r.bytes), GL_MAP_READ_BIT) : nullptr;
    if (r.deliver) r.deliver(p, p ? r.bytes : 0);
    if (p) glUnmapNamedBuffer(r.staging.id());
    ++delivered;
  }
  return delivered;
}

GLuint ResourcePool::framebuffer(const std::vector<GLuint>& colors, GLuint depth, int layer, int level) {
  FramebufferKey key{colors, depth, layer, level};
  if (auto it = framebuffers_.find(key); it != framebuffers_.end()) return it->second.id();
  gl::Framebuffer f = gl::createFramebuffer();
  std::vector<GLenum> draw;
  for (size_t i = 0; i < colors.size(); ++i) {
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
    if (layer >= 0) glNamedFramebufferTextureLayer(f.id(), attachment, colors[i], level, layer);
    else glNamedFramebufferTexture(f.id(), attachment, colors[i], level);
    draw.push_back(attachment);
  }
  if (depth) {
    if (layer >= 0) glNamedFramebufferTextureLayer(f.id(), GL_DEPTH_ATTACHMENT, depth, level, layer);
    else glNamedFramebufferTexture(f.id(), GL_DEPTH_ATTACHMENT, depth, level);
  }
  if (draw.empty()) glNamedFramebufferDrawBuffer(f.id(), GL_NONE);
  else glNamedFramebufferDrawBuffers(f.id(), GLsizei(draw.size()), draw.data());
  const GLuint id = f.id();
  framebuffers_.emplace(std::move(key), std::move(f));
  return id;
}

void ResourcePool::dropFramebuffersOf(GLuint texture) {
  for (auto it = framebuffers_.begin(); it != framebuffers_.end();) {
    const auto& k = it->first;
    if (k.depth == texture || std::find(k.colors.begin(), k.colors.end(), texture) != k.colors.end())
      it = framebuffers_.erase(it);
    else
      ++it;
  }
}

namespace {
// Whether an entry goes at a frame's end: an idle pooled one after
// kIdleFramesKept idle frames, a named one after its lifetime.
template <class Entry>
bool expire(Entry& e, int keptFrames) {
  if (e.persistent && e.key.empty()) return false;  // its owner releases it
  if (e.inUse || e.usedThisFrame) {
    e.idleFrames = 0;
    e.usedThisFrame = false;
    return false;
  }
  return ++e.idleFrames > (e.key.empty() ? keptFrames : e.lifetimeFrames);
}
}  // namespace

void ResourcePool::endFrame() {
  ++frame_;
  for (auto it = textures_.begin(); it != textures_.end();) {
    if (expire(it->second, kIdleFramesKept)) {
      dropFramebuffersOf(it->first);
      it = textures_.erase(it);
    } else {
      ++it;
    }
  }
  for (auto it = buffers_.begin(); it != buffers_.end();)
    it = expire(it->second, kIdleFramesKept) ? buffers_.erase(it) : std::next(it);
}

void ResourcePool::clear() {
  framebuffers_.clear();
  samplers_.clear();
  textures_.clear();
  buffers_.clear();
  for (Readback& r : readbacks_)
    if (r.fence) glDeleteSync(r.fence);
  readbacks_.clear();
}

std::vector<PoolAllocation> ResourcePool::registry() const {
  std::vector<PoolAllocation> out;
  for (const auto& [id, e] : textures_)
    out.push_back({e.name, true, e.desc.bytes(), e.inUse, e.persistent, e.idleFrames, e.users});
  for (const auto& [id, e] : buffers_)
    out.push_back({e.name, false, e.classBytes, e.inUse, e.persistent, e.idleFrames, e.users});
  return out;
}

size_t ResourcePool::bytes() const {
  size_t n = 0;
  for (const auto& [id, e] : textures_) n += e.desc.bytes();
  for (const auto& [id, e] : buffers_) n += e.classBytes;
  return n;
}

size_t ResourcePool::idleBytes() const {
  size_t n = 0;
  for (const auto& [id, e] : textures_) n += e.idleFrames > 0 ? e.desc.bytes() : 0;
  for (const auto& [id, e] : buffers_) n += e.idleFrames > 0 ? e.classBytes : 0;
  return n;
}

const TextureDesc* ResourcePool::describe(GLuint texture) const {
  auto it = textures_.find(texture);
  return it == textures_.end() ? nullptr : &it->second.desc;
}

}  // namespace hs::render
