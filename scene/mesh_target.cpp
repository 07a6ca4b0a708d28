#include "scene/mesh_target.h"

namespace hs::scene {

MeshTarget findMeshTarget(const SceneState& state, const std::string& name, std::string& error) {
  MeshTarget t;
  t.entity = state.findByName(name);
  if (t.entity != kNoEntity) {
    const Entity* e = state.find(t.entity);
    if (!e->mesh) {
      error = "'" + name + "' is an entity without a mesh";
      return t;
    }
    t.asset = state.findAsset(e->mesh->mesh);
    t.what = "entity '" + name + "'";
  } else {
    for (const auto& [aid, a] : state.assets)
      if (a.name == name) {
        t.asset = &a;
        break;
      }
    t.what = "asset '" + name + "'";
  }
  if (!t.asset || !t.asset->data) {
    t.asset = nullptr;
    std::string known;
    for (const auto& [aid, a] : state.assets) known += (known.empty() ? "" : ", ") + ("'" + a.name + "'");
    error = "no entity with a mesh and no mesh asset named '" + name + "'" +
            (known.empty() ? " (the scene has no mesh assets)" : " (mesh assets: " + known + ")");
    return t;
  }
  if (t.entity != kNoEntity) t.what += " (asset '" + t.asset->name + "')";
  return t;
}

}  // namespace hs::scene
