#include "app/terrain_panel.h"

#include <chrono>

#include <QAction>
#include <QButtonGroup>
#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QLabel>
#include <QLocale>
#include <QMenu>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QSpinBox>
#include <QToolButton>
#include <QVBoxLayout>

#include "app/background_job.h"
#include "app/foliage_panel.h"
#include "app/foliage_tool.h"
#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/selection.h"
#include "app/property_panel.h"
#include "app/terrain_layers_editor.h"
#include "app/terrain_rules_editor.h"
#include "app/viewport_widget.h"
#include "scene/fields.h"
#include "scene/operations.h"
#include "scene/terrain_ops.h"

namespace hs::app {
namespace {

const TerrainToolKind kKinds[] = {TerrainToolKind::Off,     TerrainToolKind::Raise,          TerrainToolKind::Lower,
                                  TerrainToolKind::Smooth,  TerrainToolKind::Flatten,        TerrainToolKind::Ramp,
                                  TerrainToolKind::Noise,   TerrainToolKind::Terrace,        TerrainToolKind::ThermalErosion,
                                  TerrainToolKind::HydraulicErosion, TerrainToolKind::Paint, TerrainToolKind::Holes};

const char* kCurves[] = {"Smooth", "Linear", "Spherical", "Tip", "Constant"};

QString mib(size_t bytes) { return QLocale().formattedDataSize(qint64(bytes)); }

QDoubleSpinBox* spin(QWidget* parent, double min, double max, double step, int decimals, const QString& suffix,
                     const QString& tip) {
  return numberSpin(parent, min, max, step, decimals, suffix, tip);
}

}  // namespace

TerrainPanel::TerrainPanel(MainWindow& window)
    : QWidget(&window), window_(window), doc_(window.document()), tool_(new TerrainTool(doc_, this)) {
  setObjectName("terrainPanel");
  // The brush of the last session.
  QSettings s;
  terrain::BrushSettings b = tool_->settings();
  b.radius = s.value("terrain/radius", 20.0).toDouble();
  b.strength = s.value("terrain/strength", 0.5).toFloat();
  b.falloff.falloff = s.value("terrain/falloff", 0.5).toFloat();
  b.spacing = s.value("terrain/spacing", 0.25).toFloat();
  std::vector<std::string> ignored;  // settings files hold what the widgets allowed
  tool_->setSettings(b.sanitized(glm::dvec2(1.0), 1e6, ignored));
  buildUi();
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet&) { refresh(); });
  connect(doc_.undoStack(), &QUndoStack::indexChanged, this, [this] { refresh(); });
  connect(&window_.selection(), &Selection::changed, this, [this] { refresh(); });
  connect(tool_, &TerrainTool::settingsChanged, this, [this] {
    refreshBrush();
    window_.viewport()->update();
  });
  connect(tool_, &TerrainTool::strokeFinished, this, [this](const QString& text, bool warning) {
    if (!text.isEmpty()) warning ? window_.messages()->warning(text) : window_.messages()->info(text);
    refresh();
  });
  // The renderer finds unreadable texture files when it draws; Messages
  // must hear of them (naming the file and the layer) or the layer just
  // shows its flat colour without a word.
  connect(window_.viewport(), &ViewportWidget::frameRendered, this, [this] { reportMaterialProblems(); });
  // Properties > Add Component > Terrain > New Terrain… opens our dialog.
  window_.properties()->setNewTerrainHook([this](scene::EntityId showOn) { requestNewTerrain(showOn); });
  refreshBrush();
  refresh();
}

TerrainPanel::~TerrainPanel() {
  // A running job commits into the document: wait for it while it exists.
  if (job_ && job_->isRunning()) {
    job_->cancel();
    job_->waitForFinished();
  }
  QSettings s;
  s.setValue("terrain/radius", tool_->settings().radius);
  s.setValue("terrain/strength", double(tool_->settings().strength));
  s.setValue("terrain/falloff", double(tool_->settings().falloff.falloff));
  s.setValue("terrain/spacing", double(tool_->settings().spacing));
}

