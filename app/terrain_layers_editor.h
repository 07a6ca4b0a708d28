#pragma once
// The Terrain panel's "Layers and materials" group: the terrain's paint
// layers (Unreal's layer infos), adding and removing them, and each layer's
// material: name, albedo colour, roughness, tiling in metres, albedo texture
// and normal map files. Every change is one undo step through the document
// (scene::ops::setTerrainMaterial, addTerrainLayer, removeTerrainLayer); a
// spin box scrubbed or stepped until it loses focus is one step.
//
// Commands without dialogs (addLayer, removeLayer, setTexture) are what the
// buttons call and what tests drive.
#include <functional>

#include <QGroupBox>

#include "scene/document.h"

class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QPushButton;
class QToolButton;

namespace hs::app {

class MessagePanel;
class Prompts;

class TerrainLayersEditor : public QGroupBox {
  Q_OBJECT
 public:
  // `terrain` says which terrain the panel works on (nullptr: none).
  TerrainLayersEditor(scene::Document& doc, Prompts& prompts, MessagePanel& messages,
                      std::function<const scene::TerrainAsset*()> terrain, QWidget* parent);

  // Shows the terrain's layers and the chosen layer's material again.
  void refresh();
  int currentLayer() const;
  void setCurrentLayer(int layer);

  // Appends a layer (a grey material named "Layer N"); returns its index or -1.
  int addLayer();
  // Removes `layer` (its weight goes to the others); false with a message if refused.
  bool removeLayer(int layer);
  // Sets (empty: clears) the chosen layer's albedo texture or normal map.
  bool setTexture(bool normal, const QString& path);

 signals:
  // After a layer was added or removed: the brush's layer follows.
  void layerRemoved(int layer);
  void layerAdded(int layer);

 private:
  void refreshMaterial();
  // Pushes the chosen layer's material with `change` applied.
  void editMaterial(const std::function<void(terrain::Material&)>& change, const QString& mergeKey = {});
  QString scrubKey(const char* field) const;

  scene::Document& doc_;
  Prompts& prompts_;
  MessagePanel& messages_;
  std::function<const scene::TerrainAsset*()> terrain_;
  bool updating_ = false;
  int scrub_ = 0;  // bumped when a spin box loses focus: the next edit is a new undo step

  QComboBox* layer_ = nullptr;
  QToolButton *add_ = nullptr, *remove_ = nullptr;
  QLineEdit* name_ = nullptr;
  QPushButton* albedo_ = nullptr;
  QDoubleSpinBox *roughness_ = nullptr, *tiling_ = nullptr;
  QPushButton *albedoTexture_ = nullptr, *normalTexture_ = nullptr;
  QToolButton *clearAlbedo_ = nullptr, *clearNormal_ = nullptr;
};

}  // namespace hs::app
