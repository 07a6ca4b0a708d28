#include "scene/demo_mesh.h"

#include <memory>

#include "scene/mesh_materials.h"

namespace hs::scene {

EntityId addDemoGroup(SceneState& s, const std::string& name) {
  Entity group;
  group.id = s.maxEntityId() + 1;
  group.name = name;
  s.roots.push_back(group.id);
  s.entities.emplace(group.id, group);
  return group.id;
}

Material& addDemoMesh(SceneState& s, const std::string& name, mesh::MeshData mesh, const glm::dvec3& position,
                      EntityId parent, const std::string& madeIn) {
  mesh.materials[0].name = "surface";
  MeshAsset a;
  a.id = s.maxAssetId() + 1;
  a.name = name;
  a.sourcePath = "(made in code: " + madeIn + ")";
  a.contentHash = mesh::contentHash(mesh);
  a.data = std::make_shared<const mesh::MeshData>(std::move(mesh));
  s.assets.emplace(a.id, a);
  addMeshMaterials(s, a.id);
  Entity e;
  e.id = s.maxEntityId() + 1;
  e.name = name;
  e.parent = parent;
  e.transform.translation = position;
  e.mesh = MeshInstance{a.id};
  s.entities[parent].children.push_back(e.id);
  s.entities.emplace(e.id, e);
  return s.materials.at(s.assets.at(a.id).materialSlots.front());
}

}  // namespace hs::scene