bool TerrainPanel::busy() const { return job_ && job_->isRunning(); }

const scene::TerrainAsset* TerrainPanel::currentTerrain() const { return scene::terrainOf(doc_.state(), current()); }

void TerrainPanel::reportMaterialProblems() {
  for (const std::string& p : window_.viewport()->takeTerrainMaterialProblems())
    window_.messages()->warning("Terrain texture not loaded: " + QString::fromStdString(p) +
                                " (the layer shows its colour alone)");
}

scene::EntityId TerrainPanel::current() const {
  const scene::SceneState& s = doc_.state();
  const auto& sel = window_.selection().ids();
  for (auto it = sel.rbegin(); it != sel.rend(); ++it)
    if (scene::terrainOf(s, *it)) return *it;
  const auto all = scene::terrainEntities(s, false);
  return all.empty() ? scene::kNoEntity : all.front();
}

void TerrainPanel::buildUi() {
  auto* content = new QWidget;
  auto* v = new QVBoxLayout(content);
  info_ = new QLabel(content);
  info_->setObjectName("terrainInfo");
  info_->setWordWrap(true);
  info_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  v->addWidget(info_);

  auto* brush = new QGroupBox("Brush", content);
  auto* bl = new QVBoxLayout(brush);
  auto* grid = new QGridLayout;
  tools_ = new QButtonGroup(this);
  tools_->setExclusive(true);
  for (int i = 0; i < int(std::size(kKinds)); ++i) {
    auto* b = new QToolButton(brush);
    b->setText(terrainToolLabel(kKinds[i]));
    b->setObjectName(QString("terrainTool_%1").arg(terrainToolLabel(kKinds[i])));
    b->setCheckable(true);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    // The dock is narrow beside Properties: buttons share the width they get.
    b->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    b->setMinimumWidth(0);
    tools_->addButton(b, i);
    grid->addWidget(b, i / 3, i % 3);
  }
  tools_->button(0)->setToolTip("No brush: clicks select and the gizmo moves things");
  connect(tools_, &QButtonGroup::idClicked, this, [this](int id) { tool_->setKind(kKinds[id]); });
  bl->addLayout(grid);
  auto* form = new QFormLayout;
  radius_ = spin(brush, 0.05, 100000.0, 1.0, 2, " m", "Brush radius ([ and ])");
  radius_->setObjectName("terrainRadius");
  strength_ = spin(brush, 0.001, 1000.0, 0.05, 3, "", "Raise/Lower/Noise: metres at the centre per dab; others: 0..1 (Shift+[ and Shift+])");
  strength_->setObjectName("terrainStrength");
  falloff_ = spin(brush, 0.0, 1.0, 0.05, 2, "", "Share of the radius over which the effect fades");
  curve_ = new QComboBox(brush);
  for (const char* c : kCurves) curve_->addItem(c);
  spacing_ = spin(brush, 0.01, 4.0, 0.05, 2, "× radius", "Distance between dabs along the stroke");
  layer_ = new QComboBox(brush);
  layer_->setObjectName("terrainLayer");
  layer_->setToolTip("Paint: the layer painted");
  erase_ = new QCheckBox("Erase", brush);
  erase_->setToolTip("Paint: paint the layer away; Holes: fill holes");
  flattenMode_ = new QComboBox(brush);
  flattenMode_->addItems({"To the height under the first dab", "Along the slope under the first dab"});
  terraceStep_ = spin(brush, 0.01, 10000.0, 0.5, 2, " m", "Terrace step height");
  noiseScale_ = spin(brush, 0.01, 100000.0, 1.0, 2, " m", "Noise feature size");
  form->addRow("Radius", radius_);
  form->addRow("Strength", strength_);
  form->addRow("Falloff", falloff_);
  form->addRow("Falloff curve", curve_);
  form->addRow("Spacing", spacing_);
  form->addRow("Layer", layer_);
  form->addRow("", erase_);
  form->addRow("Flatten", flattenMode_);
  form->addRow("Terrace step", terraceStep_);
  form->addRow("Noise scale", noiseScale_);
  bl->addLayout(form);
  for (QDoubleSpinBox* w : {radius_, strength_, falloff_, spacing_, terraceStep_, noiseScale_})
    connect(w, &QDoubleSpinBox::valueChanged, this, [this] { brushFromWidgets(); });
  for (QComboBox* w : {curve_, layer_, flattenMode_})
    connect(w, &QComboBox::currentIndexChanged, this, [this] { brushFromWidgets(); });
  connect(erase_, &QCheckBox::toggled, this, [this] { brushFromWidgets(); });
  v->addWidget(brush);

  auto* undo = new QGroupBox("Terrain undo", content);
  auto* ul = new QFormLayout(undo);
  undo_ = new QLabel(undo);
  undo_->setObjectName("terrainUndoMemory");
  undo_->setWordWrap(true);
  undoCap_ = new QSpinBox(undo);
  undoCap_->setRange(0, 65536);
  undoCap_->setSuffix(" MiB");
  undoCap_->setToolTip("Most memory terrain undo may hold; the oldest steps are dropped first");
  undoCap_->setValue(int(QSettings().value("terrain/undoCapMiB", 512).toInt()));
  doc_.terrainUndo().setCap(size_t(undoCap_->value()) << 20);
  connect(undoCap_, &QSpinBox::valueChanged, this, [this](int miB) {
    const size_t dropped = doc_.terrainUndo().setCap(size_t(miB) << 20);
    QSettings().setValue("terrain/undoCapMiB", miB);
    if (dropped) window_.messages()->info(QString("Terrain undo: %1 oldest step(s) dropped to fit %2 MiB").arg(dropped).arg(miB));
    refresh();
  });
  ul->addRow(undo_);
  ul->addRow("Memory cap", undoCap_);
  v->addWidget(undo);

  auto* whole = new QGroupBox("Whole terrain", content);
  auto* wl = new QGridLayout(whole);
  auto button = [&](const QString& text, const char* name, auto fn, int r, int c) {
    auto* b = new QPushButton(text, whole);
    b->setObjectName(name);
    connect(b, &QPushButton::clicked, this, fn);
    wl->addWidget(b, r, c);
    needTerrain_ << b;
    return b;
  };
  // One column: the dock is narrow.
  button("Thermal Erosion…", "terrainErodeThermal", [this] { requestErode(false); }, 0, 0);
  button("Hydraulic Erosion…", "terrainErodeHydraulic", [this] { requestErode(true); }, 1, 0);
  button("Export Heightmap…", "terrainExport", [this] { requestExportHeightmap(); }, 2, 0);
  lodError_ = spin(whole, 0.1, 64.0, 0.25, 2, " px", "Screen-space error bound of the LOD (the terrain component's field)");
  connect(lodError_, &QDoubleSpinBox::valueChanged, this, [this](double px) {
    if (updating_ || current() == scene::kNoEntity) return;
    scene::ops::setField(doc_, current(), *scene::findEntityField("terrain.lod_error_px"), scene::FieldValue(px),
                         "terrainLodError");
  });
  wl->addWidget(new QLabel("LOD error bound", whole), 3, 0);
  wl->addWidget(lodError_, 4, 0);
  needTerrain_ << lodError_;
  v->addWidget(whole);

  // Layers and materials, then the rules that paint them.
  layers_ = new TerrainLayersEditor(doc_, window_.prompts(), *window_.messages(), [this] { return currentTerrain(); },
                                    content);
  connect(layers_, &TerrainLayersEditor::layerRemoved, this, [this](int removed) {
    // The brush keeps painting the same material: layers above move down one.
    terrain::BrushSettings b = tool_->settings();
    if (b.paintLayer > removed) --b.paintLayer;
    else if (b.paintLayer == removed) b.paintLayer = 0;
    tool_->setSettings(b);
  });
  v->addWidget(layers_);
  rules_ = new TerrainRulesEditor(doc_, [this] { return currentTerrain(); }, [this] { applyPaintRules(false); }, content);
  v->addWidget(rules_);
  v->addStretch(1);
  // Combo boxes would otherwise be as wide as their longest entry.
  for (QComboBox* c : content->findChildren<QComboBox*>()) {
    c->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    c->setMinimumContentsLength(6);
  }

  putInScrollArea(this, content);
}

