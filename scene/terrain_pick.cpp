#include "scene/terrain_pick.h"

namespace hs::scene {

std::optional<TerrainPick> pickTerrain(const SceneState& state, const glm::dvec3& origin, const glm::dvec3& direction,
                                       double maxDistance) {
  std::optional<TerrainPick> best;
  for (EntityId id : terrainEntities(state, true)) {
    const TerrainAsset* t = terrainOf(state, id);
    // intersectRay works in the heightfield's own frame (its origin); the
    // entity's translation shifts that frame in the world.
    const glm::dvec3 shift(state.worldMatrix(id)[3]);
    const double limit = best ? best->hit.distance : maxDistance;
    auto hit = terrain::intersectRay(t->data->heights(), origin - shift, direction, limit);
    if (!hit) continue;
    hit->world += shift;
    best = TerrainPick{id, t->id, *hit};
  }
  return best;
}

std::optional<double> terrainSurfaceAt(const SceneState& state, EntityId entity, const glm::dvec2& worldXY) {
  const TerrainAsset* t = terrainOf(state, entity);
  if (!t) return std::nullopt;
  const glm::dvec3 shift(state.worldMatrix(entity)[3]);
  auto z = t->data->heights().surfaceAtWorld(worldXY - glm::dvec2(shift));
  if (!z) return std::nullopt;
  return *z + shift.z;
}

}  // namespace hs::scene
