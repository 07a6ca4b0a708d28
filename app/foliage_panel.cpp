#include "app/foliage_panel.h"

#include <algorithm>

#include <QActionGroup>
#include <QButtonGroup>
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QMenu>
#include <QPixmap>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "app/background_job.h"
#include "app/busy_cursor.h"
#include "app/foliage_dialogs.h"
#include "app/foliage_ground_cache.h"
#include "app/foliage_work.h"
#include "app/form_widgets.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/plant_preview.h"
#include "app/preview_renderer.h"
#include "app/prompts.h"
#include "app/status_bar.h"
#include "app/viewport_widget.h"
#include "foliage/foliage_operations.h"
#include "foliage/instance.h"
#include "render/instance_format.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/foliage_data.h"
#include "scene/foliage_ops.h"
#include "scene/impostor_ops.h"
#include "scene/terrain_asset.h"

namespace hs::app {
namespace {

// The tools in the panel's two rows: what adds and removes, then what selects and moves.
const FoliageToolKind kKinds[] = {FoliageToolKind::Off,    FoliageToolKind::Paint, FoliageToolKind::Erase,
                                  FoliageToolKind::Fill,   FoliageToolKind::Select, FoliageToolKind::Lasso,
                                  FoliageToolKind::Move};
constexpr int kToolsPerRow = 4;

// Each tool's tooltip and its Foliage menu entry.
QString toolTipOf(FoliageToolKind k) {
  switch (k) {
    case FoliageToolKind::Off: return "No foliage tool: clicks select entities and the gizmo moves them";
    case FoliageToolKind::Paint:
      return "Paint instances of the brush's types up to their density (one undo step per stroke)";
    case FoliageToolKind::Erase: return "Erase the brush's types (with none chosen: every type) under the brush";
    case FoliageToolKind::Fill:
      return "Draw a loop on the ground: the brush's types fill it up to their density times the brush's (one "
             "undo step)";
    case FoliageToolKind::Select:
      return "Click: the nearest instance within the radius; drag: every instance under the brush; Shift adds to "
             "the selection";
    case FoliageToolKind::Lasso:
      return "Draw a loop on the ground: selects the instances inside it (of the brush's types, with none chosen "
             "every type); Shift adds to the selection";
    case FoliageToolKind::Move:
      return "Drag: the selection follows the ground under the cursor, each instance put back on the surface "
             "under its new place (one undo step)";
  }
  return {};
}
QString menuText(FoliageToolKind k) {
  switch (k) {
    case FoliageToolKind::Off: return "Foliage Tool &Off";
    case FoliageToolKind::Lasso: return "&Lasso Select";
    case FoliageToolKind::Fill: return "&Fill Area";
    case FoliageToolKind::Move: return "&Move Selected Instances";
    default: return QString("%1 Brush").arg(foliageToolLabel(k));
  }
}

// An operation's seed from its checked values, else the declared default.
uint64_t seedOf(const Json& values, const OperationDecl& op) {
  return values.contains("seed") && values["seed"].is_number_integer() ? values["seed"].get<uint64_t>()
                                                                       : uint64_t(defaultNumber(op.param("seed")));
}

QString number(size_t n) { return QLocale().toString(qulonglong(n)); }

constexpr int kThumbnailPixels = 40;  // the type list's icons

// What an instance holds: its record in the store and its GPU copy.
constexpr size_t kInstanceBytes = sizeof(foliage::PackedInstance) + render::kGpuInstanceBytes;

}  // namespace

FoliagePanel::FoliagePanel(MainWindow& window)
    : QWidget(&window),
      window_(window),
      doc_(window.document()),
      ground_(new FoliageGroundCache(doc_, this)),
      tool_(new FoliageTool(doc_, *ground_, this)) {
  setObjectName("foliagePanel");
  tool_->setDialogParent(&window_);
  // The brush of the last session.
  QSettings s;
  FoliageBrush b;
  b.radius = s.value("foliage/radius", 10.0).toDouble();
  b.densityFactor = s.value("foliage/density", 1.0).toDouble();
  b.seed = s.value("foliage/seed", 1).toULongLong();
  tool_->setBrush(b);
  buildUi();
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.foliage || c.assets || c.reset) refresh();
  });
  connect(doc_.undoStack(), &QUndoStack::indexChanged, this, [this] { refresh(); });
  connect(tool_, &FoliageTool::settingsChanged, this, [this] {
    refreshBrush();
    window_.viewport()->update();
  });
  connect(tool_, &FoliageTool::selectionChanged, this, [this] {
    refreshSelection();
    window_.viewport()->update();
  });
  connect(tool_, &FoliageTool::strokeFinished, this, [this](const QString& text, bool warning) {
    warning ? window_.messages()->warning(text) : window_.messages()->info(text);
  });
  refreshBrush();
  refresh();
}