void TerrainPanel::populateMenu(QMenu* menu) {
  menu->addAction("&New Terrain…", this, [this] { requestNewTerrain(); });
  menu->addAction("&Import DEM…", this, &TerrainPanel::requestImportDem);
  menu->addSeparator();
  menu->addAction("Export &Heightmap…", this, &TerrainPanel::requestExportHeightmap);
  menu->addAction("Export Paint &Weights…", this, &TerrainPanel::requestExportWeights);
  menu->addSeparator();
  menu->addAction("&Thermal Erosion…", this, [this] { requestErode(false); });
  menu->addAction("H&ydraulic Erosion…", this, [this] { requestErode(true); });
  menu->addAction("Apply &Paint Rules", this, [this] { applyPaintRules(false); });
  menu->addSeparator();
  auto shortcut = [&](const QString& text, QList<QKeySequence> keys, auto fn) {
    QAction* a = menu->addAction(text, this, fn);
    a->setShortcuts(keys);
    window_.addAction(a);  // active wherever the focus is in the window
  };
  // One set of keys for whichever brush is active (one at a time): the
  // foliage brush when its tool is on (its density factor for strength),
  // else the terrain's. Two window-wide actions on the same keys would
  // cancel each other out.
  auto foliage = [this]() -> FoliageTool* {
    FoliageTool* f = window_.foliagePanel() ? window_.foliagePanel()->tool() : nullptr;
    return f && f->active() ? f : nullptr;
  };
  auto radius = [this, foliage](double k) {
    if (FoliageTool* f = foliage()) f->scaleRadius(k);
    else tool_->scaleRadius(k);
  };
  auto strength = [this, foliage](double k) {
    if (FoliageTool* f = foliage()) f->scaleDensity(k);
    else tool_->scaleStrength(k);
  };
  shortcut("Brush Radius Smaller", {QKeySequence(Qt::Key_BracketLeft)}, [radius] { radius(1.0 / 1.25); });
  shortcut("Brush Radius Larger", {QKeySequence(Qt::Key_BracketRight)}, [radius] { radius(1.25); });
  // Shift+[ is '{' on most layouts: both are listed.
  shortcut("Brush Strength Lower", {QKeySequence(Qt::SHIFT | Qt::Key_BracketLeft), QKeySequence(Qt::Key_BraceLeft)},
           [strength] { strength(1.0 / 1.25); });
  shortcut("Brush Strength Higher", {QKeySequence(Qt::SHIFT | Qt::Key_BracketRight), QKeySequence(Qt::Key_BraceRight)},
           [strength] { strength(1.25); });
}

