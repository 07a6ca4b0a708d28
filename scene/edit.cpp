#include "scene/edit.h"

#include <algorithm>
#include <stdexcept>

#include "sequencer/binding_target.h"

namespace hs::scene {

Edit::Edit(Document& doc, QString text, QString mergeKey)
    : doc_(doc), text_(std::move(text)), mergeKey_(std::move(mergeKey)) {}

bool Edit::exists(EntityId id) const { return peek(id) != nullptr; }

const Entity* Edit::peek(EntityId id) const {
  auto it = patch_.entities.find(id);
  if (it != patch_.entities.end()) return it->second.after ? &*it->second.after : nullptr;
  return doc_.state().find(id);
}

Entity& Edit::entity(EntityId id) {
  auto it = patch_.entities.find(id);
  if (it == patch_.entities.end()) {
    const Entity* e = doc_.state().find(id);
    if (!e) throw std::out_of_range("no entity " + std::to_string(id));
    it = patch_.entities.emplace(id, BeforeAfter<Entity>{*e, *e}).first;
  }
  if (!it->second.after) throw std::out_of_range("entity " + std::to_string(id) + " was removed");
  return *it->second.after;
}

void Edit::touchRoots() {
  if (!patch_.roots) patch_.roots.emplace(doc_.state().roots, doc_.state().roots);
}

std::vector<EntityId>& Edit::siblings(EntityId parent) {
  if (parent == kNoEntity) {
    touchRoots();
    return patch_.roots->second;
  }
  return entity(parent).children;
}

EntityId Edit::addEntity(Entity e, EntityId parent, int index) {
  if (e.id == kNoEntity) e.id = doc_.allocateEntityId();
  if (parent != kNoEntity && !exists(parent)) parent = kNoEntity;
  e.parent = parent;
  e.children.clear();
  const EntityId id = e.id;
  auto& list = siblings(parent);
  if (index < 0 || size_t(index) > list.size()) index = int(list.size());
  list.insert(list.begin() + index, id);
  auto it = patch_.entities.find(id);
  if (it == patch_.entities.end())
    patch_.entities.emplace(id, BeforeAfter<Entity>{std::nullopt, std::move(e)});
  else
    it->second.after = std::move(e);
  return id;
}

void Edit::removeEntity(EntityId id) {
  if (!exists(id)) return;
  // Children first (copy: the list changes as they go).
  const std::vector<EntityId> children = peek(id)->children;
  for (EntityId c : children) removeEntity(c);
  const EntityId parent = peek(id)->parent;
  auto& list = siblings(parent);
  list.erase(std::remove(list.begin(), list.end(), id), list.end());
  const Entity& removed = entity(id);  // make sure the entity has a before/after entry
  const TerrainId shown = removed.terrain ? removed.terrain->terrain : kNoTerrain;
  patch_.entities[id].after.reset();
  // A terrain nothing else shows goes with it (its tiles stay in the undo step).
  removeTerrainIfUnused(shown);
  // Its tracks go with it (and come back with undo).
  const sequencer::Sequence& seq = patch_.sequence ? patch_.sequence->second : doc_.state().sequence;
  if (seq.findBinding(id)) std::erase_if(sequence().bindings, [id](const auto& b) { return b.entity == id; });
}

bool Edit::reparent(EntityId id, EntityId newParent, int index, bool keepWorld) {
  if (!exists(id)) return false;
  if (newParent != kNoEntity && !exists(newParent)) return false;
  // Refuse a cycle: newParent may not be id or below it.
  for (EntityId p = newParent; p != kNoEntity; p = peek(p)->parent)
    if (p == id) return false;

  const glm::dmat4 world = worldMatrix(id);
  const EntityId oldParent = peek(id)->parent;
  auto& oldList = siblings(oldParent);
  const auto oldPos = std::find(oldList.begin(), oldList.end(), id);
  const int oldIndex = int(oldPos - oldList.begin());
  oldList.erase(oldPos);
  auto& newList = siblings(newParent);
  // Moving down within the same list: the removal shifted the target.
  if (oldParent == newParent && index > oldIndex) --index;
  if (index < 0 || size_t(index) > newList.size()) index = int(newList.size());
  newList.insert(newList.begin() + index, id);
  Entity& e = entity(id);
  e.parent = newParent;
  if (keepWorld) {
    const glm::dmat4 parentWorld = newParent == kNoEntity ? glm::dmat4(1.0) : worldMatrix(newParent);
    e.transform = Transform::fromMatrix(glm::inverse(parentWorld) * world);
  }
  return true;
}

EntityId Edit::duplicate(EntityId id) {
  const Entity* src = peek(id);
  if (!src) return kNoEntity;
  Entity copy = *src;
  copy.id = kNoEntity;
  const auto& list = src->parent == kNoEntity ? (patch_.roots ? patch_.roots->second : doc_.state().roots)
                                              : peek(src->parent)->children;
  const int index = int(std::find(list.begin(), list.end(), id) - list.begin()) + 1;
  const std::vector<EntityId> children = src->children;
  const EntityId newId = addEntity(copy, src->parent, index);
  copyBinding(id, newId);
  // Recreate the subtree under the copy, in order.
  std::vector<std::pair<EntityId, EntityId>> stack;  // (source, new parent)
  for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, newId);
  while (!stack.empty()) {
    auto [s, p] = stack.back();
    stack.pop_back();
    Entity c = *peek(s);
    const std::vector<EntityId> grand = c.children;
    c.id = kNoEntity;
    const EntityId n = addEntity(c, p);
    copyBinding(s, n);
    for (auto it = grand.rbegin(); it != grand.rend(); ++it) stack.emplace_back(*it, n);
  }
  return newId;
}

