#include "render/cluster_gpu_pool.h"

#include <algorithm>

namespace hs::render {

void ClusterGpuPool::configure(size_t slotVertices, size_t slotIndices, size_t budgetBytes, size_t maxSlots) {
  const size_t perSlot = slotVertices * 32 + slotIndices * 4;
  const size_t capacity = std::min(std::max<size_t>(budgetBytes / std::max<size_t>(perSlot, 1), 1), maxSlots);
  if (slotVertices == slotVertices_ && slotIndices == slotIndices_ && capacity == capacity_ && vao_) return;
  // New buffers: the pages come back from the CPU cache as the cuts ask.
  clear();
  slotVertices_ = slotVertices;
  slotIndices_ = slotIndices;
  capacity_ = capacity;
  if (capacity_ == 0 || slotVertices_ == 0) return;
  auto make = [](gl::Buffer& b, size_t bytes) {
    b = gl::createBuffer();
    glNamedBufferStorage(b.id(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
  };
  make(positions_, capacity_ * slotVertices_ * sizeof(glm::vec3));
  make(normals_, capacity_ * slotVertices_ * sizeof(glm::vec3));
  make(uvs_, capacity_ * slotVertices_ * sizeof(glm::vec2));
  make(indices_, capacity_ * slotIndices_ * sizeof(uint32_t));
  vao_ = gl::createVertexArray();
  const GLuint vao = vao_.id();
  // The layout of GpuMesh's VAOs (gpu_mesh_cache.cpp), so mesh.vert and
  // every material program draw clusters as they draw meshes.
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayVertexBuffer(vao, 0, positions_.id(), 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayVertexBuffer(vao, 1, normals_.id(), 0, sizeof(glm::vec3));
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 1, 1);
  glEnableVertexArrayAttrib(vao, 2);
  glVertexArrayVertexBuffer(vao, 2, uvs_.id(), 0, sizeof(glm::vec2));
  glVertexArrayAttribFormat(vao, 2, 2, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 2, 2);
  glVertexArrayElementBuffer(vao, indices_.id());
  free_.clear();
  for (size_t s = capacity_; s-- > 0;) free_.push_back(int32_t(s));
  clusterFirst_.assign(capacity_, {});
  if (objectIndices_) setObjectIndexBuffer(objectIndices_);
}

void ClusterGpuPool::setObjectIndexBuffer(GLuint buffer) {
  objectIndices_ = buffer;
  if (!vao_) return;
  const GLuint vao = vao_.id();
  glEnableVertexArrayAttrib(vao, 7);
  glVertexArrayVertexBuffer(vao, 7, buffer, 0, sizeof(uint32_t));
  glVertexArrayAttribIFormat(vao, 7, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao, 7, 7);
  glVertexArrayBindingDivisor(vao, 7, 1);
}

int32_t ClusterGpuPool::use(const PageKey& key, uint64_t frame) {  // `frame`: the cut's stamp
  auto it = slots_.find(key);
  if (it == slots_.end()) return -1;
  it->second.lastFrame = std::max(it->second.lastFrame, frame);  // a pinned page (UINT64_MAX) stays pinned
  return it->second.index;
}

bool ClusterGpuPool::upload(const PageKey& key, const DecodedPage& page, uint64_t frame) {
  if (resident(key)) return true;
  if (page.positions.size() > slotVertices_ || page.indices.size() > slotIndices_ || capacity_ == 0) return false;
  if (free_.empty()) {
    // The least recently drawn page not drawn in this frame gives way.
    auto victim = slots_.end();
    for (auto it = slots_.begin(); it != slots_.end(); ++it)
      if (it->second.lastFrame < frame && (victim == slots_.end() || it->second.lastFrame < victim->second.lastFrame))
        victim = it;
    if (victim == slots_.end()) return false;
    free_.push_back(victim->second.index);
    slots_.erase(victim);
  }
  const int32_t s = free_.back();
  free_.pop_back();
  const size_t v0 = size_t(s) * slotVertices_, i0 = size_t(s) * slotIndices_;
  const size_t n = page.positions.size();
  glNamedBufferSubData(positions_.id(), GLintptr(v0 * sizeof(glm::vec3)), GLsizeiptr(n * sizeof(glm::vec3)),
                       page.positions.data());
  glNamedBufferSubData(normals_.id(), GLintptr(v0 * sizeof(glm::vec3)), GLsizeiptr(n * sizeof(glm::vec3)),
                       page.normals.data());
  glNamedBufferSubData(uvs_.id(), GLintptr(v0 * sizeof(glm::vec2)), GLsizeiptr(n * sizeof(glm::vec2)),
                       page.uvs.data());
  glNamedBufferSubData(indices_.id(), GLintptr(i0 * sizeof(uint32_t)), GLsizeiptr(page.indices.size() * sizeof(uint32_t)),
                       page.indices.data());
  clusterFirst_[size_t(s)] = page.clusterFirstIndex;
  slots_[key] = {s, frame};
  return true;
}

void ClusterGpuPool::forget(const scene::ClusterAsset* asset) {
  for (auto it = slots_.begin(); it != slots_.end();) {
    if (it->first.asset == asset) {
      free_.push_back(it->second.index);
      it = slots_.erase(it);
    } else {
      ++it;
    }
  }
}

void ClusterGpuPool::clear() {
  slots_.clear();
  free_.clear();
  clusterFirst_.clear();
  positions_.reset(), normals_.reset(), uvs_.reset(), indices_.reset();
  vao_.reset();
  capacity_ = 0;
}

}  // namespace hs::render