void TerrainPanel::refreshBrush() {
  updating_ = true;
  const terrain::BrushSettings& b = tool_->settings();
  for (int i = 0; i < int(std::size(kKinds)); ++i)
    if (kKinds[i] == tool_->kind()) tools_->button(i)->setChecked(true);
  radius_->setValue(b.radius);
  strength_->setValue(double(b.strength));
  falloff_->setValue(double(b.falloff.falloff));
  curve_->setCurrentIndex(std::min(int(b.falloff.shape), int(std::size(kCurves)) - 1));
  spacing_->setValue(double(b.spacing));
  if (b.paintLayer < layer_->count()) layer_->setCurrentIndex(b.paintLayer);
  erase_->setChecked(b.erase);
  flattenMode_->setCurrentIndex(b.flattenMode == terrain::FlattenMode::Slope ? 1 : 0);
  terraceStep_->setValue(double(b.terrace.stepHeight));
  noiseScale_->setValue(b.noise.scale);
  const TerrainToolKind k = tool_->kind();
  layer_->setEnabled(k == TerrainToolKind::Paint);
  erase_->setEnabled(k == TerrainToolKind::Paint || k == TerrainToolKind::Holes);
  flattenMode_->setEnabled(k == TerrainToolKind::Flatten);
  terraceStep_->setEnabled(k == TerrainToolKind::Terrace);
  noiseScale_->setEnabled(k == TerrainToolKind::Noise);
  updating_ = false;
}

