#include "render/render_world.h"

#include <cmath>

#include "scene/light_units.h"
#include "scene/terrain_asset.h"

namespace hs::render {

RenderWorld RenderWorld::build(const scene::SceneState& s) {
  RenderWorld w;
  w.state = &s;
  // World matrices, parents first (one walk, no re-walking of chains).
  w.world.reserve(s.entities.size());
  struct Item {
    scene::EntityId id;
    glm::dmat4 parent;
  };
  std::vector<Item> stack;
  for (auto it = s.roots.rbegin(); it != s.roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const scene::Entity* e = s.find(item.id);
    if (!e || w.world.count(item.id)) continue;
    const glm::dmat4 m = item.parent * e->transform.matrix();
    w.world.emplace(item.id, m);
    for (auto c = e->children.rbegin(); c != e->children.rend(); ++c) stack.push_back({*c, m});
  }

  for (scene::EntityId id : s.depthFirstOrder()) {
    const scene::Entity& e = *s.find(id);
    if (!e.light || !s.effectivelyVisible(id)) continue;
    const glm::dmat4& m = w.world.at(id);
    WorldLight l;
    l.entity = id;
    l.type = e.light->type;
    l.position = glm::dvec3(m[3]);
    l.direction = glm::normalize(glm::dmat3(m) * glm::dvec3(0, 0, -1));
    l.color = scene::lightRadiometricColor(*e.light);
    l.range = e.light->range;
    l.cosInnerHalf = float(std::cos(glm::radians(double(e.light->innerConeDeg)) * 0.5));
    l.cosOuterHalf = float(std::cos(glm::radians(double(e.light->outerConeDeg)) * 0.5));
    l.castsShadows = e.light->castsShadows;
    l.shadowResolution = e.light->shadowResolution;
    if (l.type == scene::Light::Type::Sun) {
      if (!w.sun) w.sun = l;  // one sun: the first in outliner order
    } else {
      w.lights.push_back(l);
    }
  }

  for (const auto& [id, e] : s.entities) {
    if (!e.mesh || !s.effectivelyVisible(id)) continue;
    const scene::MeshAsset* asset = s.findAsset(e.mesh->mesh);
    if (!asset || !asset->data) continue;
    w.meshes.push_back({id, asset, w.world.at(id), e.mesh->tint});
  }
  if (!s.terrains.empty()) w.terrains = scene::terrainEntities(s, true);
  return w;
}

}  // namespace hs::render