FoliagePanel::~FoliagePanel() {
  QSettings s;
  s.setValue("foliage/radius", tool_->brush().radius);
  s.setValue("foliage/density", tool_->brush().densityFactor);
  s.setValue("foliage/seed", qulonglong(tool_->brush().seed));
}

void FoliagePanel::buildUi() {
  auto* content = new QWidget;
  auto* v = new QVBoxLayout(content);
  info_ = new QLabel(content);
  info_->setObjectName("foliageInfo");
  info_->setWordWrap(true);
  v->addWidget(info_);

  list_ = new QTreeWidget(content);
  list_->setObjectName("foliageTypes");
  list_->setHeaderLabels({"Type", "Mesh", "Instances", "Memory"});
  list_->setIconSize(QSize(kThumbnailPixels, kThumbnailPixels));
  thumbnails_ = new PreviewRenderer(this);
  connect(thumbnails_, &PreviewRenderer::ready, this, [this](int key, const QImage& image) {
    auto it = thumbs_.find(scene::AssetId(key));
    if (it == thumbs_.end()) return;
    it->second.icon = QIcon(QPixmap::fromImage(image));
    refreshThumbnails();
  });
  connect(thumbnails_, &PreviewRenderer::problem, this,
          [this](const QString& m) { window_.messages()->warning("Foliage thumbnails: " + m); });
  list_->setRootIsDecorated(false);
  list_->setSelectionMode(QAbstractItemView::SingleSelection);
  list_->setToolTip("The scene's foliage types. The brush works on the selected type, or on every checked one "
                    "when \"Checked types\" is on. Double-click to edit.");
  list_->header()->setStretchLastSection(false);
  list_->header()->setSectionResizeMode(0, QHeaderView::Stretch);
  list_->header()->setSectionResizeMode(1, QHeaderView::Stretch);
  list_->header()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
  list_->header()->setSectionResizeMode(3, QHeaderView::ResizeToContents);
  list_->setMinimumHeight(120);
  connect(list_, &QTreeWidget::currentItemChanged, this, [this] {
    if (updating_) return;
    tool_->setTypes(brushTypes());
    refresh();
  });
  connect(list_, &QTreeWidget::itemChanged, this, [this] {
    if (!updating_) tool_->setTypes(brushTypes());
  });
  connect(list_, &QTreeWidget::itemDoubleClicked, this, [this] { requestEditType(); });
  v->addWidget(list_, 1);

  auto* buttons = new QGridLayout;
  auto button = [&](const QString& text, const char* name, const QString& tip, auto fn, int r, int c) {
    auto* b = new QPushButton(text, content);
    b->setObjectName(name);
    b->setToolTip(tip);
    connect(b, &QPushButton::clicked, this, fn);
    buttons->addWidget(b, r, c);
    return b;
  };
  button("Generate Plant…", "foliageGeneratePlant", "A tree, shrub, grass clump or rock as a mesh asset with its LODs",
         [this] { requestGeneratePlant(); }, 0, 0);
  button("New Type…", "foliageNewType", "A foliage type drawing one of the scene's mesh assets",
         [this] { requestNewType(); }, 0, 1);
  editType_ = button("Edit Type…", "foliageEditType", "The selected type's settings", [this] { requestEditType(); }, 1, 0);
  scatter_ = button("Scatter…", "foliageScatter",
                    "Place instances by rule over the whole ground: the selected type, or every type competing",
                    [this] { requestScatter(); }, 1, 1);
  clear_ = button("Clear", "foliageClear", "Remove every instance of the selected type", [this] { requestClear(); }, 2, 0);
  v->addLayout(buttons);

  auto* brush = new QGroupBox("Brush", content);
  auto* bl = new QVBoxLayout(brush);
  auto* row = new QGridLayout;
  tools_ = new QButtonGroup(this);
  tools_->setExclusive(true);
  for (int i = 0; i < int(std::size(kKinds)); ++i) {
    QToolButton* b = namedToolButton(brush, foliageToolLabel(kKinds[i]),
                                     qPrintable(QString("foliageTool_%1").arg(foliageToolLabel(kKinds[i]))), {});
    b->setCheckable(true);
    b->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    b->setMinimumWidth(0);
    b->setToolTip(toolTipOf(kKinds[i]));
    tools_->addButton(b, i);
    row->addWidget(b, i / kToolsPerRow, i % kToolsPerRow);
  }
  connect(tools_, &QButtonGroup::idClicked, this, [this](int id) { tool_->setKind(kKinds[id]); });
  bl->addLayout(row);
  auto* form = new QFormLayout;
  radius_ = numberSpin(brush, FoliageTool::kMinRadius, FoliageTool::kMaxRadius, 1.0, 2, " m", "Brush radius");
  radius_->setObjectName("foliageRadius");
  density_ = numberSpin(brush, 0.0, FoliageTool::kMaxDensityFactor, 0.1, 2, "×",
                        "Paint: times each type's density (1: the type's own)");
  density_->setObjectName("foliageDensity");
  seed_ = new QSpinBox(brush);
  seed_->setObjectName("foliageSeed");
  seed_->setRange(0, 2147483647);
  seed_->setKeyboardTracking(false);
  seed_->setToolTip("Paint: each stroke's dabs draw their seeds from it; Reapply: the rotation, scale and sink");
  useChecked_ = new QCheckBox("Checked types (else the selected one)", brush);
  useChecked_->setObjectName("foliageUseChecked");
  useChecked_->setToolTip("Paint several types at once, each to its density and spacing");
  form->addRow("Radius", radius_);
  form->addRow("Density", density_);
  form->addRow("Seed", seed_);
  form->addRow(useChecked_);
  bl->addLayout(form);
  connect(radius_, &QDoubleSpinBox::valueChanged, this, [this] { brushFromWidgets(); });
  connect(density_, &QDoubleSpinBox::valueChanged, this, [this] { brushFromWidgets(); });
  connect(seed_, &QSpinBox::valueChanged, this, [this] { brushFromWidgets(); });
  connect(useChecked_, &QCheckBox::toggled, this, [this] { tool_->setTypes(brushTypes()); });
  v->addWidget(brush);

  auto* sel = new QGroupBox("Selected instances", content);
  auto* sl = new QGridLayout(sel);
  selectionInfo_ = new QLabel(sel);
  selectionInfo_->setObjectName("foliageSelectionInfo");
  sl->addWidget(selectionInfo_, 0, 0, 1, 3);
  auto selButton = [&](const QString& text, const char* name, const QString& tip, auto fn, int c) {
    auto* b = new QPushButton(text, sel);
    b->setObjectName(name);
    b->setToolTip(tip);
    connect(b, &QPushButton::clicked, this, fn);
    sl->addWidget(b, 1, c);
    return b;
  };
  deleteSelection_ = selButton("Delete", "foliageDeleteSelection", "Remove the selected instances (one undo step)",
                               [this] { tool_->deleteSelection(); }, 0);
  reapply_ = selButton("Reapply", "foliageReapply",
                       "Draw rotation, scale and sink again from each type's current settings; instances its "
                       "filters now refuse are removed (one undo step)",
                       [this] { tool_->reapplySelection(); }, 1);
  deselect_ = selButton("Deselect", "foliageDeselect", "Empty the selection", [this] { tool_->clearSelection(); }, 2);
  v->addWidget(sel);

  putInScrollArea(this, content);
}