void Edit::copyBinding(EntityId from, EntityId to) {
  const sequencer::Sequence& seq = patch_.sequence ? patch_.sequence->second : doc_.state().sequence;
  const sequencer::Binding* b = seq.findBinding(from);
  if (!b) return;
  sequencer::Binding copy = *b;
  copy.entity = to;
  copy.label = peek(to)->name;
  sequence().bindings.push_back(std::move(copy));
}

AssetId Edit::addAsset(MeshAsset asset) {
  if (asset.id == kNoAsset) asset.id = doc_.allocateAssetId();
  const AssetId id = asset.id;
  const MeshAsset* existing = doc_.state().findAsset(id);
  patch_.assets[id] = BeforeAfter<MeshAsset>{existing ? std::optional(*existing) : std::nullopt,
                                             std::move(asset)};
  return id;
}

bool Edit::usedByOtherAsset(MaterialId material, AssetId except) const {
  auto uses = [material](const MeshAsset& a) {
    return std::find(a.materialSlots.begin(), a.materialSlots.end(), material) != a.materialSlots.end();
  };
  for (const auto& [aid, ba] : patch_.assets)
    if (aid != except && ba.after && uses(*ba.after)) return true;
  for (const auto& [aid, a] : doc_.state().assets)
    if (aid != except && !patch_.assets.count(aid) && uses(a)) return true;
  return false;
}

void Edit::removeAsset(AssetId id) {
  auto it = patch_.assets.find(id);
  if (it != patch_.assets.end())
    it->second.after.reset();
  else if (const MeshAsset* a = doc_.state().findAsset(id))
    patch_.assets.emplace(id, BeforeAfter<MeshAsset>{*a, std::nullopt});
  // Its materials and the textures that live in its mesh go with it (and
  // come back with undo); other materials drop references to those textures.
  std::vector<TextureId> gone;
  for (const auto& [tid, t] : doc_.state().textures)
    if (t.asset == id) gone.push_back(tid);
  for (const auto& [tid, ba] : patch_.textures)
    if (ba.after && ba.after->asset == id) gone.push_back(tid);
  for (TextureId t : gone) removeTexture(t);
  std::vector<MaterialId> materials;
  for (const auto& [mid, m] : doc_.state().materials) materials.push_back(mid);
  for (const auto& [mid, ba] : patch_.materials)
    if (ba.after) materials.push_back(mid);
  for (MaterialId mid : materials) {
    const Material* m = peekMaterial(mid);
    if (!m) continue;
    if (m->asset == id) {
      // A material the user assigned to another asset's slot (material_ops.h
      // assignMaterial) stays, owned by the scene from now on.
      if (usedByOtherAsset(mid, id)) material(mid).asset = kNoAsset;
      else removeMaterial(mid);
      continue;
    }
    for (TextureId t : gone)
      if (m->baseColorTexture == t || m->normalMap == t || m->heightMap == t) {
        Material& w = material(mid);
        for (TextureId* ref : {&w.baseColorTexture, &w.normalMap, &w.heightMap})
          if (*ref == t) *ref = kNoTexture;
      }
  }
}

TerrainId Edit::addTerrain(TerrainAsset terrain) {
  if (terrain.id == kNoTerrain) terrain.id = doc_.allocateTerrainId();
  const TerrainId id = terrain.id;
  const TerrainAsset* existing = doc_.state().findTerrain(id);
  patch_.terrains[id] = BeforeAfter<TerrainAsset>{existing ? std::optional(*existing) : std::nullopt, std::move(terrain)};
  return id;
}

void Edit::removeTerrain(TerrainId id) {
  auto it = patch_.terrains.find(id);
  if (it != patch_.terrains.end()) {
    it->second.after.reset();
    return;
  }
  if (const TerrainAsset* t = doc_.state().findTerrain(id))
    patch_.terrains.emplace(id, BeforeAfter<TerrainAsset>{*t, std::nullopt});
}

const TerrainAsset* Edit::peekTerrain(TerrainId id) const {
  auto it = patch_.terrains.find(id);
  if (it != patch_.terrains.end()) return it->second.after ? &*it->second.after : nullptr;
  return doc_.state().findTerrain(id);
}