void TerrainPanel::brushFromWidgets() {
  if (updating_) return;
  terrain::BrushSettings b = tool_->settings();
  b.radius = radius_->value();
  b.strength = float(strength_->value());
  b.falloff.falloff = float(falloff_->value());
  b.falloff.shape = terrain::FalloffShape(curve_->currentIndex());
  b.spacing = float(spacing_->value());
  if (layer_->currentIndex() >= 0) b.paintLayer = layer_->currentIndex();
  b.erase = erase_->isChecked();
  b.flattenMode = flattenMode_->currentIndex() == 1 ? terrain::FlattenMode::Slope : terrain::FlattenMode::Height;
  b.terrace.stepHeight = float(terraceStep_->value());
  b.noise.scale = noiseScale_->value();
  tool_->setSettings(b);
}

void TerrainPanel::refresh() {
  const scene::EntityId e = current();
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), e);
  for (QWidget* w : needTerrain_) w->setEnabled(t != nullptr && !busy());
  const scene::TerrainUndoBudget& budget = doc_.terrainUndo();
  undo_->setText(QString("%1 of %2 in %3 step(s)%4")
                     .arg(mib(budget.bytesUsed()), mib(budget.cap()))
                     .arg(budget.steps())
                     .arg(budget.droppedTotal() ? QString("; %1 oldest dropped").arg(budget.droppedTotal()) : QString()));
  layers_->refresh();
  rules_->refresh();
  if (!t) {
    info_->setText("No terrain in the scene. Terrain > New Terrain… or Import DEM… makes one.");
    return;
  }
  const terrain::Heightfield& hf = t->data->heights();
  const terrain::HeightRange r = hf.range();
  const auto& geo = hf.geo();
  info_->setText(QString("<b>%1</b><br>%2 × %3 m, %4 × %5 samples (%6 m)<br>heights %7 … %8 m<br>%9<br>%10 in memory")
                     .arg(QString::fromStdString(t->name).toHtmlEscaped())
                     .arg(hf.sizeMetres().x, 0, 'f', 1)
                     .arg(hf.sizeMetres().y, 0, 'f', 1)
                     .arg(hf.samplesX())
                     .arg(hf.samplesY())
                     .arg(hf.spacing().x, 0, 'g', 4)
                     .arg(double(r.min), 0, 'f', 2)
                     .arg(double(r.max), 0, 'f', 2)
                     .arg(geo.valid() ? QString::fromStdString(geo.crsName).toHtmlEscaped() : QString("local coordinates (no CRS)"))
                     .arg(mib(t->data->terrain().memoryBytes())));
  // The brush's layers (names change through materials; layers come and go).
  QStringList names;
  for (const auto& m : t->materials) names << QString::fromStdString(m.name);
  QStringList current;
  for (int i = 0; i < layer_->count(); ++i) current << layer_->itemText(i);
  if (names != current) {
    updating_ = true;
    layer_->clear();
    layer_->addItems(names);
    layer_->setCurrentIndex(std::clamp(tool_->settings().paintLayer, 0, int(names.size()) - 1));
    updating_ = false;
  }
  updating_ = true;
  lodError_->setValue(doc_.state().find(e)->terrain->lodErrorPixels);
  updating_ = false;
}

