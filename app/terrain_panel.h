#pragma once
// The Terrain panel (a dock): the terrain being worked on (the selected
// terrain entity, else the scene's first), its size, resolution and CRS, the
// brush (tool, radius, strength, falloff curve, spacing, target layer and
// the tool's options), the terrain undo memory, whole-terrain erosion (on a
// worker with progress and Cancel), the paint layers and their materials
// (terrain_layers_editor.h), the paint rules and Apply Paint Rules
// (terrain_rules_editor.h; on a worker), and the Terrain menu: New Terrain,
// Import DEM, Export Heightmap / Weights. Material texture files the
// viewport's renderer cannot read are reported in Messages.
//
// Like MainWindow, every command has a form without dialogs (createTerrain,
// importDem, erode, applyPaintRules, exportHeightmap, exportWeights), which
// the request*() menu commands call after their dialogs and tests call
// directly.
#include <functional>
#include <memory>

#include <QWidget>

#include "app/terrain_dialogs.h"
#include "app/terrain_tool.h"
#include "scene/document.h"

class QAction;
class QButtonGroup;
class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QMenu;
class QPushButton;
class QSpinBox;
class QStackedWidget;

namespace hs::app {

class BackgroundJob;
class TerrainLayersEditor;
class TerrainRulesEditor;
class MainWindow;

class TerrainPanel : public QWidget {
  Q_OBJECT
 public:
  explicit TerrainPanel(MainWindow& window);
  ~TerrainPanel() override;

  TerrainTool* tool() { return tool_; }
  // The terrain entity the panel works on (kNoEntity: the scene has none).
  scene::EntityId current() const;
  // Adds the Terrain menu's commands and the brush shortcuts to `menu`.
  void populateMenu(QMenu* menu);
  bool busy() const;

  // --- commands without dialogs (tests, and the request*() forms) ---------
  // With spec.showOn: on that entity (Properties > Add Component > Terrain).
  scene::EntityId createTerrain(const scene::ops::NewTerrain& spec);
  // DEM import on a worker; with `wait`, returns when done (whether it worked).
  bool importDem(const QString& path, const DemImportRequest& request, bool wait);
  bool erode(bool hydraulic, const terrain::ThermalParams& thermal, const terrain::HydraulicParams& hydraulicParams,
             scene::TerrainJobMask mask, bool wait);
  bool applyPaintRules(bool wait);
  bool exportHeightmap(const QString& path, bool wait);
  bool exportWeights(const QString& dir, bool wait);

  // --- with their dialogs ---------------------------------------------------
  // With `showOn`, the terrain goes on that entity instead of a new one.
  void requestNewTerrain(scene::EntityId showOn = scene::kNoEntity);
  void requestImportDem();
  void requestErode(bool hydraulic);
  void requestExportHeightmap();
  void requestExportWeights();

 private:
  void buildUi();
  void refresh();          // the terrain's facts, layers, undo memory
  void refreshBrush();     // widgets from the tool's settings
  void brushFromWidgets();
  const scene::TerrainAsset* currentTerrain() const;
  void reportMaterialProblems();
  void runJob(std::unique_ptr<scene::TerrainJob> job, const QString& title, bool wait, std::shared_ptr<bool> ok);
  bool runExport(const QString& title, std::function<std::string(const Progress&)> work, bool wait);
  void report(const scene::TerrainJobOutcome& out, const QString& title);

  MainWindow& window_;
  scene::Document& doc_;
  TerrainTool* tool_;
  std::unique_ptr<BackgroundJob> job_;
  bool updating_ = false;

  QLabel *info_ = nullptr, *undo_ = nullptr;
  QButtonGroup* tools_ = nullptr;
  QDoubleSpinBox *radius_ = nullptr, *strength_ = nullptr, *falloff_ = nullptr, *spacing_ = nullptr;
  QComboBox *curve_ = nullptr, *layer_ = nullptr, *flattenMode_ = nullptr;
  QCheckBox* erase_ = nullptr;
  QDoubleSpinBox *terraceStep_ = nullptr, *noiseScale_ = nullptr;
  QSpinBox* undoCap_ = nullptr;
  TerrainLayersEditor* layers_ = nullptr;
  TerrainRulesEditor* rules_ = nullptr;
  QDoubleSpinBox* lodError_ = nullptr;
  QList<QWidget*> needTerrain_;
};

}  // namespace hs::app
