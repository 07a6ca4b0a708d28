#pragma once
// The Foliage panel (a dock beside Terrain): the scene's foliage types (name,
// mesh, instance count; checkable), New Type / Edit Type (FoliageTypeDialog),
// Generate Plant (PlantDialog), Scatter (FoliageScatterDialog), Clear (the
// selected type's instances), the brush (Paint, Erase, Select: radius,
// density factor, seed, the selected type or every checked one) and the
// selection's Delete and Reapply. Each command runs a document operation
// (scene/foliage_ops.h, as `hybridscape-cli foliage` does) and is one undo
// step; what it did goes to Messages.
//
// As TerrainPanel does, every command has a form without dialogs
// (generatePlant, addType, editType, scatter, clear) that the request*()
// menu commands call after their dialogs and tests call directly.
//
// Scatter runs on a worker into a copy of the store, under a window-modal
// progress dialog with Cancel (a million instances take a second or two);
// its cells go into the document at the end (scene::ops::commitFoliageWork,
// which refuses if the document's foliage changed meanwhile). Plant
// generation (a fraction of a second) runs on the UI thread under a busy
// cursor.
#include <map>

#include <QIcon>
#include <QWidget>

#include "app/foliage_tool.h"
#include "core/json.h"
#include "foliage/foliage_type.h"
#include "foliage/plants.h"
#include "scene/document.h"

class QAction;
class QButtonGroup;
class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QMenu;
class QPushButton;
class QSpinBox;
class QTreeWidget;

namespace hs::app {

class PreviewRenderer;

class FoliageGroundCache;
class MainWindow;

class FoliagePanel : public QWidget {
  Q_OBJECT
 public:
  explicit FoliagePanel(MainWindow& window);
  ~FoliagePanel() override;

  FoliageTool* tool() { return tool_; }
  FoliageGroundCache& groundCache() { return *ground_; }
  // Adds the Foliage menu's commands and brush tools to `menu`.
  void populateMenu(QMenu* menu);

  // The type selected in the list (-1: none), and the checked ones.
  int currentType() const;
  void setCurrentType(int index);
  void setTypeChecked(int index, bool checked);
  // What the brush works on: every checked type when "checked types" is
  // on, else the selected one.
  foliage::TypeSet brushTypes() const;

  // --- commands without dialogs (tests, and the request*() forms) ---------
  // A generated plant as a mesh asset; its id, or kNoAsset (reported).
  scene::AssetId generatePlant(const QString& name, const foliage::PlantParams& params);
  bool addType(const foliage::FoliageType& type);
  bool editType(int index, const foliage::FoliageType& type);
  // `values`: `foliage scatter`'s options keyed by declaration (seed,
  // overrides of a single type's rules, region).
  bool scatter(const foliage::TypeSet& types, const Json& values);
  // `values`: `foliage fill`'s options (layer, min_weight, seed, region).
  bool fillLayer(const foliage::TypeSet& types, const Json& values);
  // Removes every instance of the type.
  bool clear(int index);
  // Bakes the impostors foliage types draw that the scene does not store
  // current (every one with `all`) on a worker with its own headless GL,
  // under a progress dialog with Cancel, and stores them as one step
  // (`foliage impostors`'s operation, scene/impostor_ops.h).
  bool bakeImpostors(bool all);
  // `values`: `foliage move`'s offset_m and keep_height, for the selection.
  bool moveSelectionBy(const Json& values);

  // --- with their dialogs ---------------------------------------------------
  void requestGeneratePlant();
  void requestNewType();
  void requestEditType();
  void requestScatter();
  void requestFillLayer();
  void requestClear();
  void requestMoveSelection();

 private:
  void buildUi();
  void refresh();  // the list, counts, buttons
  void refreshBrush();
  void brushFromWidgets();
  void refreshSelection();
  QStringList meshNames() const;
  QStringList layerNames() const;
  bool report(bool ok, const std::string& error, const std::vector<std::string>& messages,
              const std::string& summary, const QString& title);

  // The type list's thumbnails: each type's mesh asset drawn small on a
  // worker (PreviewRenderer), kept per asset while its content is the same.
  void refreshThumbnails();
  struct Thumbnail {
    uint64_t contentHash = 0;
    QIcon icon;  // null until drawn
  };

  MainWindow& window_;
  scene::Document& doc_;
  FoliageGroundCache* ground_;
  FoliageTool* tool_;
  PreviewRenderer* thumbnails_ = nullptr;
  std::map<scene::AssetId, Thumbnail> thumbs_;
  bool updating_ = false;

  QLabel *info_ = nullptr, *selectionInfo_ = nullptr;
  QTreeWidget* list_ = nullptr;
  QPushButton *editType_ = nullptr, *scatter_ = nullptr, *clear_ = nullptr;
  QPushButton *deleteSelection_ = nullptr, *reapply_ = nullptr, *deselect_ = nullptr;
  QButtonGroup* tools_ = nullptr;
  QDoubleSpinBox *radius_ = nullptr, *density_ = nullptr;
  QSpinBox* seed_ = nullptr;
  QCheckBox* useChecked_ = nullptr;
  QList<QAction*> toolActions_;  // the Foliage menu's brush tools, by FoliageToolKind
};

}  // namespace hs::app