// --- commands ---------------------------------------------------------------

scene::EntityId TerrainPanel::createTerrain(const scene::ops::NewTerrain& spec) {
  std::string error;
  const scene::EntityId id = scene::ops::addTerrain(doc_, spec, error);
  if (id == scene::kNoEntity) {
    window_.messages()->error("New terrain: " + QString::fromStdString(error));
    window_.prompts().showError(this, "New Terrain", QString::fromStdString(error));
    return id;
  }
  window_.selection().select(id);
  window_.viewport()->frameSelection();
  const terrain::Heightfield& hf = scene::terrainOf(doc_.state(), id)->data->heights();
  window_.messages()->info(QString("New terrain '%1': %2 × %3 m, %4 × %5 samples")
                               .arg(QString::fromStdString(spec.name))
                               .arg(hf.sizeMetres().x)
                               .arg(hf.sizeMetres().y)
                               .arg(hf.samplesX())
                               .arg(hf.samplesY()));
  return id;
}

void TerrainPanel::report(const scene::TerrainJobOutcome& out, const QString& title) {
  for (const std::string& w : out.warnings) window_.messages()->warning(title + ": " + QString::fromStdString(w));
  if (out.cancelled) {
    window_.messages()->info(title + " was cancelled; the terrain is unchanged.");
  } else if (!out.ok) {
    window_.messages()->error(title + ": " + QString::fromStdString(out.error));
    window_.prompts().showError(this, title, QString::fromStdString(out.error));
  } else {
    window_.messages()->info(QString::fromStdString(out.summary));
    if (!out.push.kept)
      window_.messages()->warning(title + " touched more tiles than the whole terrain undo memory holds: it cannot be undone.");
    else if (out.push.dropped)
      window_.messages()->info(QString("Terrain undo memory is full: the %1 oldest terrain step(s) can no longer be undone.")
                                   .arg(out.push.dropped));
  }
  refresh();
}

void TerrainPanel::runJob(std::unique_ptr<scene::TerrainJob> job, const QString& title, bool wait,
                          std::shared_ptr<bool> ok) {
  if (busy()) {
    window_.messages()->warning("A terrain operation is still running; try again when it has finished.");
    return;
  }
  if (!job->valid()) {
    window_.messages()->error(title + ": " + QString::fromStdString(job->invalidReason()));
    return;
  }
  std::shared_ptr<scene::TerrainJob> shared(std::move(job));
  // Window-modal from the start: Undo and brush strokes wait for the result.
  job_ = std::make_unique<BackgroundJob>(&window_, title, title + "…", true, 0);
  connect(job_.get(), &BackgroundJob::finished, this, [this, shared, title, ok] {
    const scene::TerrainJobOutcome out = shared->commit(doc_);
    report(out, title);
    if (ok) *ok = out.ok;
  });
  job_->start([shared](const Progress& p) { shared->run(&p); });
  refresh();
  if (wait) job_->waitForFinished();
}

bool TerrainPanel::erode(bool hydraulic, const terrain::ThermalParams& thermal,
                         const terrain::HydraulicParams& hydraulicParams, scene::TerrainJobMask mask, bool wait) {
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
  if (!t) return false;
  auto ok = std::make_shared<bool>(false);
  runJob(hydraulic ? scene::TerrainJob::hydraulic(doc_, t->id, hydraulicParams, mask)
                   : scene::TerrainJob::thermal(doc_, t->id, thermal, mask),
         hydraulic ? "Hydraulic Erosion" : "Thermal Erosion", wait, ok);
  return wait ? *ok : true;
}

bool TerrainPanel::applyPaintRules(bool wait) {
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
  if (!t) return false;
  auto ok = std::make_shared<bool>(false);
  runJob(scene::TerrainJob::paintRules(doc_, t->id), "Paint Rules", wait, ok);
  return wait ? *ok : true;
}

