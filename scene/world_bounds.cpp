#include "scene/world_bounds.h"

namespace hs::scene {

void WorldBox::extend(const glm::dvec3& p) {
  if (empty) {
    min = max = p;
    empty = false;
  } else {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
}

namespace {

void addEntity(const SceneState& s, EntityId id, WorldBox& box, bool visibleOnly) {
  const Entity* e = s.find(id);
  if (!e || (visibleOnly && !e->visible)) return;
  const glm::dmat4 w = s.worldMatrix(id);
  const MeshAsset* a = e->mesh ? s.findAsset(e->mesh->mesh) : nullptr;
  if (a && a->data && !a->data->positions.empty()) {
    const mesh::Bounds b = a->data->bounds();
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z);
      box.extend(glm::dvec3(w * glm::dvec4(corner, 1.0)));
    }
  } else if (const TerrainAsset* t = terrainOf(s, id)) {
    // Terrains ignore rotation and scale (components.h): translation only.
    const terrain::Heightfield& hf = t->data->heights();
    const terrain::HeightRange r = hf.range();
    const glm::dvec3 o = glm::dvec3(w[3]) + hf.origin();
    box.extend(o + glm::dvec3(0.0, 0.0, double(r.min)));
    box.extend(o + glm::dvec3(hf.sizeMetres(), double(r.max)));
  } else if (!e->light && !e->camera) {
    box.extend(glm::dvec3(w[3]));
  }
  for (EntityId c : e->children) addEntity(s, c, box, visibleOnly);
}

}  // namespace

WorldBox worldBounds(const SceneState& state, const std::vector<EntityId>& ids) {
  WorldBox box;
  if (ids.empty()) {
    for (EntityId r : state.roots) addEntity(state, r, box, true);
  } else {
    for (EntityId id : ids) addEntity(state, id, box, false);
  }
  return box;
}

}  // namespace hs::scene