void FoliagePanel::populateMenu(QMenu* menu) {
  menu->addAction("&Generate Plant…", this, [this] { requestGeneratePlant(); });
  menu->addAction("&New Foliage Type…", this, [this] { requestNewType(); });
  menu->addAction("&Edit Foliage Type…", this, [this] { requestEditType(); });
  menu->addSeparator();
  menu->addAction("&Scatter…", this, [this] { requestScatter(); });
  menu->addAction("Fill Paint &Layer…", this, [this] { requestFillLayer(); });
  menu->addAction("&Clear Type", this, [this] { requestClear(); });
  menu->addAction("Bake &Impostors", this, [this] { bakeImpostors(false); });
  menu->addSeparator();
  auto* group = new QActionGroup(this);
  for (FoliageToolKind k : kKinds) {
    QAction* a = menu->addAction(menuText(k), this, [this, k] { tool_->setKind(k); });
    a->setCheckable(true);
    a->setChecked(tool_->kind() == k);
    group->addAction(a);
    toolActions_ << a;
  }
  menu->addSeparator();
  menu->addAction("Move Selected Instances &By…", this, [this] { requestMoveSelection(); });
  menu->addAction("&Delete Selected Instances", this, [this] { tool_->deleteSelection(); });
  menu->addAction("&Reapply to Selected Instances", this, [this] { tool_->reapplySelection(); });
  menu->addAction("Deselect Instances", this, [this] { tool_->clearSelection(); });
}