bool TerrainPanel::importDem(const QString& path, const DemImportRequest& request, bool wait) {
  if (busy()) {
    window_.messages()->warning("A terrain operation is still running; try again when it has finished.");
    return false;
  }
  if (request.intoSelected) {
    const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
    if (!t) return false;
    auto ok = std::make_shared<bool>(false);
    runJob(scene::TerrainJob::demInto(doc_, t->id, path.toStdString(), request.options), "Import DEM into terrain",
           wait, ok);
    return wait ? *ok : true;
  }
  auto result = std::make_shared<terrain::DemImportResult>();
  auto ok = std::make_shared<bool>(false);
  job_ = std::make_unique<BackgroundJob>(&window_, "Import DEM", QString("Importing %1…").arg(QFileInfo(path).fileName()),
                                         true, 0);
  connect(job_.get(), &BackgroundJob::finished, this, [this, result, ok, path] {
    const terrain::DemImportReport& r = result->report;
    for (const std::string& w : r.warnings) window_.messages()->warning(QString::fromStdString(w));
    if (result->cancelled) {
      window_.messages()->info("Import of " + path + " was cancelled; the scene is unchanged.");
      return;
    }
    if (!result->ok()) {
      const QString error = QString::fromStdString(result->error.empty() ? path.toStdString() + ": could not be imported" : result->error);
      window_.messages()->error(error);
      window_.prompts().showError(this, "Import DEM", error);
      return;
    }
    // Named after the file by the rule `terrain import` uses too (scene/terrain_ops.h).
    std::string error;
    const scene::EntityId id =
        scene::ops::addTerrainFromDem(doc_, std::move(*result->heightfield), path.toStdString(), {}, error);
    if (id == scene::kNoEntity) {
      window_.messages()->error("Import DEM: " + QString::fromStdString(error));
      return;
    }
    window_.messages()->info(QString::fromStdString(terrain::summary(r)));
    // The nodata report, always (also when nothing was missing).
    window_.messages()->info(QString("%1: nodata: %2 samples in %3 void(s), largest %4 samples%5")
                                 .arg(QFileInfo(path).fileName())
                                 .arg(r.fill.filled)
                                 .arg(r.fill.voids)
                                 .arg(r.fill.largestVoid)
                                 .arg(r.fill.filled ? QString(", filled by %1").arg(QString::fromStdString(r.fill.method)) : QString()));
    window_.selection().select(id);
    window_.viewport()->frameSelection();
    *ok = true;
  });
  const std::string file = path.toStdString();
  const terrain::DemImportOptions options = request.options;
  job_->start([result, file, options](const Progress& p) { *result = terrain::importDem(file, options, &p); });
  if (wait) job_->waitForFinished();
  return wait ? *ok : true;
}

bool TerrainPanel::runExport(const QString& title, std::function<std::string(const Progress&)> work, bool wait) {
  if (busy()) {
    window_.messages()->warning("A terrain operation is still running; try again when it has finished.");
    return false;
  }
  auto result = std::make_shared<std::string>();
  auto ok = std::make_shared<bool>(false);
  job_ = std::make_unique<BackgroundJob>(&window_, title, title + "…", false, 300);
  connect(job_.get(), &BackgroundJob::finished, this, [this, result, ok, title] {
    if (result->rfind("error:", 0) == 0) {
      const QString e = QString::fromStdString(result->substr(6));
      window_.messages()->error(title + ": " + e);
      window_.prompts().showError(this, title, e);
    } else {
      window_.messages()->info(QString::fromStdString(*result));
      *ok = true;
    }
  });
  job_->start([result, work](const Progress& p) { *result = work(p); });
  if (wait) job_->waitForFinished();
  return wait ? *ok : true;
}

