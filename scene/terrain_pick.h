#pragma once
// A ray against every visible terrain of a scene (brush picking, the CLI's
// tests, placing things on the ground): terrain::intersectRay per terrain,
// shifted by the showing entity's translation, nearest hit wins. Holes are
// not hit.
#include <limits>
#include <optional>

#include "scene/scene_state.h"
#include "terrain/ray_pick.h"

namespace hs::scene {

struct TerrainPick {
  EntityId entity = kNoEntity;
  TerrainId terrain = kNoTerrain;
  terrain::RayHit hit;  // hit.world: world position; hit.local: metres from the heightfield origin (brush centre)
};

std::optional<TerrainPick> pickTerrain(const SceneState& state, const glm::dvec3& origin, const glm::dvec3& direction,
                                       double maxDistance = std::numeric_limits<double>::infinity());

// The surface height (world Z) under a world XY on the terrain `entity`
// shows, or nullopt outside it or in a hole.
std::optional<double> terrainSurfaceAt(const SceneState& state, EntityId entity, const glm::dvec2& worldXY);

}  // namespace hs::scene