int FoliagePanel::currentType() const {
  const QTreeWidgetItem* it = list_->currentItem();
  return it ? list_->indexOfTopLevelItem(const_cast<QTreeWidgetItem*>(it)) : -1;
}

void FoliagePanel::setCurrentType(int index) {
  if (QTreeWidgetItem* it = list_->topLevelItem(index)) list_->setCurrentItem(it);
}

void FoliagePanel::setTypeChecked(int index, bool checked) {
  if (QTreeWidgetItem* it = list_->topLevelItem(index)) it->setCheckState(0, checked ? Qt::Checked : Qt::Unchecked);
}

foliage::TypeSet FoliagePanel::brushTypes() const {
  foliage::TypeSet out;
  if (useChecked_->isChecked()) {
    for (int i = 0; i < list_->topLevelItemCount(); ++i)
      if (list_->topLevelItem(i)->checkState(0) == Qt::Checked) out.push_back(uint16_t(i));
  } else if (currentType() >= 0) {
    out.push_back(uint16_t(currentType()));
  }
  return out;
}

void FoliagePanel::refreshThumbnails() {
  const foliage::FoliageStore* store = scene::foliageStoreOf(doc_.state());
  const int n = store ? int(store->types().size()) : 0;
  for (int i = 0; i < n && i < list_->topLevelItemCount(); ++i) {
    QTreeWidgetItem* it = list_->topLevelItem(i);
    const scene::AssetId id = scene::foliageTypeAsset(doc_.state(), store->type(size_t(i)));
    const scene::MeshAsset* a = doc_.state().findAsset(id);
    if (!a) {
      it->setIcon(0, QIcon());
      continue;
    }
    auto found = thumbs_.find(id);
    if (found == thumbs_.end() || found->second.contentHash != a->contentHash) {
      // Not drawn for this content yet: ask once; the icon comes with ready().
      if (std::optional<scene::SceneState> s = meshPreviewScene(doc_.state(), id)) {
        thumbs_[id] = Thumbnail{a->contentHash, QIcon()};
        thumbnails_->request(int(id), std::move(*s), kPreviewCamera, kThumbnailPixels);
      }
      it->setIcon(0, QIcon());
      continue;
    }
    it->setIcon(0, found->second.icon);
  }
}

