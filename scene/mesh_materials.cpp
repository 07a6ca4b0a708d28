#include "scene/mesh_materials.h"

namespace hs::scene {

size_t materialSlotCount(const mesh::MeshData& mesh) {
  for (const mesh::Submesh& s : mesh.submeshes)
    if (s.material < 0 || size_t(s.material) >= mesh.materials.size()) return mesh.materials.size() + 1;
  return mesh.materials.size();
}

size_t materialSlotOf(const mesh::MeshData& mesh, const mesh::Submesh& submesh) {
  const bool own = submesh.material >= 0 && size_t(submesh.material) < mesh.materials.size();
  return own ? size_t(submesh.material) : mesh.materials.size();
}

namespace {

std::string freeName(const std::string& base, const IdSource& ids, const std::vector<Material>& made) {
  auto taken = [&](const std::string& n) {
    if (ids.nameTaken && ids.nameTaken(n)) return true;
    for (const Material& m : made)
      if (m.name == n) return true;
    return false;
  };
  if (!taken(base)) return base;
  for (int i = 2;; ++i)
    if (const std::string n = base + " " + std::to_string(i); !taken(n)) return n;
}

}  // namespace

MeshMaterials makeMeshMaterials(const MeshAsset& asset, const IdSource& ids) {
  MeshMaterials out;
  if (!asset.data) return out;
  const mesh::MeshData& m = *asset.data;
  for (size_t t = 0; t < m.textures.size(); ++t) {
    TextureAsset tex;
    tex.id = ids.texture();
    tex.name = asset.name + " / " + (m.textures[t].name.empty() ? "texture " + std::to_string(t) : m.textures[t].name);
    tex.asset = asset.id;
    tex.meshTexture = int(t);
    tex.image = std::shared_ptr<const mesh::Texture>(asset.data, &m.textures[t]);
    out.textures.push_back(std::move(tex));
  }
  const size_t slotCount = materialSlotCount(m);
  for (size_t s = 0; s < slotCount; ++s) {
    Material mat;
    mat.id = ids.material();
    mat.asset = asset.id;
    if (s < m.materials.size()) {
      const mesh::Material& src = m.materials[s];
      mat.name = freeName(asset.name + " / " + (src.name.empty() ? "material " + std::to_string(s) : src.name), ids,
                          out.materials);
      mat.baseColor = glm::vec3(src.baseColor);
      mat.opacity = src.baseColor.a;
      if (src.diffuseTexture >= 0 && size_t(src.diffuseTexture) < out.textures.size())
        mat.baseColorTexture = out.textures[size_t(src.diffuseTexture)].id;
    } else {
      mat.name = freeName(asset.name + " / default", ids, out.materials);
    }
    out.slotIds.push_back(mat.id);
    out.materials.push_back(std::move(mat));
  }
  return out;
}

void addMeshMaterials(SceneState& state, AssetId assetId) {
  auto it = state.assets.find(assetId);
  if (it == state.assets.end()) return;
  IdSource ids{[&] { return state.maxMaterialId() + 1; }, [&] { return state.maxTextureId() + 1; },
               [&](const std::string& n) { return state.findMaterialByName(n) != kNoMaterial; }};
  // Ids come from the state's maxima, so insert each as it is made.
  MeshMaterials made;
  {
    MaterialId nextM = state.maxMaterialId();
    TextureId nextT = state.maxTextureId();
    ids.material = [&nextM] { return ++nextM; };
    ids.texture = [&nextT] { return ++nextT; };
    made = makeMeshMaterials(it->second, ids);
  }
  for (TextureAsset& t : made.textures) state.textures.emplace(t.id, std::move(t));
  for (Material& m : made.materials) state.materials.emplace(m.id, std::move(m));
  it->second.materialSlots = std::move(made.slotIds);
}

bool linkMeshTextures(SceneState& state, std::string& error) {
  for (auto& [id, t] : state.textures) {
    if (t.standalone()) continue;
    const MeshAsset* a = state.findAsset(t.asset);
    if (!a || !a->data || t.meshTexture < 0 || size_t(t.meshTexture) >= a->data->textures.size()) {
      error = "texture " + std::to_string(id) + " ('" + t.name + "') refers to texture " +
              std::to_string(t.meshTexture) + " of mesh asset " + std::to_string(t.asset) + ", which does not exist";
      return false;
    }
    t.image = std::shared_ptr<const mesh::Texture>(a->data, &a->data->textures[size_t(t.meshTexture)]);
  }
  return true;
}

}  // namespace hs::scene
