#pragma once
// A draw source for many instances of a few meshes (foliage, scattered
// rocks; draw_source.h): instances in the compact 32-byte format below,
// grouped in cells whose origins are kept in double and sent relative to
// the frame origin. Each frame it culls every instance against every view
// the frame draws (the camera views, then the shadow views) and draws each
// view's visible instances of each type with one instanced draw per part
// (a submesh of the type's mesh), in one of two ways:
//   Culling::Gpu  a compute pass ("<name>_cull": shaders/instance_cull.comp
//                 and instance_commands.comp) writes the visible lists and
//                 the indirect commands; the passes draw them with
//                 glMultiDrawElementsIndirect, the CPU never sees a count
//                 (they come back a frame later, FrameGraph::readback, for
//                 the statistics);
//   Culling::Cpu  the CPU culls (the same sphere test, in double) and
//                 uploads the lists; glDrawElementsInstanced.
// Both draw with mesh.vert's INSTANCED variant and the type's materials;
// the instance's stable id reaches the fragment shader as vObject (the id
// pass writes pickBase + id, the transparency key hashes it with the
// primitive). The instance data lives in a persistent buffer of the frame
// graph, uploaded when setInstances changed it. Include only inside render/.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "render/draw_source.h"
#include "render/visible_set.h"

namespace hs::render {

class MaterialTable;

// One instance (std430, shaders/instances.glsl), 32 bytes.
struct GpuInstance {
  glm::vec3 position{0.0f};  // relative to its cell's origin (m)
  float scale = 1.0f;        // uniform
  uint32_t rotation[2] = {0, 0x7FFF0000u};  // unit quaternion (x, y | z, w) as snorm16 pairs
  uint32_t typeAndCell = 0;  // type | cell << 16
  uint32_t id = 0;           // stable: picking, the transparency key
};
static_assert(sizeof(GpuInstance) == 32);

// Packs an instance; `rotation` is normalised first.
GpuInstance packInstance(const glm::vec3& positionInCell, const glm::quat& rotation, float scale, uint16_t type,
                         uint16_t cell, uint32_t id);
// The rotation an instance stores (after snorm16 rounding, normalised).
glm::quat instanceRotation(const GpuInstance& instance);

struct InstanceSet {
  std::vector<scene::AssetId> types;  // mesh assets of the document (their materials draw them)
  std::vector<glm::dvec3> cells;      // world origins of the cells
  std::vector<GpuInstance> instances;
  scene::EntityId entity = scene::kNoEntity;  // what picking an instance names, with its id
};

class InstancedSource final : public DrawSource {
 public:
  enum class Culling { Cpu, Gpu };
  InstancedSource(std::string name, Culling culling);
  ~InstancedSource() override;

  // Replaces the instances (uploaded by the next frame that draws them).
  void setInstances(InstanceSet set);
  const InstanceSet& instances() const { return set_; }
  Culling culling() const { return culling_; }
  // Visible instances summed over the views of a frame that has been
  // delivered (GPU: a frame or more late; CPU: the last frame); -1: none yet.
  int64_t lastVisible() const { return *lastVisible_; }

  std::string ownPass() const override { return name_; }
  bool has(DrawVariant variant, SurfaceSet surfaces) const override;
  void addMaterials(FrameContext& frame, std::vector<DrawItem>& draws) override;
  void addPreparePasses(FrameGraph& graph, FrameContext& frame) override;
  void declare(PassBuilder& builder, DrawVariant variant) const override;
  void draw(FrameContext& frame, const DrawCall& call, const PassResources& resources) override;
  size_t triangles(SurfaceSet surfaces) const override;
  uint32_t pickIds() const override { return maxId_ + 1; }
  PickedItem picked(uint32_t k) const override { return {set_.entity, k}; }

 private:
  struct Part {
    uint32_t type = 0, firstIndex = 0, indexCount = 0, submesh = 0;
  };
  bool wanted(const Part& part, SurfaceSet surfaces) const;
  void drawParts(FrameContext& frame, const PassResources& r, size_t view, const DrawCall& call);
  void bindInstances(const PassResources& r) const;

  std::string name_, bufferName_;
  Culling culling_;
  InstanceSet set_;
  uint64_t revision_ = 1, uploaded_ = 0;
  uint32_t maxId_ = 0;
  // This frame's: the types' meshes (null: asset gone) and their draws in
  // the MaterialTable, the parts, the types' first slots in a view's list,
  // and the frame's resources.
  std::vector<const GpuMesh*> meshes_;
  std::vector<size_t> materialDraw_;
  const MaterialTable* materials_ = nullptr;
  std::vector<Part> parts_;
  std::vector<uint32_t> typeBase_;
  std::vector<uint32_t> cpuCounts_;  // Cpu: visible per view and type
  size_t cameraViews_ = 0;
  BufferRef instanceBuffer_, cells_, visible_, commands_;
  bool active_ = false;  // something to draw this frame
  std::shared_ptr<int64_t> lastVisible_ = std::make_shared<int64_t>(-1);
};

}  // namespace hs::render
