#include "scene/foliage_ground.h"

#include "scene/terrain_asset.h"

namespace hs::scene {

mesh::MeshData worldMesh(const mesh::MeshData& local, const glm::dmat4& world) {
  mesh::MeshData out;
  out.origin = glm::dvec3(world[3]);
  out.positions.reserve(local.positions.size());
  const glm::dmat3 linear(world);
  // p_world = M p, as the renderer draws it (render/visible_set.cpp): the
  // mesh's own origin is where an import put the entity (its translation,
  // scene/operations.cpp), not a second offset. Relative to M's
  // translation: linear p.
  for (const glm::vec3& p : local.positions) out.positions.emplace_back(linear * glm::dvec3(p));
  out.indices = local.indices;
  out.submeshes = local.submeshes;
  return out;
}

FoliageGround::FoliageGround(const SceneState& state, bool withMeshes) {
  for (EntityId id : terrainEntities(state, true)) {
    const TerrainAsset* t = terrainOf(state, id);
    if (!t) continue;
    terrain_ = std::make_unique<terrain::Terrain>(t->data->terrain().clone());
    terrain_->height.setOrigin(terrainWorldOrigin(state, id));
    ground_.terrain = terrain_.get();
    terrainEntity_ = id;
    break;
  }
  if (!withMeshes) return;
  for (EntityId id : state.depthFirstOrder()) {
    const Entity* e = state.find(id);
    if (!e || !e->mesh || !state.effectivelyVisible(id)) continue;
    const MeshAsset* a = state.findAsset(e->mesh->mesh);
    if (!a || !a->data || a->data->triangleCount() == 0) continue;
    meshData_.push_back(std::make_unique<mesh::MeshData>(worldMesh(*a->data, state.worldMatrix(id))));
    meshes_.push_back(std::make_unique<foliage::MeshGround>(*meshData_.back()));
    ground_.meshes.push_back(meshes_.back().get());
  }
}

}  // namespace hs::scene