void FoliagePanel::refresh() {
  const foliage::FoliageStore* store = scene::foliageStoreOf(doc_.state());
  const size_t n = store ? store->types().size() : 0;
  updating_ = true;
  // Rows follow the types' order (the brush and the commands use indices);
  // check marks stay on their rows.
  while (list_->topLevelItemCount() > int(n)) delete list_->takeTopLevelItem(list_->topLevelItemCount() - 1);
  while (list_->topLevelItemCount() < int(n)) {
    auto* it = new QTreeWidgetItem(list_);
    it->setFlags(it->flags() | Qt::ItemIsUserCheckable);
    it->setCheckState(0, Qt::Unchecked);
    it->setTextAlignment(2, Qt::AlignRight | Qt::AlignVCenter);
    it->setTextAlignment(3, Qt::AlignRight | Qt::AlignVCenter);
  }
  for (size_t i = 0; i < n; ++i) {
    const foliage::FoliageType& t = store->type(i);
    QTreeWidgetItem* it = list_->topLevelItem(int(i));
    it->setText(0, QString::fromStdString(t.name));
    it->setText(1, QString::fromStdString(t.mesh));
    const size_t count = store->instanceCount(uint16_t(i));
    it->setText(2, number(count));
    it->setText(3, formatBytes(count * kInstanceBytes));
    it->setToolTip(3, QString("%1 in the scene's store and %2 on the GPU (%3 + %4 bytes an instance); the mesh "
                              "and its levels are the asset's, shared by every instance")
                          .arg(formatBytes(count * sizeof(foliage::PackedInstance)))
                          .arg(formatBytes(count * render::kGpuInstanceBytes))
                          .arg(sizeof(foliage::PackedInstance))
                          .arg(render::kGpuInstanceBytes));
    it->setToolTip(1, scene::foliageTypeAsset(doc_.state(), t) == scene::kNoAsset
                          ? QString("No mesh asset of this name in the scene: the type draws nothing")
                          : QString());
  }
  if (!list_->currentItem() && n > 0) list_->setCurrentItem(list_->topLevelItem(0));
  updating_ = false;
  refreshThumbnails();
  tool_->setTypes(brushTypes());
  const bool selected = currentType() >= 0;
  editType_->setEnabled(selected);
  clear_->setEnabled(selected);
  scatter_->setEnabled(n > 0);
  if (n == 0)
    info_->setText("No foliage types. Generate Plant… (or import a mesh), then New Type… to draw it.");
  else
    info_->setText(QString("%1 type(s), %2 instances in %3 cells of 64 m")
                       .arg(n)
                       .arg(number(store->instanceCount()))
                       .arg(number(store->cellCount())));
  refreshSelection();
}

void FoliagePanel::refreshBrush() {
  updating_ = true;
  const FoliageBrush& b = tool_->brush();
  for (int i = 0; i < int(std::size(kKinds)); ++i)
    if (kKinds[i] == tool_->kind()) {
      tools_->button(i)->setChecked(true);
      if (i < toolActions_.size()) toolActions_[i]->setChecked(true);
    }
  radius_->setValue(b.radius);
  density_->setValue(b.densityFactor);
  seed_->setValue(int(std::min<uint64_t>(b.seed, 2147483647)));
  updating_ = false;
}

void FoliagePanel::brushFromWidgets() {
  if (updating_) return;
  FoliageBrush b = tool_->brush();
  b.radius = radius_->value();
  b.densityFactor = density_->value();
  b.seed = uint64_t(seed_->value());
  tool_->setBrush(b);
}

