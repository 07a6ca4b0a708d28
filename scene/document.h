#pragma once
// The open scene: its state, its undo history and its file. Every change goes
// through push() as a patch (see edit.h for how edits build them), so the
// editor, the CLI and tests share one command API and one undo stack.
#include <QObject>
#include <QString>
#include <QUndoStack>

#include "scene/scene_patch.h"
#include "scene/scene_state.h"
#include "scene/terrain_undo_budget.h"

namespace hs::scene {

// What a change touched, so views refresh only what they show.
struct ChangeSet {
  std::vector<EntityId> entities;  // added, removed or modified
  bool hierarchy = false;          // entities added/removed/reparented/renamed
  bool assets = false;
  bool materials = false;          // materials or textures added, removed or changed
  bool settings = false;
  bool sequence = false;           // tracks, keys, frame rate or range
  std::vector<TerrainId> terrains; // terrains whose values or tiles changed
  bool foliage = false;            // foliage types or instances
  bool reset = false;              // a whole new state (new/open)
};

class Document : public QObject {
  Q_OBJECT
 public:
  explicit Document(QObject* parent = nullptr);
  ~Document() override;

  const SceneState& state() const { return state_; }
  QUndoStack* undoStack() { return &undo_; }

  // Pushes an undoable command that applies `patch`. Consecutive pushes with
  // the same non-empty `mergeKey` fold into one undo step (a gizmo drag).
  // Empty patches are dropped. Returns whether anything was pushed.
  bool push(ScenePatch patch, const QString& text, const QString& mergeKey = {});

  // Replaces the whole state (New, Open): clears history, marks clean.
  void reset(SceneState state, const QString& filePath);

  QString filePath() const { return filePath_; }
  void setFilePath(const QString& path);
  bool isModified() const { return !undo_.isClean(); }
  void markSaved() { undo_.setClean(); }

  EntityId allocateEntityId() { return nextEntity_++; }
  AssetId allocateAssetId() { return nextAsset_++; }
  TerrainId allocateTerrainId() { return nextTerrain_++; }
  MaterialId allocateMaterialId() { return nextMaterial_++; }
  TextureId allocateTextureId() { return nextTexture_++; }

  // Terrain tile edits (scene/terrain_edits.h) and their undo memory cap.
  TerrainUndoBudget& terrainUndo() { return terrainUndo_; }
  // Tells views that terrain `id`'s tiles changed (a stroke, a terrain undo).
  void notifyTerrainChanged(TerrainId id);

  // The scene's foliage (foliage_data.h), made empty when it has none.
  // Edits go through pushFoliageEdit (foliage_command.h).
  FoliageData& foliage();
  // Tells views that the foliage changed (an edit, an undo, ground following).
  void notifyFoliageChanged();

  // Called by the undo command; not for general use.
  void applyFromCommand(const ScenePatch& patch, bool forward);

 signals:
  void changed(const hs::scene::ChangeSet& changes);
  void filePathChanged(const QString& path);
  void modifiedChanged(bool modified);

 private:
  SceneState state_;
  QUndoStack undo_;
  QString filePath_;
  EntityId nextEntity_ = 1;
  AssetId nextAsset_ = 1;
  TerrainId nextTerrain_ = 1;
  MaterialId nextMaterial_ = 1;
  TextureId nextTexture_ = 1;
  TerrainUndoBudget terrainUndo_;  // outlives undo_'s commands (cleared in ~Document)
};

}  // namespace hs::scene

Q_DECLARE_METATYPE(hs::scene::ChangeSet)
