#pragma once
// Edit: the one way to change a document. Open an Edit, change working
// copies of entities, assets and settings through it, commit: the edit
// becomes a single undo step holding only what it touched.
//
//   Edit e(doc, "Rename");
//   e.entity(id).name = "Pillar";
//   e.commit();
//
// Structural changes (add, remove, reparent) go through the methods below so
// parent, children and roots stay consistent.
#include <QString>

#include "scene/document.h"

namespace hs::scene {

class Edit {
 public:
  Edit(Document& doc, QString text, QString mergeKey = {});
  Edit(const Edit&) = delete;
  Edit& operator=(const Edit&) = delete;

  const SceneState& current() const { return doc_.state(); }

  bool exists(EntityId id) const;
  // Working copy of an existing (or newly added) entity. Check exists() first:
  // an unknown id is a programming error and throws std::out_of_range.
  Entity& entity(EntityId id);
  // Read-only view through the edit: the working copy if touched.
  const Entity* peek(EntityId id) const;

  // Adds `e` under `parent` (kNoEntity: a root) at `index` (-1: last).
  // Assigns a fresh id when e.id is 0. Returns the id.
  EntityId addEntity(Entity e, EntityId parent = kNoEntity, int index = -1);
  // Removes the entity and its whole subtree, and their animation tracks.
  void removeEntity(EntityId id);
  // Moves `id` under `newParent` at `index` (-1: last). With `keepWorld` the
  // entity stays where it is in the world. Refuses (returns false) a move
  // under itself or one of its descendants.
  bool reparent(EntityId id, EntityId newParent, int index = -1, bool keepWorld = true);
  // Copies the subtree of `id` (new ids, same assets, copies of their
  // animation tracks) next to it; returns the copy's id.
  EntityId duplicate(EntityId id);

  AssetId addAsset(MeshAsset asset);
  // Removes the asset with its own materials and the textures of its mesh
  // (other materials lose their references to those textures).
  void removeAsset(AssetId id);
  // Terrains: add (assigns an id when 0), remove, or change a working copy
  // of the small values (name, materials, rules). Tiles are shared, not
  // copied (terrain_asset.h).
  TerrainId addTerrain(TerrainAsset terrain);
  void removeTerrain(TerrainId id);
  TerrainAsset& terrain(TerrainId id);  // throws std::out_of_range if unknown
  const TerrainAsset* peekTerrain(TerrainId id) const;
  // Removes terrain `id` if no entity (as this edit leaves them) shows it.
  void removeTerrainIfUnused(TerrainId id);
  // Materials and textures (material.h): add (assigns an id when 0),
  // remove, or change a working copy.
  MaterialId addMaterial(Material material);
  void removeMaterial(MaterialId id);  // with its timeline tracks (object_tracks.h)
  Material& material(MaterialId id);  // throws std::out_of_range if unknown
  const Material* peekMaterial(MaterialId id) const;
  TextureId addTexture(TextureAsset texture);
  void removeTexture(TextureId id);
  // Working copy of an existing asset's small values (name, material slots;
  // its mesh data is shared). Throws std::out_of_range if unknown.
  MeshAsset& asset(AssetId id);
  SceneSettings& settings();
  // Working copy of the timeline (tracks, keys, rate, range).
  sequencer::Sequence& sequence();

  glm::dmat4 worldMatrix(EntityId id) const;

  // Pushes the patch as one undo step; false if nothing changed.
  bool commit();

 private:
  std::vector<EntityId>& siblings(EntityId parent);
  void copyBinding(EntityId from, EntityId to);
  void touchRoots();
  // Whether a mesh asset other than `except` (as this edit leaves them)
  // draws a slot with `material`.
  bool usedByOtherAsset(MaterialId material, AssetId except) const;

  Document& doc_;
  QString text_;
  QString mergeKey_;
  ScenePatch patch_;
  bool committed_ = false;
};

}  // namespace hs::scene