void FoliagePanel::refreshSelection() {
  const size_t n = tool_->selection().size();
  selectionInfo_->setText(n ? QString("%1 selected").arg(number(n)) : QString("None (the Select and Lasso tools pick them)"));
  for (QPushButton* b : {deleteSelection_, reapply_, deselect_}) b->setEnabled(n > 0);
}

QStringList FoliagePanel::meshNames() const {
  QStringList names;
  for (const auto& [id, a] : doc_.state().assets) names << QString::fromStdString(a.name);
  names.sort(Qt::CaseInsensitive);
  return names;
}

QStringList FoliagePanel::layerNames() const {
  // The terrain foliage stands on (scene::FoliageGround: the first visible one).
  QStringList names;
  for (scene::EntityId id : scene::terrainEntities(doc_.state(), true))
    if (const scene::TerrainAsset* t = scene::terrainOf(doc_.state(), id)) {
      for (const auto& m : t->materials) names << QString::fromStdString(m.name);
      break;
    }
  return names;
}

bool FoliagePanel::report(bool ok, const std::string& error, const std::vector<std::string>& messages,
                          const std::string& summary, const QString& title) {
  for (const std::string& m : messages) window_.messages()->warning(title + ": " + QString::fromStdString(m));
  if (!ok) {
    window_.messages()->error(title + ": " + QString::fromStdString(error));
    window_.prompts().showError(this, title, QString::fromStdString(error));
    return false;
  }
  if (!summary.empty()) window_.messages()->info(title + ": " + QString::fromStdString(summary));
  return true;
}

// --- commands ---------------------------------------------------------------

scene::AssetId FoliagePanel::generatePlant(const QString& name, const foliage::PlantParams& params) {
  std::string error;
  foliage::PlantStats stats;
  scene::AssetId id = scene::kNoAsset;
  {
    const BusyCursor busy;  // a conifer with its LODs: a fraction of a second
    id = scene::ops::addPlantAsset(doc_, name.toStdString(), params, error, &stats);
  }
  if (id == scene::kNoAsset) {
    report(false, error, {}, {}, "Generate Plant");
    return id;
  }
  const scene::MeshAsset* a = doc_.state().findAsset(id);
  report(true, {}, {},
         std::string("mesh asset \"") + a->name + "\": " + foliage::plantKindName(params.kind) + ", " +
             std::to_string(a->data->triangleCount()) + " triangles, " + std::to_string(a->lods.size() + 1) +
             " levels of detail",
         "Generate Plant");
  return id;
}

bool FoliagePanel::addType(const foliage::FoliageType& type) {
  const scene::ops::FoliageOutcome out = scene::ops::addFoliageType(doc_, type);
  if (!report(out.ok, out.error, out.messages, out.summary, "New Foliage Type")) return false;
  setCurrentType(int(doc_.foliage().store().types().size()) - 1);
  return true;
}

bool FoliagePanel::editType(int index, const foliage::FoliageType& type) {
  if (index < 0) return false;
  const scene::ops::FoliageOutcome out = scene::ops::setFoliageType(doc_, size_t(index), type);
  return report(out.ok, out.error, out.messages, out.summary, "Edit Foliage Type");
}

