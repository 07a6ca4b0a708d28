#pragma once
// What foliage stands on in a scene, in world coordinates: the ground the
// foliage tools place on and snap to (foliage/surface.h's Ground), made
// from the document's visible terrain and mesh entities. A terrain's
// heights are a copy-on-write clone placed at its entity's world origin (no
// samples copied); a mesh entity's level 0 is transformed into world space
// around its entity's translation (float offsets from a double origin, so
// scans at UTM coordinates keep their millimetres) and indexed by a BVH.
// Building it costs what the meshes cost (a BVH per mesh); the editor
// keeps one until the scene's entities or assets change.
#include <memory>
#include <vector>

#include "foliage/surface.h"
#include "scene/scene_state.h"

namespace hs::scene {

class FoliageGround {
 public:
  // The first visible terrain entity's terrain (the tools place on one) and
  // every visible mesh entity. `withMeshes` false: the terrain only.
  explicit FoliageGround(const SceneState& state, bool withMeshes = true);
  FoliageGround(const FoliageGround&) = delete;
  FoliageGround& operator=(const FoliageGround&) = delete;

  const foliage::Ground& ground() const { return ground_; }
  bool empty() const { return !ground_.terrain && ground_.meshes.empty(); }
  EntityId terrainEntity() const { return terrainEntity_; }

 private:
  std::unique_ptr<terrain::Terrain> terrain_;
  std::vector<std::unique_ptr<mesh::MeshData>> meshData_;
  std::vector<std::unique_ptr<foliage::MeshGround>> meshes_;
  foliage::Ground ground_;
  EntityId terrainEntity_ = kNoEntity;
};

// A mesh's triangles in world space as the renderer draws them (the
// entity's matrix times each position; MeshData::origin is the entity's
// translation after an import, not added again), positions only, relative
// to the matrix's translation.
mesh::MeshData worldMesh(const mesh::MeshData& local, const glm::dmat4& world);

}  // namespace hs::scene