bool TerrainPanel::exportHeightmap(const QString& path, bool wait) {
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
  if (!t) return false;
  // A copy-on-write snapshot: painting may go on while the file is written.
  std::shared_ptr<const scene::TerrainData> snap = t->data->snapshot();
  const std::string file = path.toStdString();
  return runExport("Export Heightmap", [snap, file](const Progress&) -> std::string {
    auto r = terrain::exportHeightmap(snap->heights(), file);
    if (!r) return "error:" + r.error();
    std::string s = "Exported " + r->file + ": " + std::to_string(r->width) + " × " + std::to_string(r->height) + " samples";
    if (r->quantisationStep > 0.0) s += ", 16-bit step " + std::to_string(r->quantisationStep) + " m";
    if (!r->sidecar.empty()) s += ", sidecar " + r->sidecar;
    return s;
  }, wait);
}

bool TerrainPanel::exportWeights(const QString& dir, bool wait) {
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
  if (!t) return false;
  scene::TerrainAsset copy = *t;
  copy.data = t->data->snapshot();
  const std::string folder = dir.toStdString();
  return runExport("Export Paint Weights", [copy, folder](const Progress&) -> std::string {
    auto r = scene::ops::exportPaintWeights(copy, folder);
    if (!r) return "error:" + r.error();
    return "Exported " + std::to_string(r->size()) + " paint weight images (16-bit PNG) into " + folder;
  }, wait);
}

// --- with dialogs ---------------------------------------------------------------

void TerrainPanel::requestNewTerrain(scene::EntityId showOn) {
  std::string name = "Terrain";
  for (int i = 2; doc_.state().findByName(name) != scene::kNoEntity; ++i) name = "Terrain " + std::to_string(i);
  if (const scene::Entity* e = doc_.state().find(showOn)) name = e->name;
  NewTerrainDialog d(&window_, QString::fromStdString(name));
  if (d.exec() != QDialog::Accepted) return;
  scene::ops::NewTerrain spec = d.spec();
  spec.centre = window_.viewport()->camera().pivot();
  spec.centre.z = 0.0;
  spec.showOn = showOn;  // centred on that entity instead
  createTerrain(spec);
}

void TerrainPanel::requestImportDem() {
  const QString path = window_.prompts().askOpenFile(
      &window_, "Import DEM", QSettings().value("terrain/lastDemDirectory", QDir::homePath()).toString(),
      "Elevation models (*.tif *.tiff *.dt0 *.dt1 *.dt2 *.hgt *.asc *.img *.dem *.bil *.vrt *.nc);;All files (*)");
  if (path.isEmpty()) return;
  QSettings().setValue("terrain/lastDemDirectory", QFileInfo(path).absolutePath());
  DemImportDialog d(&window_, path, scene::terrainOf(doc_.state(), current()) != nullptr);
  if (d.exec() != QDialog::Accepted) return;
  importDem(path, d.request(), false);
}

void TerrainPanel::requestErode(bool hydraulic) {
  const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), current());
  if (!t) return;
  QStringList layers;
  for (const auto& m : t->materials) layers << QString::fromStdString(m.name);
  ErosionDialog d(&window_, hydraulic, layers);
  if (d.exec() != QDialog::Accepted) return;
  erode(hydraulic, d.thermal(), d.hydraulic(), d.mask(), false);
}

void TerrainPanel::requestExportHeightmap() {
  if (!scene::terrainOf(doc_.state(), current())) return;
  QString path = window_.prompts().askSaveFile(
      &window_, "Export Heightmap", QDir::homePath() + "/heights.png",
      "16-bit PNG (*.png);;32-bit float EXR (*.exr);;GeoTIFF (*.tif *.tiff);;RAW 16-bit (*.r16)");
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += ".png";
  exportHeightmap(path, false);
}

void TerrainPanel::requestExportWeights() {
  if (!scene::terrainOf(doc_.state(), current())) return;
  const QString dir = QFileDialog::getExistingDirectory(&window_, "Export Paint Weights Into", QDir::homePath());
  if (!dir.isEmpty()) exportWeights(dir, false);
}

}  // namespace hs::app