bool FoliagePanel::scatter(const foliage::TypeSet& types, const Json& values) {
  const foliage::FoliageStore& store = doc_.foliage().store();
  for (uint16_t t : types)
    if (t >= store.types().size()) return report(false, "foliage type " + std::to_string(t) + " does not exist", {}, {}, "Scatter");
  // One type: its rules with the given overrides (checked as the CLI does);
  // several compete by their own rules.
  std::optional<foliage::FoliageType> rules;
  if (types.size() == 1) {
    rules = foliage::scatterRules(store.type(types[0]), values);
    if (const std::vector<std::string> problems = foliage::validate(*rules); !problems.empty())
      return report(false, problems.front(), {}, {}, "Scatter");
  }
  const uint64_t seed = seedOf(values, foliage::foliageScatterOperation());
  std::shared_ptr<const scene::FoliageGround> ground = ground_->shared();
  const std::optional<foliage::Region2> region = foliage::regionFromValues(values);
  const scene::ops::FoliageOutcome out = runFoliageWork(
      &window_, doc_, "Scatter", "Scattering foliage…",
      [ground, types, seed, region, rules](foliage::FoliageStore& copy, const Progress& p) {
        return scene::ops::scatterOnStore(copy, *ground, types, seed, region, rules, 0, &p);
      });
  return report(out.ok, out.error, out.messages, out.summary, "Scatter");
}

bool FoliagePanel::bakeImpostors(bool all) {
  const QString title = "Bake Impostors";
  const std::vector<scene::AssetId> ids = scene::ops::impostorsToBake(doc_.state(), all);
  if (ids.empty())
    return report(true, {}, {}, "every impostor a foliage type draws is stored and current; nothing baked", title);
  // On a worker with a GL context of its own (the viewport's stays with the
  // UI thread), from a copy of the state: assets and materials are shared
  // immutable values. storeImpostors refuses what changed meanwhile.
  const scene::SceneState state = doc_.state();
  auto baked = std::make_shared<std::vector<scene::ops::BakedImpostor>>();
  auto error = std::make_shared<std::string>();
  BackgroundJob job(&window_, title, "Baking impostors…", true, 0);
  job.start([state, ids, baked, error](const Progress& p) {
    render::OffscreenRenderer renderer;
    if (!renderer.initialize(*error)) {
      *error = "cannot start headless OpenGL: " + *error;
      return;
    }
    for (size_t i = 0; i < ids.size() && !p.cancelled(); ++i) {
      p.report(double(i) / double(ids.size()), state.findAsset(ids[i])->name);
      auto images = renderer.renderer().bakeImpostor(state, ids[i], *error);
      if (!images) return;
      baked->emplace_back(ids[i], std::make_shared<const foliage::ImpostorImages>(std::move(*images)));
    }
  });
  job.waitForFinished();
  if (job.cancelRequested()) return report(true, {}, {}, "cancelled; nothing stored", title);
  if (!error->empty() && baked->size() < ids.size()) return report(false, *error, {}, {}, title);
  const scene::ops::StoredImpostors stored = scene::ops::storeImpostors(doc_, *baked);
  return report(stored.stored > 0 || stored.skipped.empty(), stored.skipped.empty() ? "" : stored.skipped.front(),
                stored.skipped, std::to_string(stored.stored) + " impostor(s) baked and stored in the scene", title);
}

bool FoliagePanel::fillLayer(const foliage::TypeSet& types, const Json& values) {
  const OperationDecl& op = foliage::foliageFillOperation();
  const std::string layer = values.value("layer", std::string());
  const double minWeight = values.value("min_weight", defaultNumber(op.param("min_weight")));
  const uint64_t seed = seedOf(values, op);
  std::shared_ptr<const scene::FoliageGround> ground = ground_->shared();
  const std::optional<foliage::Region2> region = foliage::regionFromValues(values);
  // A layer over a whole valley: seconds, on a worker.
  const scene::ops::FoliageOutcome out = runFoliageWork(
      &window_, doc_, "Fill Paint Layer", "Filling the paint layer…",
      [ground, types, layer, minWeight, seed, region](foliage::FoliageStore& copy, const Progress& p) {
        return scene::ops::fillLayerOnStore(copy, *ground, types, layer, minWeight, seed, region, &p);
      });
  return report(out.ok, out.error, out.messages, out.summary, "Fill Paint Layer");
}

