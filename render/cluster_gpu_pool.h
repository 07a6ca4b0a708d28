#pragma once
// The GPU side of cluster pages (issue 38 item 4): fixed-size slots in four
// buffers (positions, normals, UVs as mesh VAOs read them, and indices into
// the slot's vertices), one page a slot, under the GPU budget
// (SceneSettings::clusterGpuBudgetMb) and no larger than the scene's pages
// need. A page arriving when every slot is taken replaces the least
// recently drawn page that the current frame does not draw; when all of
// them are drawn this frame the budget is full and the page waits (the cut
// keeps the coarser level). Include only inside render/.
#include <cstdint>
#include <map>
#include <vector>

#include <epoxy/gl.h>

#include "render/cluster_page_loader.h"
#include "render/gl/gl_handle.h"

namespace hs::render {

class ClusterGpuPool {
 public:
  // Slots of `slotVertices` vertices and `slotIndices` indices, as many as
  // `budgetBytes` holds (at least one) but no more than `maxSlots`. A
  // change of slot size drops every page; of the count, those past it.
  void configure(size_t slotVertices, size_t slotIndices, size_t budgetBytes, size_t maxSlots);
  bool resident(const PageKey& key) const { return slots_.count(key) > 0; }
  // The slot of a resident page, marked as drawn by the cut of `stamp`
  // (stamps grow; UINT64_MAX pins it, as the roots are); -1 if not resident.
  int32_t use(const PageKey& key, uint64_t stamp);
  // Uploads `page` (false: no slot free of the pages the cut of `stamp`
  // draws, or the page does not fit a slot).
  bool upload(const PageKey& key, const DecodedPage& page, uint64_t stamp);
  void forget(const scene::ClusterAsset* asset);
  void clear();

  GLuint vao() const { return vao_.id(); }
  void setObjectIndexBuffer(GLuint buffer);
  size_t slotVertices() const { return slotVertices_; }
  size_t slotIndices() const { return slotIndices_; }
  // Per resident slot: where each of its clusters' triangles start (in
  // indices from the slot's first).
  const std::vector<uint32_t>& clusterFirst(int32_t slot) const { return clusterFirst_[size_t(slot)]; }
  size_t capacity() const { return capacity_; }
  size_t residentPages() const { return slots_.size(); }
  size_t bytes() const { return capacity_ * slotBytes(); }
  size_t slotBytes() const { return slotVertices_ * 32 + slotIndices_ * 4; }

 private:
  size_t slotVertices_ = 0, slotIndices_ = 0, capacity_ = 0;
  gl::Buffer positions_, normals_, uvs_, indices_;
  gl::VertexArray vao_;
  GLuint objectIndices_ = 0;
  struct Slot {
    int32_t index = -1;
    uint64_t lastFrame = 0;
  };
  std::map<PageKey, Slot> slots_;
  std::vector<int32_t> free_;
  std::vector<std::vector<uint32_t>> clusterFirst_;
};

}  // namespace hs::render