TerrainAsset& Edit::terrain(TerrainId id) {
  auto it = patch_.terrains.find(id);
  if (it == patch_.terrains.end()) {
    const TerrainAsset* t = doc_.state().findTerrain(id);
    if (!t) throw std::out_of_range("no terrain " + std::to_string(id));
    it = patch_.terrains.emplace(id, BeforeAfter<TerrainAsset>{*t, *t}).first;
  }
  if (!it->second.after) throw std::out_of_range("terrain " + std::to_string(id) + " was removed");
  return *it->second.after;
}

void Edit::removeTerrainIfUnused(TerrainId id) {
  if (id == kNoTerrain || !peekTerrain(id)) return;
  // Entities as this edit leaves them: the document's, with the patch's on top.
  for (const auto& [eid, e] : doc_.state().entities) {
    const Entity* now = peek(eid);
    if (now && now->terrain && now->terrain->terrain == id) return;
  }
  for (const auto& [eid, ba] : patch_.entities)
    if (ba.after && ba.after->terrain && ba.after->terrain->terrain == id) return;
  removeTerrain(id);
}

namespace {

// The working copy of `id` in `patch`, taken from `current` on first use.
template <class Id, class T>
T& workingCopy(std::map<Id, BeforeAfter<T>>& patch, const T* current, Id id, const char* what) {
  auto it = patch.find(id);
  if (it == patch.end()) {
    if (!current) throw std::out_of_range(std::string("no ") + what + " " + std::to_string(id));
    it = patch.emplace(id, BeforeAfter<T>{*current, *current}).first;
  }
  if (!it->second.after) throw std::out_of_range(std::string(what) + " " + std::to_string(id) + " was removed");
  return *it->second.after;
}

template <class Id, class T>
void removeFrom(std::map<Id, BeforeAfter<T>>& patch, const T* current, Id id) {
  auto it = patch.find(id);
  if (it != patch.end()) {
    it->second.after.reset();
    return;
  }
  if (current) patch.emplace(id, BeforeAfter<T>{*current, std::nullopt});
}

}  // namespace

MaterialId Edit::addMaterial(Material material) {
  if (material.id == kNoMaterial) material.id = doc_.allocateMaterialId();
  const MaterialId id = material.id;
  const Material* existing = doc_.state().findMaterial(id);
  patch_.materials[id] = BeforeAfter<Material>{existing ? std::optional(*existing) : std::nullopt, std::move(material)};
  return id;
}

void Edit::removeMaterial(MaterialId id) {
  removeFrom(patch_.materials, doc_.state().findMaterial(id), id);
  // Its tracks go with it in the same step (and come back with undo).
  const uint64_t target = sequencer::materialTarget(id);
  const sequencer::Sequence& seq = patch_.sequence ? patch_.sequence->second : doc_.state().sequence;
  if (seq.findBinding(target)) std::erase_if(sequence().bindings, [target](const auto& b) { return b.entity == target; });
}

Material& Edit::material(MaterialId id) {
  return workingCopy(patch_.materials, doc_.state().findMaterial(id), id, "material");
}

const Material* Edit::peekMaterial(MaterialId id) const {
  auto it = patch_.materials.find(id);
  if (it != patch_.materials.end()) return it->second.after ? &*it->second.after : nullptr;
  return doc_.state().findMaterial(id);
}

TextureId Edit::addTexture(TextureAsset texture) {
  if (texture.id == kNoTexture) texture.id = doc_.allocateTextureId();
  const TextureId id = texture.id;
  const TextureAsset* existing = doc_.state().findTexture(id);
  patch_.textures[id] =
      BeforeAfter<TextureAsset>{existing ? std::optional(*existing) : std::nullopt, std::move(texture)};
  return id;
}

void Edit::removeTexture(TextureId id) { removeFrom(patch_.textures, doc_.state().findTexture(id), id); }

MeshAsset& Edit::asset(AssetId id) { return workingCopy(patch_.assets, doc_.state().findAsset(id), id, "asset"); }

sequencer::Sequence& Edit::sequence() {
  if (!patch_.sequence) patch_.sequence.emplace(doc_.state().sequence, doc_.state().sequence);
  return patch_.sequence->second;
}

SceneSettings& Edit::settings() {
  if (!patch_.settings) patch_.settings.emplace(doc_.state().settings, doc_.state().settings);
  return patch_.settings->second;
}

glm::dmat4 Edit::worldMatrix(EntityId id) const {
  glm::dmat4 m(1.0);
  for (int depth = 0; depth < 10000 && id != kNoEntity; ++depth) {
    const Entity* e = peek(id);
    if (!e) break;
    m = e->transform.matrix() * m;
    id = e->parent;
  }
  return m;
}

bool Edit::commit() {
  if (committed_) return false;
  committed_ = true;
  return doc_.push(std::move(patch_), text_, mergeKey_);
}

}  // namespace hs::scene