bool FoliagePanel::clear(int index) {
  if (index < 0 || size_t(index) >= doc_.foliage().store().types().size()) return false;
  const std::string name = doc_.foliage().store().type(size_t(index)).name;
  const scene::ops::FoliageOutcome out = scene::ops::eraseFoliage(
      doc_, std::nullopt, {uint16_t(index)}, QString("Clear foliage %1").arg(QString::fromStdString(name)));
  return report(out.ok, out.error, out.messages, out.summary, "Clear " + QString::fromStdString(name));
}

// --- with dialogs ---------------------------------------------------------------

void FoliagePanel::requestGeneratePlant() {
  std::string name = "Plant";
  auto taken = [this](const std::string& n) {
    for (const auto& [id, a] : doc_.state().assets)
      if (a.name == n) return true;
    return false;
  };
  for (int i = 2; taken(name); ++i) name = "Plant " + std::to_string(i);
  PlantDialog d(&window_, QString::fromStdString(name));
  if (d.exec() != QDialog::Accepted) return;
  generatePlant(d.name(), d.params());
}

void FoliagePanel::requestNewType() {
  const QStringList meshes = meshNames();
  if (meshes.isEmpty()) {
    window_.prompts().showError(this, "New Foliage Type",
                                "The scene has no mesh asset for a type to draw: Generate Plant… or import a mesh first.");
    return;
  }
  std::string name = "Foliage";
  for (int i = 2; doc_.foliage().store().findType(name) >= 0; ++i) name = "Foliage " + std::to_string(i);
  FoliageTypeDialog d(&window_, meshes, layerNames(), nullptr, QString::fromStdString(name));
  if (d.exec() != QDialog::Accepted) return;
  foliage::FoliageType t;
  std::string error;
  if (d.type(t, error)) addType(t);  // checked by the dialog's OK already
}

void FoliagePanel::requestEditType() {
  const int i = currentType();
  if (i < 0) return;
  const foliage::FoliageType current = doc_.foliage().store().type(size_t(i));
  FoliageTypeDialog d(&window_, meshNames(), layerNames(), &current);
  if (d.exec() != QDialog::Accepted) return;
  foliage::FoliageType t;
  std::string error;
  if (d.type(t, error)) editType(i, t);
}

void FoliagePanel::requestScatter() {
  const std::vector<foliage::FoliageType> types = doc_.foliage().store().types();
  if (types.empty()) return;
  FoliageScatterDialog d(&window_, types, currentType(), layerNames());
  if (d.exec() != QDialog::Accepted) return;
  scatter(d.types(), d.values());
}

void FoliagePanel::requestFillLayer() {
  const std::vector<foliage::FoliageType> types = doc_.foliage().store().types();
  if (types.empty()) return;
  const QStringList layers = layerNames();
  if (layers.isEmpty()) {
    report(false, "the scene has no terrain with paint layers", {}, {}, "Fill Paint Layer");
    return;
  }
  FoliageFillDialog d(&window_, types, currentType(), layers);
  if (d.exec() != QDialog::Accepted) return;
  fillLayer(d.types(), d.values());
}

void FoliagePanel::requestClear() { clear(currentType()); }

bool FoliagePanel::moveSelectionBy(const Json& values) {
  const Json o = values.value("offset_m", Json::array({0.0, 0.0, 0.0}));
  if (!o.is_array() || o.size() != 3) return report(false, "the offset needs three numbers", {}, {}, "Move Foliage");
  const glm::dvec3 offset(o[0].get<double>(), o[1].get<double>(), o[2].get<double>());
  return tool_->moveSelectionBy(offset, !values.value("keep_height", false));
}

void FoliagePanel::requestMoveSelection() {
  if (tool_->selection().empty()) {
    report(false, "nothing selected (the Select or Lasso tool picks instances)", {}, {}, "Move Foliage");
    return;
  }
  FoliageMoveDialog d(&window_, tool_->selection().size());
  if (d.exec() != QDialog::Accepted) return;
  moveSelectionBy(d.values());
}

}  // namespace hs::app
