#include "render/resource_pool.h"

#include <algorithm>

namespace hs::render {

GLenum TextureDesc::target() const {
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
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 0;
  }
}

size_t TextureDesc::bytes() const {
  size_t texels = 0;
  int w = width, h = height;
  for (int l = 0; l < std::max(levels, 1); ++l) {
    texels += size_t(std::max(w, 1)) * size_t(std::max(h, 1));
    w /= 2;
    h /= 2;
  }
  return texels * bytesPerTexel(format) * size_t(std::max(samples, 1)) * size_t(std::max(layers, 1)) *
         (cube ? 6u : 1u);
}

GLuint ResourcePool::acquireTexture(const TextureDesc& desc, const std::string& name) {
  for (auto& [id, e] : textures_)
    if (!e.inUse && !e.persistent && e.desc == desc) {
      e.inUse = e.usedThisFrame = true;
      e.name = name;
      return id;
    }
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
  for (auto& [id, e] : buffers_)
    if (!e.inUse && !e.persistent && e.desc == desc) {
      e.inUse = e.usedThisFrame = true;
      e.name = name;
      return id;
    }
  gl::Buffer b = gl::createBuffer();
  const GLuint id = b.id();
  glNamedBufferStorage(id, GLsizeiptr(std::max<size_t>(desc.bytes, 4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  BufferEntry e;
  e.buffer = std::move(b);
  e.desc = desc;
  e.name = name;
  e.inUse = e.usedThisFrame = true;
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
  const GLuint id = acquireBuffer(desc, name);
  buffers_.at(id).persistent = true;
  return id;
}

GLuint ResourcePool::framebuffer(const std::vector<GLuint>& colors, GLuint depth, int layer) {
  FramebufferKey key{colors, depth, layer};
  if (auto it = framebuffers_.find(key); it != framebuffers_.end()) return it->second.id();
  gl::Framebuffer f = gl::createFramebuffer();
  std::vector<GLenum> draw;
  for (size_t i = 0; i < colors.size(); ++i) {
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + i);
    if (layer >= 0) glNamedFramebufferTextureLayer(f.id(), attachment, colors[i], 0, layer);
    else glNamedFramebufferTexture(f.id(), attachment, colors[i], 0);
    draw.push_back(attachment);
  }
  if (depth) {
    if (layer >= 0) glNamedFramebufferTextureLayer(f.id(), GL_DEPTH_ATTACHMENT, depth, 0, layer);
    else glNamedFramebufferTexture(f.id(), GL_DEPTH_ATTACHMENT, depth, 0);
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

void ResourcePool::endFrame() {
  for (auto it = textures_.begin(); it != textures_.end();) {
    TextureEntry& e = it->second;
    if (!e.persistent && !e.inUse && !e.usedThisFrame) {
      dropFramebuffersOf(it->first);
      it = textures_.erase(it);
      continue;
    }
    e.usedThisFrame = false;
    ++it;
  }
  for (auto it = buffers_.begin(); it != buffers_.end();) {
    BufferEntry& e = it->second;
    if (!e.persistent && !e.inUse && !e.usedThisFrame) {
      it = buffers_.erase(it);
      continue;
    }
    e.usedThisFrame = false;
    ++it;
  }
}

void ResourcePool::clear() {
  framebuffers_.clear();
  textures_.clear();
  buffers_.clear();
}

std::vector<PoolAllocation> ResourcePool::registry() const {
  std::vector<PoolAllocation> out;
  for (const auto& [id, e] : textures_) out.push_back({e.name, true, e.desc.bytes(), e.inUse, e.persistent});
  for (const auto& [id, e] : buffers_) out.push_back({e.name, false, e.desc.bytes, e.inUse, e.persistent});
  return out;
}

size_t ResourcePool::bytes() const {
  size_t n = 0;
  for (const auto& [id, e] : textures_) n += e.desc.bytes();
  for (const auto& [id, e] : buffers_) n += e.desc.bytes;
  return n;
}

const TextureDesc* ResourcePool::describe(GLuint texture) const {
  auto it = textures_.find(texture);
  return it == textures_.end() ? nullptr : &it->second.desc;
}

}  // namespace hs::render
