#include "scene/scene_state.h"

#include <algorithm>
#include <set>
#include <unordered_set>

namespace hs::scene {

const Entity* SceneState::find(EntityId id) const {
  auto it = entities.find(id);
  return it == entities.end() ? nullptr : &it->second;
}

const MeshAsset* SceneState::findAsset(AssetId id) const {
  auto it = assets.find(id);
  return it == assets.end() ? nullptr : &it->second;
}

std::vector<double> MeshAsset::lodErrors() const {
  std::vector<double> out{0.0};
  for (const MeshLod& l : lods) out.push_back(l.hausdorff);
  return out;
}

const TerrainAsset* SceneState::findTerrain(TerrainId id) const {
  auto it = terrains.find(id);
  return it == terrains.end() ? nullptr : &it->second;
}

const Material* SceneState::findMaterial(MaterialId id) const {
  auto it = materials.find(id);
  return it == materials.end() ? nullptr : &it->second;
}

const TextureAsset* SceneState::findTexture(TextureId id) const {
  auto it = textures.find(id);
  return it == textures.end() ? nullptr : &it->second;
}

MaterialId SceneState::findMaterialByName(const std::string& name) const {
  for (const auto& [id, m] : materials)
    if (m.name == name) return id;
  return kNoMaterial;
}

glm::dmat4 SceneState::worldMatrix(EntityId id) const {
  glm::dmat4 m(1.0);
  // Walk up, multiplying on the left; a depth limit guards against a cycle
  // in a damaged file (validate() rejects those at load).
  for (int depth = 0; depth < 10000; ++depth) {
    const Entity* e = find(id);
    if (!e) break;
    m = e->transform.matrix() * m;
    id = e->parent;
  }
  return m;
}

bool SceneState::effectivelyVisible(EntityId id) const {
  for (int depth = 0; depth < 10000; ++depth) {
    const Entity* e = find(id);
    if (!e) return true;
    if (!e->visible) return false;
    id = e->parent;
  }
  return true;
}

bool SceneState::isAncestorOrSelf(EntityId ancestor, EntityId id) const {
  for (int depth = 0; depth < 10000 && id != kNoEntity; ++depth) {
    if (id == ancestor) return true;
    const Entity* e = find(id);
    if (!e) return false;
    id = e->parent;
  }
  return false;
}

std::vector<EntityId> SceneState::depthFirstOrder() const {
  std::vector<EntityId> out;
  out.reserve(entities.size());
  std::vector<EntityId> stack(roots.rbegin(), roots.rend());
  std::unordered_set<EntityId> visited;  // a damaged file may hold a cycle
  while (!stack.empty()) {
    const EntityId id = stack.back();
    stack.pop_back();
    const Entity* e = find(id);
    if (!e || !visited.insert(id).second) continue;
    out.push_back(id);
    stack.insert(stack.end(), e->children.rbegin(), e->children.rend());
  }
  return out;
}

std::vector<EntityId> SceneState::cameras() const {
  std::vector<EntityId> out;
  for (EntityId id : depthFirstOrder())
    if (find(id)->camera) out.push_back(id);
  return out;
}

EntityId SceneState::findByName(const std::string& name) const {
  for (EntityId id : depthFirstOrder())
    if (find(id)->name == name) return id;
  return kNoEntity;
}

EntityId SceneState::maxEntityId() const { return entities.empty() ? 0 : entities.rbegin()->first; }
AssetId SceneState::maxAssetId() const { return assets.empty() ? 0 : assets.rbegin()->first; }
TerrainId SceneState::maxTerrainId() const { return terrains.empty() ? 0 : terrains.rbegin()->first; }
MaterialId SceneState::maxMaterialId() const { return materials.empty() ? 0 : materials.rbegin()->first; }
TextureId SceneState::maxTextureId() const { return textures.empty() ? 0 : textures.rbegin()->first; }

std::string SceneState::validate() const {
  std::set<EntityId> seen;
  for (EntityId r : roots) {
    const Entity* e = find(r);
    if (!e) return "root " + std::to_string(r) + " does not exist";
    if (e->parent != kNoEntity) return "root " + std::to_string(r) + " has a parent";
  }
  for (const auto& [id, e] : entities) {
    if (e.id != id) return "entity key " + std::to_string(id) + " holds id " + std::to_string(e.id);
    for (EntityId c : e.children) {
      const Entity* ce = find(c);
      if (!ce) return "entity " + std::to_string(id) + " lists missing child " + std::to_string(c);
      if (ce->parent != id)
        return "entity " + std::to_string(c) + " is listed under " + std::to_string(id) +
               " but its parent is " + std::to_string(ce->parent);
    }
    if (e.parent != kNoEntity) {
      const Entity* p = find(e.parent);
      if (!p) return "entity " + std::to_string(id) + " has missing parent " + std::to_string(e.parent);
      if (std::count(p->children.begin(), p->children.end(), id) != 1)
        return "entity " + std::to_string(id) + " is not listed exactly once under its parent";
    } else if (std::count(roots.begin(), roots.end(), id) != 1) {
      return "entity " + std::to_string(id) + " has no parent and is not listed exactly once as a root";
    }
    if (e.mesh && e.mesh->mesh != kNoAsset && !findAsset(e.mesh->mesh))
      return "entity " + std::to_string(id) + " uses missing mesh asset " + std::to_string(e.mesh->mesh);
    if (e.terrain && e.terrain->terrain != kNoTerrain && !findTerrain(e.terrain->terrain))
      return "entity " + std::to_string(id) + " shows missing terrain " + std::to_string(e.terrain->terrain);
  }
  for (const auto& [id, a] : assets)
    for (MaterialId m : a.materialSlots)
      if (m != kNoMaterial && !findMaterial(m))
        return "mesh asset " + std::to_string(id) + " uses missing material " + std::to_string(m);
  for (const auto& [id, t] : textures)
    if (!t.standalone() && !findAsset(t.asset))
      return "texture " + std::to_string(id) + " ('" + t.name + "') lives in missing mesh asset " + std::to_string(t.asset);
  for (const auto& [id, m] : materials)
    for (TextureId t : {m.baseColorTexture, m.normalMap, m.heightMap})
      if (t != kNoTexture && !findTexture(t))
        return "material " + std::to_string(id) + " ('" + m.name + "') uses missing texture " + std::to_string(t);
  // Every entity reachable exactly once from the roots (no cycles).
  const auto order = depthFirstOrder();
  seen.insert(order.begin(), order.end());
  if (seen.size() != entities.size() || order.size() != entities.size())
    return "the hierarchy has a cycle or unreachable entities";
  return {};
}

}  // namespace hs::scene
