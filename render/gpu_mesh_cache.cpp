#include "render/gpu_mesh_cache.h"

#include <algorithm>
#include <cmath>

namespace hs::render {

void GpuMesh::release() {
  if (vao) glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(4, buffers);
  if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
  vao = 0;
  textures.clear();
}

void GpuMeshCache::clear() {
  for (auto& [id, g] : meshes_) g->release();
  meshes_.clear();
}

namespace {

GLuint uploadTexture(const mesh::Texture& t) {
  if (t.rgba.empty() || t.width <= 0 || t.height <= 0) return 0;
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  const int levels = 1 + int(std::floor(std::log2(double(std::max(t.width, t.height)))));
  glTextureStorage2D(tex, levels, GL_SRGB8_ALPHA8, t.width, t.height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Rows arrive top row first and texture coordinates have v = 0 at the top
  // row (mesh_data.h), so no flip is needed.
  glTextureSubImage2D(tex, 0, 0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, t.rgba.data());
  glGenerateTextureMipmap(tex);
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") || epoxy_gl_version() >= 46)
    glTextureParameterf(tex, GL_TEXTURE_MAX_ANISOTROPY_EXT, 8.0f);
  return tex;
}

}  // namespace

const GpuMesh* GpuMeshCache::get(const scene::MeshAsset& asset) {
  if (!asset.data || asset.data->indices.empty()) return nullptr;
  auto it = meshes_.find(asset.id);
  if (it != meshes_.end()) {
    if (it->second->hash == asset.contentHash) return it->second.get();
    it->second->release();
  }

  auto g = std::make_unique<GpuMesh>();
  const mesh::MeshData& m = *asset.data;
  g->data = asset.data;
  g->bounds = m.bounds();
  g->hash = asset.contentHash;
  g->hasUvs = m.uvs.size() == m.positions.size();
  glCreateBuffers(4, g->buffers);
  glNamedBufferStorage(g->buffers[0], GLsizeiptr(m.positions.size() * sizeof(glm::vec3)), m.positions.data(), 0);
  glNamedBufferStorage(g->buffers[1], GLsizeiptr(m.normals.size() * sizeof(glm::vec3)), m.normals.data(), 0);
  if (g->hasUvs)
    glNamedBufferStorage(g->buffers[2], GLsizeiptr(m.uvs.size() * sizeof(glm::vec2)), m.uvs.data(), 0);
  glNamedBufferStorage(g->buffers[3], GLsizeiptr(m.indices.size() * sizeof(uint32_t)), m.indices.data(), 0);
  g->gpuBytes = m.positions.size() * 24 + m.uvs.size() * 8 + m.indices.size() * 4;

  glCreateVertexArrays(1, &g->vao);
  // Separate streams: the arrays upload exactly as MeshData holds them.
  glVertexArrayVertexBuffer(g->vao, 0, g->buffers[0], 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(g->vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(g->vao, 0, 0);
  glEnableVertexArrayAttrib(g->vao, 0);
  glVertexArrayVertexBuffer(g->vao, 1, g->buffers[1], 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(g->vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(g->vao, 1, 1);
  glEnableVertexArrayAttrib(g->vao, 1);
  if (g->hasUvs) {
    glVertexArrayVertexBuffer(g->vao, 2, g->buffers[2], 0, sizeof(glm::vec2));
    glVertexArrayAttribFormat(g->vao, 2, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(g->vao, 2, 2);
    glEnableVertexArrayAttrib(g->vao, 2);
  }
  glVertexArrayElementBuffer(g->vao, g->buffers[3]);

  for (const auto& t : m.textures) {
    g->textures.push_back(uploadTexture(t));
    g->gpuBytes += size_t(t.width) * size_t(t.height) * 4 * 4 / 3;
  }
  const GpuMesh* out = g.get();
  meshes_[asset.id] = std::move(g);
  return out;
}

void GpuMeshCache::collect(const scene::SceneState& state) {
  std::erase_if(meshes_, [&](const auto& kv) {
    const scene::MeshAsset* a = state.findAsset(kv.first);
    const bool stale = !a || a->contentHash != kv.second->hash;
    if (stale) kv.second->release();
    return stale;
  });
}

size_t GpuMeshCache::gpuBytes() const {
  size_t n = 0;
  for (const auto& [id, g] : meshes_) n += g->gpuBytes;
  return n;
}

}  // namespace hs::render
