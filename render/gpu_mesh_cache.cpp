#include "render/gpu_mesh_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/tangents.h"

namespace hs::render {

void GpuMesh::release() {
  if (vao) glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(4, buffers);
  if (tangents) glDeleteBuffers(1, &tangents);
  tangents = 0;
  tangentBytes = 0;
  if (ownsTextures && !textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
  vao = 0;
  textures.clear();
}

void GpuMeshCache::Entry::release() {
  // Levels first: they borrow the base's textures.
  for (auto& l : lods)
    if (l) l->release();
  lods.clear();
  if (base) base->release();
  base.reset();
}

void GpuMeshCache::clear() {
  for (auto& [id, e] : meshes_) e.release();
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

// Attribute 7: one uint per instance from `buffer` (the object index).
void bindObjectIndices(GLuint vao, GLuint buffer) {
  glVertexArrayVertexBuffer(vao, 7, buffer, 0, sizeof(uint32_t));
  glVertexArrayAttribIFormat(vao, 7, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao, 7, 7);
  glVertexArrayBindingDivisor(vao, 7, 1);
  glEnableVertexArrayAttrib(vao, 7);
}

// Buffers and vertex array for `m`; textures are the caller's business.
std::unique_ptr<GpuMesh> uploadGeometry(const std::shared_ptr<const mesh::MeshData>& data, uint64_t hash,
                                        GLuint objectIndices) {
  auto g = std::make_unique<GpuMesh>();
  const mesh::MeshData& m = *data;
  g->data = data;
  g->bounds = m.bounds();
  g->hash = hash;
  g->hasUvs = m.uvs.size() == m.positions.size();
  g->uvBounds.assign(m.submeshes.size(), glm::vec4(0.0f));
  if (g->hasUvs)
    for (size_t s = 0; s < m.submeshes.size(); ++s) {
      const mesh::Submesh& sm = m.submeshes[s];
      glm::vec2 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
      for (uint32_t k = sm.firstIndex; k < sm.firstIndex + sm.indexCount && k < m.indices.size(); ++k)
        if (const uint32_t i = m.indices[k]; i < m.uvs.size() && std::isfinite(m.uvs[i].x) && std::isfinite(m.uvs[i].y)) {
          lo = glm::min(lo, m.uvs[i]);
          hi = glm::max(hi, m.uvs[i]);
        }
      if (lo.x <= hi.x) g->uvBounds[s] = glm::vec4(lo, hi);
    }
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
  if (objectIndices) bindObjectIndices(g->vao, objectIndices);
  return g;
}

}  // namespace

const GpuMesh* GpuMeshCache::get(const scene::MeshAsset& asset, int level) {
  if (!asset.data || asset.data->indices.empty()) return nullptr;
  Entry& e = meshes_[asset.id];
  if (e.base && e.base->hash != asset.contentHash) e.release();
  if (!e.base) {
    e.base = uploadGeometry(asset.data, asset.contentHash, objectIndices_);
    for (const auto& t : asset.data->textures) {
      e.base->textures.push_back(uploadTexture(t));
      e.base->gpuBytes += size_t(t.width) * size_t(t.height) * 4 * 4 / 3;
    }
  }
  if (level <= 0 || size_t(level) > asset.lods.size()) return e.base.get();

  const scene::MeshLod& lod = asset.lods[size_t(level) - 1];
  if (!lod.data || lod.data->indices.empty()) return e.base.get();
  if (e.lods.size() < asset.lods.size()) e.lods.resize(asset.lods.size());
  std::unique_ptr<GpuMesh>& g = e.lods[size_t(level) - 1];
  if (g && g->hash != lod.contentHash) {
    g->release();
    g.reset();
  }
  if (!g) {
    g = uploadGeometry(lod.data, lod.contentHash, objectIndices_);
    g->textures = e.base->textures;  // material indices match level 0's
    g->ownsTextures = false;
  }
  return g.get();
}

void GpuMeshCache::collect(const scene::SceneState& state) {
  for (auto it = meshes_.begin(); it != meshes_.end();) {
    Entry& e = it->second;
    const scene::MeshAsset* a = state.findAsset(it->first);
    if (!a || !e.base || a->contentHash != e.base->hash) {
      e.release();
      it = meshes_.erase(it);
      continue;
    }
    // Levels the asset no longer has, or has with other data.
    for (size_t k = 0; k < e.lods.size(); ++k)
      if (e.lods[k] && (k >= a->lods.size() || a->lods[k].contentHash != e.lods[k]->hash)) {
        e.lods[k]->release();
        e.lods[k].reset();
      }
    ++it;
  }
}

void GpuMeshCache::setObjectIndexBuffer(GLuint buffer) {
  objectIndices_ = buffer;
  for (auto& [id, e] : meshes_) {
    if (e.base) bindObjectIndices(e.base->vao, buffer);
    for (auto& l : e.lods)
      if (l) bindObjectIndices(l->vao, buffer);
  }
}

void GpuMeshCache::addTangents(const GpuMesh& constMesh) {
  if (constMesh.tangents || !constMesh.data) return;
  // The cache owns every GpuMesh it hands out; draws see them const.
  GpuMesh& g = const_cast<GpuMesh&>(constMesh);
  const std::vector<glm::vec4> t = mesh::computeTangents(*g.data);
  glCreateBuffers(1, &g.tangents);
  glNamedBufferStorage(g.tangents, GLsizeiptr(t.size() * sizeof(glm::vec4)), t.data(), 0);
  g.tangentBytes = t.size() * sizeof(glm::vec4);
  glVertexArrayVertexBuffer(g.vao, 3, g.tangents, 0, sizeof(glm::vec4));
  glVertexArrayAttribFormat(g.vao, 3, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(g.vao, 3, 3);
  glEnableVertexArrayAttrib(g.vao, 3);
}

size_t GpuMeshCache::tangentBytes() const {
  size_t n = 0;
  for (const auto& [id, e] : meshes_) {
    if (e.base) n += e.base->tangentBytes;
    for (const auto& l : e.lods)
      if (l) n += l->tangentBytes;
  }
  return n;
}

size_t GpuMeshCache::gpuBytes() const {
  size_t n = 0;
  for (const auto& [id, e] : meshes_) {
    if (e.base) n += e.base->gpuBytes;
    for (const auto& l : e.lods)
      if (l) n += l->gpuBytes;
  }
  return n;
}

}  // namespace hs::render
