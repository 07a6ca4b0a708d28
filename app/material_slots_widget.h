#pragma once
// The material slots of one mesh asset, each with a list of the scene's
// materials to choose from (the Properties panel's mesh section; the
// editor's face of `hybridscape-cli material assign`). A choice goes
// through scene::ops::assignMaterial: one undo step, every entity showing
// the asset follows.
#include <string>
#include <vector>

#include <QWidget>

#include "scene/document.h"

class QComboBox;
class QFormLayout;

namespace hs::app {

class MaterialSlotsWidget : public QWidget {
  Q_OBJECT
 public:
  MaterialSlotsWidget(scene::Document& doc, QWidget* parent = nullptr);

  // Shows the slots of `asset` as `state` has them (rebuilt only when the
  // slots, their materials or the materials' names changed).
  void showAsset(const scene::SceneState& state, scene::AssetId asset);
  // The chooser of slot `slot` (null past the last).
  QComboBox* chooser(size_t slot) const;

 signals:
  void problem(const QString& message);

 private:
  scene::Document& doc_;
  scene::AssetId asset_ = scene::kNoAsset;
  std::string shownKey_;  // what the combos were built from
  QFormLayout* form_ = nullptr;
  std::vector<QComboBox*> choosers_;
};

}  // namespace hs::app
