#pragma once
// Which terrain a Terrain component shows, in the Properties panel: the
// "Add Component > Terrain" submenu (one entry per terrain of the scene,
// and New Terrain…) and the component's "Terrain" row (a combo box of the
// scene's terrains). A terrain component without a terrain draws nothing,
// so neither offers one. Each choice is one undo step
// (scene::ops::setShownTerrain); New Terrain… goes to `newTerrain` (the
// Terrain panel's dialog, which makes the terrain on this entity).
#include <functional>

#include <QComboBox>

#include "scene/document.h"

class QMenu;

namespace hs::app {

using NewTerrainHook = std::function<void(scene::EntityId showOn)>;

// Fills the Add Component > Terrain submenu for `entity`, now and whenever
// it opens. Without a hook and without terrains it says where terrains are made.
void fillTerrainComponentMenu(QMenu* menu, scene::Document& doc, scene::EntityId entity, const NewTerrainHook& newTerrain);

class TerrainPicker : public QComboBox {
  Q_OBJECT
 public:
  TerrainPicker(scene::Document& doc, scene::EntityId entity, NewTerrainHook newTerrain, QWidget* parent);
  // Lists the scene's terrains again and shows the entity's.
  void refresh();

 private:
  void chosen(int index);
  scene::Document& doc_;
  scene::EntityId entity_;
  NewTerrainHook newTerrain_;
  bool updating_ = false;
};

}  // namespace hs::app
