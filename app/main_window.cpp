#include "app/main_window.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QInputDialog>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QScreen>
#include <QSettings>
#include <QStatusBar>
#include <QStyle>
#include <QTimer>
#include <QToolBar>
#include <QUrl>

#include "app/autosave.h"
#include "app/background_job.h"
#include "app/foliage_panel.h"
#include "app/particles_panel.h"
#include "app/foliage_tool.h"
#include "app/icons.h"
#include "app/import_job.h"
#include "app/message_panel.h"
#include "app/outliner_panel.h"
#include "app/prompts.h"
#include "app/property_panel.h"
#include "app/recent_files.h"
#include "app/selection.h"
#include "app/lights_panel.h"
#include "app/materials_panel.h"
#include "app/settings_panel.h"
#include "app/status_bar.h"
#include "app/timeline_clock.h"
#include "app/terrain_panel.h"
#include "app/terrain_tool.h"
#include "app/viewport_widget.h"
#include "render/renderer.h"
#include "scene/light_units.h"
#include "scene/operations.h"
#include "scene/transform.h"

namespace hs::app {

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  setObjectName("mainWindow");
  setWindowIcon(icon(Icon::Mesh));
  prompts_ = std::make_unique<DialogPrompts>();
  selection_ = new Selection(this);
  // Before the panels: the clock must see each document change first, so a
  // panel refreshing on the same change reads the new animated state.
  clock_ = new TimelineClock(doc_, this);

  viewport_ = new ViewportWidget(doc_, *selection_, this);
  setCentralWidget(viewport_);
  createDocks();
  createTimeline();
  particles_->followClock(clock_);
  createActions();
  createMenus();
  createToolBar();
  createStatusBar();
  setAcceptDrops(true);
  setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks | QMainWindow::AllowNestedDocks);

  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet&) {
    ++revision_;
    selection_->prune(doc_.state());
  });
  connect(&doc_, &scene::Document::modifiedChanged, this, &MainWindow::updateTitle);
  connect(&doc_, &scene::Document::filePathChanged, this, &MainWindow::updateTitle);
  connect(selection_, &Selection::changed, this, &MainWindow::updateSelectionActions);

  connect(viewport_, &ViewportWidget::rendererStarted, this,
          [this](const QString& gl) { messages_->info("OpenGL: " + gl); });
  connect(viewport_, &ViewportWidget::rendererFailed, this,
          [this](const QString& error) { messages_->error("The viewport cannot render: " + error); });
  // OpenGL's debug output (debug builds, HS_GL_DEBUG) and what the renderer
  // refused or clamped (each once) after each frame.
  connect(viewport_, &ViewportWidget::frameRendered, this, [this] {
    for (const std::string& m : viewport_->takeRendererMessages()) messages_->warning(QString::fromStdString(m));
  });

  autosave_ = new Autosave(doc_, this);
  connect(autosave_, &Autosave::saved, this,
          [this] { statusBar()->showMessage("Recovery copy saved", 3000); });
  connect(autosave_, &Autosave::failed, this,
          [this](const QString& error) { messages_->warning("Autosave failed: " + error); });
  autosave_->start();

  // The default arrangement, captured before any saved layout is applied,
  // is what View > Reset Layout returns to.
  const QRect screen = QApplication::primaryScreen() ? QApplication::primaryScreen()->availableGeometry()
                                                       : QRect(0, 0, 1600, 1000);
  resize(std::min(1600, screen.width() * 9 / 10), std::min(1000, screen.height() * 9 / 10));
  // Side widths again now that every dock is in (the timeline's came later).
  if (auto* o = findChild<QDockWidget*>("outlinerDock"), *p = findChild<QDockWidget*>("propertiesDock"); o && p)
    resizeDocks({o, p}, {260, 400}, Qt::Horizontal);
  if (auto* p = findChild<QDockWidget*>("propertiesDock"), *st = findChild<QDockWidget*>("settingsDock"); p && st)
    resizeDocks({p, st}, {600, 260}, Qt::Vertical);  // Properties is the one that grows with a selection
  if (auto* settings = findChild<QDockWidget*>("settingsDock")) settings->raise();  // of the tabs below Properties
  defaultState_ = saveState();
  restoreLayout();
  updateTitle();
  updateSelectionActions();
}

MainWindow::~MainWindow() {
  // Jobs wait for their workers as they go; then this was a clean exit.
  importJob_.reset();
  docJob_.reset();
  autosave_->finishCleanly();
  // doc_ is a member, destroyed before QWidget deletes the children that
  // refer to it, and it signals as it clears its history: silence it, then
  // delete those children while it still exists.
  doc_.disconnect();
  doc_.undoStack()->disconnect();
  delete autosave_;
  for (QDockWidget* d : findChildren<QDockWidget*>()) delete d;
  delete viewport_;
}

void MainWindow::setPrompts(std::unique_ptr<Prompts> prompts) { prompts_ = std::move(prompts); }

void MainWindow::createDocks() {
  auto dock = [this](const QString& title, const QString& name, QWidget* w, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(title, this);
    d->setObjectName(name);  // saveState/restoreState key
    d->setWidget(w);
    d->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                   QDockWidget::DockWidgetClosable);
    addDockWidget(area, d);
    return d;
  };
  outliner_ = new OutlinerPanel(doc_, *selection_, this);
  properties_ = new PropertyPanel(doc_, *selection_, this);
  settings_ = new SettingsPanel(doc_, this);
  post_ = new SettingsPanel(doc_, this, SettingsSection::Post);
  post_->setPrompts([this]() -> Prompts& { return *prompts_; });
  messages_ = new MessagePanel(this);
  QDockWidget* outlinerDock = dock("Outliner", "outlinerDock", outliner_, Qt::LeftDockWidgetArea);
  QDockWidget* propertiesDock = dock("Properties", "propertiesDock", properties_, Qt::RightDockWidgetArea);
  QDockWidget* settingsDock = dock("Scene Settings", "settingsDock", settings_, Qt::RightDockWidgetArea);
  QDockWidget* messagesDock = dock("Messages", "messagesDock", messages_, Qt::BottomDockWidgetArea);
  splitDockWidget(propertiesDock, settingsDock, Qt::Vertical);
  // Post: the post chain, a tab beside Scene Settings.
  tabifyDockWidget(settingsDock, dock("Post", "postDock", post_, Qt::RightDockWidgetArea));
  // Terrain: a tab beside Scene Settings; its brush draws in the viewport.
  terrain_ = new TerrainPanel(*this);
  tabifyDockWidget(settingsDock, dock("Terrain", "terrainDock", terrain_, Qt::RightDockWidgetArea));
  viewport_->setTerrainTool(terrain_->tool());
  // Foliage: a tab beside Terrain; its brush draws in the viewport too.
  foliage_ = new FoliagePanel(*this);
  tabifyDockWidget(settingsDock, dock("Foliage", "foliageDock", foliage_, Qt::RightDockWidgetArea));
  viewport_->setFoliageTool(foliage_->tool());
  // Particles: a tab beside Foliage; the viewport draws them at the playhead.
  particles_ = new ParticlesPanel(*this);
  QDockWidget* particlesDock = dock("Particles", "particlesDock", particles_, Qt::RightDockWidgetArea);
  tabifyDockWidget(settingsDock, particlesDock);
  properties_->setParticlesHook([this, particlesDock](scene::EntityId id) {
    particles_->setCurrentEmitter(id);
    particlesDock->show();
    particlesDock->raise();
  });
  // One brush at a time: the left button cannot sculpt and paint foliage at
  // once. Choosing a tool in one panel turns the other's off (each then
  // emits again with nothing active, which stops there).
  connect(terrain_->tool(), &TerrainTool::settingsChanged, this, [this] {
    if (terrain_->tool()->active()) foliage_->tool()->setKind(FoliageToolKind::Off);
  });
  connect(foliage_->tool(), &FoliageTool::settingsChanged, this, [this] {
    if (foliage_->tool()->active()) terrain_->tool()->setKind(TerrainToolKind::Off);
  });
  // Materials: a tab beside them too, opened from a mesh's properties.
  materials_ = new MaterialsPanel(doc_, this);
  QDockWidget* materialsDock = dock("Materials", "materialsDock", materials_, Qt::RightDockWidgetArea);
  tabifyDockWidget(settingsDock, materialsDock);
  connect(materials_, &MaterialsPanel::problem, this, [this](const QString& m) { messages_->add(MessageLevel::Warning, m); });
  // Lights: every light in one table, a tab beside them as well.
  lights_ = new LightsPanel(doc_, *selection_, this);
  tabifyDockWidget(settingsDock, dock("Lights", "lightsDock", lights_, Qt::RightDockWidgetArea));
  connect(lights_, &LightsPanel::problem, this, [this](const QString& m) { messages_->warning(m); });
  connect(lights_, &LightsPanel::addRequested, this, [this](scene::Light::Type type) {
    createEntity(type == scene::Light::Type::Sun     ? Create::Sun
                 : type == scene::Light::Type::Point ? Create::PointLight
                                                     : Create::SpotLight);
  });
  connect(properties_, &PropertyPanel::problem, this, [this](const QString& m) { messages_->warning(m); });
  properties_->setMaterialsHook([this, materialsDock](scene::AssetId asset) {
    const scene::MeshAsset* a = doc_.state().findAsset(asset);
    if (a && !a->materialSlots.empty()) materials_->select(a->materialSlots.front());
    materialsDock->show();
    materialsDock->raise();
  });
  // The bottom (Timeline, Messages) spans the whole width, as Blender's
  // timeline does: its tool row then never squeezes the side panels.
  setCorner(Qt::BottomLeftCorner, Qt::BottomDockWidgetArea);
  setCorner(Qt::BottomRightCorner, Qt::BottomDockWidgetArea);
  resizeDocks({outlinerDock, propertiesDock}, {270, 360}, Qt::Horizontal);
  resizeDocks({propertiesDock, settingsDock}, {520, 260}, Qt::Vertical);
  resizeDocks({messagesDock}, {150}, Qt::Vertical);
}

void MainWindow::createActions() {
  auto make = [this](const QString& text, const QKeySequence& key, auto slot, const QString& tip = {}) {
    auto* a = new QAction(text, this);
    if (!key.isEmpty()) a->setShortcut(key);
    if (!tip.isEmpty()) a->setStatusTip(tip);
    connect(a, &QAction::triggered, this, slot);
    return a;
  };
  newAct_ = make("&New", QKeySequence::New, [this] { requestNew(); }, "Start a new scene (a sun and a camera)");
  newAct_->setIcon(style()->standardIcon(QStyle::SP_FileIcon));
  openAct_ = make("&Open…", QKeySequence::Open, [this] { requestOpen(); }, "Open a .hscene file");
  openAct_->setIcon(style()->standardIcon(QStyle::SP_DialogOpenButton));
  saveAct_ = make("&Save", QKeySequence::Save, [this] { requestSave(); }, "Save the scene");
  saveAct_->setIcon(style()->standardIcon(QStyle::SP_DialogSaveButton));
  saveAsAct_ = make("Save &As…", QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S), [this] { requestSaveAs(); },
                    "Save the scene under a new name");
  importAct_ = make("&Import Mesh…", QKeySequence(Qt::CTRL | Qt::Key_I), [this] { requestImport(); },
                    "Import a mesh (OBJ, FBX, PLY, glTF, ...) into the scene");
  importAct_->setIcon(icon(Icon::Import));
  exportMeshAct_ = make("&Export Mesh…", QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M), [this] { requestExportMesh(); },
                        "Write a mesh (the selected entity's, or an asset) as OBJ, PLY or GLB");
  repairAct_ = make("Save a &Repaired Copy…", QKeySequence(), [this] { requestRepair(); },
                    "Salvage what can still be read from a damaged scene into a new file");
  quitAct_ = make("&Quit", QKeySequence(Qt::CTRL | Qt::Key_Q), [this] { close(); });
  quitAct_->setMenuRole(QAction::QuitRole);

  undoAct_ = doc_.undoStack()->createUndoAction(this, "&Undo");
  undoAct_->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Z));
  redoAct_ = doc_.undoStack()->createRedoAction(this, "&Redo");
  redoAct_->setShortcuts({QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z), QKeySequence(Qt::CTRL | Qt::Key_Y)});
  deleteAct_ = make("&Delete", QKeySequence(Qt::Key_Delete), [this] { deleteSelection(); },
                    "Delete the selected entities and everything below them");
  duplicateAct_ = make("D&uplicate", QKeySequence(Qt::CTRL | Qt::Key_D), [this] { duplicateSelection(); });
  renameAct_ = make("&Rename", QKeySequence(Qt::Key_F2), [this] { outliner_->renameSelected(); });
  selectAllAct_ = make("Select &All", QKeySequence(Qt::CTRL | Qt::Key_A), [this] {
    selection_->set(doc_.state().depthFirstOrder());
  });
  selectNoneAct_ = make("Select &None", QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_A), [this] { selection_->clear(); });

  frameAct_ = make("&Frame Selected", QKeySequence(Qt::Key_F), [this] { viewport_->frameSelection(); },
                   "Move the view to show the selection (everything if nothing is selected)");
  frameAct_->setIcon(icon(Icon::Frame));
  frameAllAct_ = make("Frame &All", QKeySequence(Qt::Key_Home), [this] { viewport_->frameAll(); });
  gridAct_ = make("Show &Grid", QKeySequence(Qt::SHIFT | Qt::Key_G), [this](bool on) {
    viewport_->setShowGrid(on);
    QSettings().setValue("view/showGrid", on);
  }, "Show the ground grid in the viewport (the scene's own grid setting also applies)");
  gridAct_->setCheckable(true);
  gridAct_->setChecked(QSettings().value("view/showGrid", true).toBool());
  gridAct_->setIcon(icon(Icon::Grid));
  viewport_->setShowGrid(gridAct_->isChecked());
  // Transparency (render/oit.h): translucent fragments per pixel as a heat map.
  depthComplexityAct_ = make("Depth &Complexity", QKeySequence(), [this](bool on) {
    viewport_->setShowDepthComplexity(on);
  }, "Show how many translucent surfaces each pixel sees, blue (one) to red (the most), instead of the scene");
  depthComplexityAct_->setCheckable(true);
  // Huge scans (render/cluster_source.h): which level of the hierarchy draws where.
  clusterLevelsAct_ = make("Cluster &Levels", QKeySequence(), [this](bool on) {
    viewport_->setShowClusterLevels(on);
  }, "Colour the clusters of huge scans by level: green the scan's own triangles, then yellow, orange, red and "
     "magenta for coarser ones");
  clusterLevelsAct_->setCheckable(true);
  clusterLevelsAct_->setObjectName("clusterLevelsAction");
  // The post chain judged: the left half without its effects (render/renderer.h postSplit).
  postSplitAct_ = make("&Post Before/After", QKeySequence(), [this](bool on) { viewport_->setPostSplit(on); },
                       "Show the left half of the viewport without the post effects (grade, LUT, bloom, stylised "
                       "effects...), the right half with them");
  postSplitAct_->setCheckable(true);
  postSplitAct_->setObjectName("postSplitAction");
  resetLayoutAct_ = make("&Reset Layout", QKeySequence(), [this] { resetLayout(); });

  auto* modes = new QActionGroup(this);
  auto mode = [&](const QString& text, Qt::Key key, Icon ic, GizmoMode m, const QString& tip) {
    QAction* a = make(text, QKeySequence(key), [this, m] { setGizmoMode(m); }, tip);
    a->setCheckable(true);
    a->setIcon(icon(ic));
    a->setToolTip(QString("%1 (%2)").arg(QString(text).remove('&'), QKeySequence(key).toString()));
    modes->addAction(a);
    return a;
  };
  selectModeAct_ = mode("&Select", Qt::Key_Q, Icon::Select, GizmoMode::Select, "Select without a gizmo");
  moveAct_ = mode("&Move", Qt::Key_W, Icon::Move, GizmoMode::Translate, "Move the selection");
  rotateAct_ = mode("R&otate", Qt::Key_E, Icon::Rotate, GizmoMode::Rotate, "Rotate the selection");
  scaleAct_ = mode("Sc&ale", Qt::Key_R, Icon::Scale, GizmoMode::Scale, "Scale the selection (along its own axes)");

  QSettings s;
  localAct_ = make("&Local Space", QKeySequence(Qt::Key_X), [this](bool on) {
    viewport_->gizmo().setSpace(on ? GizmoSpace::Local : GizmoSpace::World);
    localAct_->setIcon(icon(on ? Icon::Local : Icon::World));
    localAct_->setToolTip(on ? "Gizmo in local space (X)" : "Gizmo in world space (X)");
    QSettings().setValue("gizmo/local", on);
    viewport_->update();
  }, "Toggle the gizmo between world and local axes");
  localAct_->setCheckable(true);
  snapAct_ = make("S&nap", QKeySequence(), [this](bool on) {
    viewport_->gizmo().snap().enabled = on;
    QSettings().setValue("gizmo/snap", on);
  }, "Snap gizmo moves to the steps beside it (hold Ctrl to invert while dragging)");
  snapAct_->setCheckable(true);
  snapAct_->setIcon(icon(Icon::Snap));
  snapAct_->setToolTip("Snap (hold Ctrl while dragging to invert)");

  // Restore the tool state of the last session.
  const int savedMode = s.value("gizmo/mode", int(GizmoMode::Translate)).toInt();
  setGizmoMode(GizmoMode(std::clamp(savedMode, 0, 3)));
  localAct_->setChecked(s.value("gizmo/local", false).toBool());
  emit localAct_->triggered(localAct_->isChecked());
  snapAct_->setChecked(s.value("gizmo/snap", false).toBool());
  viewport_->gizmo().snap().enabled = snapAct_->isChecked();
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu("&File");
  file->addAction(newAct_);
  file->addAction(openAct_);
  recentMenu_ = file->addMenu("Open &Recent");
  connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::rebuildRecentMenu);
  file->addSeparator();
  file->addAction(saveAct_);
  file->addAction(saveAsAct_);
  file->addSeparator();
  file->addAction(importAct_);
  file->addAction(exportMeshAct_);
  file->addAction(repairAct_);
  QMenu* up = file->addMenu("Import &Up Axis");
  upAxisGroup_ = new QActionGroup(this);
  const int savedUp = QSettings().value("import/upAxis", int(mesh::UpAxis::Auto)).toInt();
  for (auto [text, axis] : {std::pair{"&Automatic (from the file; else Y up)", mesh::UpAxis::Auto},
                            std::pair{"&Y Up (most DCC exports)", mesh::UpAxis::Y},
                            std::pair{"&Z Up (photogrammetry at UTM coordinates)", mesh::UpAxis::Z}}) {
    QAction* a = up->addAction(text);
    a->setCheckable(true);
    a->setData(int(axis));
    a->setChecked(int(axis) == savedUp);
    upAxisGroup_->addAction(a);
  }
  connect(upAxisGroup_, &QActionGroup::triggered, this,
          [](QAction* a) { QSettings().setValue("import/upAxis", a->data().toInt()); });
  file->addSeparator();
  file->addAction(quitAct_);

  QMenu* edit = menuBar()->addMenu("&Edit");
  edit->addAction(undoAct_);
  edit->addAction(redoAct_);
  edit->addSeparator();
  edit->addAction(deleteAct_);
  edit->addAction(duplicateAct_);
  edit->addAction(renameAct_);
  edit->addSeparator();
  edit->addAction(selectAllAct_);
  edit->addAction(selectNoneAct_);
  edit->addSeparator();
  edit->addAction("Autosave &Interval…", this, &MainWindow::editAutosaveInterval);

  QMenu* view = menuBar()->addMenu("&View");
  view->addAction(frameAct_);
  view->addAction(frameAllAct_);
  view->addSeparator();
  view->addAction(gridAct_);
  view->addAction(depthComplexityAct_);
  view->addAction(clusterLevelsAct_);
  view->addAction(postSplitAct_);
  view->addAction(viewport_->focusPickAction());  // depth of field: app/viewport_focus.cpp
  view->addSeparator();
  addTimelineMenus(file, view);
  QMenu* panels = view->addMenu("&Panels");
  for (QDockWidget* d : findChildren<QDockWidget*>()) panels->addAction(d->toggleViewAction());
  view->addSeparator();
  view->addAction(resetLayoutAct_);

  QMenu* create = menuBar()->addMenu("&Create");
  create->addAction(icon(Icon::Empty), "&Empty", this, [this] { createEntity(Create::Empty); });
  create->addAction(icon(Icon::Camera), "&Camera (from View)", this, [this] { createEntity(Create::Camera); });
  create->addAction(icon(Icon::Sun), "&Sun", this, [this] { createEntity(Create::Sun); });
  create->addAction(icon(Icon::PointLight), "&Point Light", this, [this] { createEntity(Create::PointLight); });
  create->addAction(icon(Icon::PointLight), "Sp&ot Light", this, [this] { createEntity(Create::SpotLight); });

  terrain_->populateMenu(menuBar()->addMenu("Te&rrain"));
  foliage_->populateMenu(menuBar()->addMenu("Fo&liage"));
  particles_->populateMenu(menuBar()->addMenu("&Particles"));

  QMenu* tools = menuBar()->addMenu("&Transform");
  tools->addAction(selectModeAct_);
  tools->addAction(moveAct_);
  tools->addAction(rotateAct_);
  tools->addAction(scaleAct_);
  tools->addSeparator();
  tools->addAction(localAct_);
  tools->addAction(snapAct_);

  QMenu* help = menuBar()->addMenu("&Help");
  help->addAction("&Controls", this, &MainWindow::showControls);
  help->addAction("&About Hybridscape", this, &MainWindow::showAbout);

  // Outliner right-click offers the same commands.
  outliner_->setContextActions({renameAct_, duplicateAct_, deleteAct_, frameAct_});
}

void MainWindow::createToolBar() {
  toolBar_ = addToolBar("Tools");
  toolBar_->setObjectName("toolsToolBar");
  toolBar_->setIconSize(QSize(20, 20));
  toolBar_->setMovable(false);
  toolBar_->addAction(newAct_);
  toolBar_->addAction(openAct_);
  toolBar_->addAction(saveAct_);
  toolBar_->addAction(importAct_);
  toolBar_->addSeparator();
  toolBar_->addAction(undoAct_);
  toolBar_->addAction(redoAct_);
  undoAct_->setIcon(style()->standardIcon(QStyle::SP_ArrowBack));
  redoAct_->setIcon(style()->standardIcon(QStyle::SP_ArrowForward));
  toolBar_->addSeparator();
  toolBar_->addAction(selectModeAct_);
  toolBar_->addAction(moveAct_);
  toolBar_->addAction(rotateAct_);
  toolBar_->addAction(scaleAct_);
  toolBar_->addSeparator();
  toolBar_->addAction(localAct_);
  toolBar_->addAction(snapAct_);

  auto spin = [this](const QString& tip, double value, double min, double max, double step, int decimals,
                     const QString& suffix, const char* key, auto apply) {
    auto* s = new QDoubleSpinBox(this);
    s->setToolTip(tip);
    s->setRange(min, max);
    s->setSingleStep(step);
    s->setDecimals(decimals);
    s->setSuffix(suffix);
    s->setValue(QSettings().value(key, value).toDouble());
    s->setFixedWidth(78);
    s->setFocusPolicy(Qt::ClickFocus);
    apply(s->value());
    connect(s, &QDoubleSpinBox::valueChanged, this, [key, apply](double v) {
      apply(v);
      QSettings().setValue(key, v);
    });
    toolBar_->addWidget(s);
    return s;
  };
  SnapSettings& snap = viewport_->gizmo().snap();
  snapMove_ = spin("Move snap step", 1.0, 0.001, 10000.0, 0.1, 3, " m", "gizmo/snapMove",
                   [&snap](double v) { snap.move = v; });
  snapRotate_ = spin("Rotate snap step", 15.0, 0.1, 180.0, 5.0, 1, "°", "gizmo/snapRotate",
                     [&snap](double v) { snap.rotateDeg = v; });
  snapScale_ = spin("Scale snap step", 0.1, 0.001, 10.0, 0.05, 3, "×", "gizmo/snapScale",
                    [&snap](double v) { snap.scale = v; });
  toolBar_->addSeparator();
  toolBar_->addAction(frameAct_);
  toolBar_->addAction(gridAct_);
}

void MainWindow::createStatusBar() {
  statusInfo_ = new StatusBarInfo(this);
  statusBar()->addPermanentWidget(statusInfo_);
  connect(viewport_, &ViewportWidget::frameRendered, statusInfo_, &StatusBarInfo::setFrameStats);
  connect(viewport_, &ViewportWidget::frameRendered, settings_,
          [this](const render::FrameStats& s) { settings_->showTransparencyStats(s.oit); });
  connect(viewport_, &ViewportWidget::flySpeedChanged, statusInfo_, &StatusBarInfo::setFlySpeed);
  statusInfo_->setFlySpeed(viewport_->camera().flySpeed());
  // RSS changes without frames (an import on a worker): poll it slowly.
  auto* memoryTimer = new QTimer(this);
  memoryTimer->setTimerType(Qt::VeryCoarseTimer);
  connect(memoryTimer, &QTimer::timeout, statusInfo_, &StatusBarInfo::refreshMemory);
  memoryTimer->start(2000);
}

void MainWindow::restoreLayout() {
  QSettings s;
  if (s.contains("window/geometry")) restoreGeometry(s.value("window/geometry").toByteArray());
  if (s.contains("window/state")) restoreState(s.value("window/state").toByteArray());
}

void MainWindow::saveLayout() {
  QSettings s;
  s.setValue("window/geometry", saveGeometry());
  s.setValue("window/state", saveState());
}

void MainWindow::resetLayout() {
  restoreState(defaultState_);
  for (QDockWidget* d : findChildren<QDockWidget*>()) {
    d->setFloating(false);
    d->show();
  }
  toolBar_->show();
}

void MainWindow::updateTitle() {
  setWindowTitle(documentTitle() + "[*] — Hybridscape");
  setWindowModified(doc_.isModified());
}

QString MainWindow::documentTitle() const {
  return doc_.filePath().isEmpty() ? untitledName_ : QFileInfo(doc_.filePath()).fileName();
}

void MainWindow::updateSelectionActions() {
  const bool any = !selection_->empty();
  deleteAct_->setEnabled(any);
  duplicateAct_->setEnabled(any);
  renameAct_->setEnabled(any);
}

void MainWindow::setGizmoMode(GizmoMode mode) {
  viewport_->gizmo().setMode(mode);
  QAction* a = mode == GizmoMode::Select ? selectModeAct_
               : mode == GizmoMode::Translate ? moveAct_
               : mode == GizmoMode::Rotate   ? rotateAct_
                                              : scaleAct_;
  a->setChecked(true);
  QSettings().setValue("gizmo/mode", int(mode));
  viewport_->update();
}

std::string MainWindow::uniqueName(const std::string& base) const {
  if (doc_.state().findByName(base) == scene::kNoEntity) return base;
  for (int i = 2;; ++i) {
    const std::string name = base + " " + std::to_string(i);
    if (doc_.state().findByName(name) == scene::kNoEntity) return name;
  }
}

void MainWindow::createEntity(Create what) {
  const render::RenderView view = viewport_->currentView();
  const glm::dvec3 at = viewport_->camera().pivot();
  scene::Transform t;
  t.translation = at;
  scene::EntityId id = scene::kNoEntity;
  switch (what) {
    case Create::Empty: id = scene::ops::addEmpty(doc_, uniqueName("Empty"), t); break;
    case Create::Camera: {
      // From the view: what the user sees becomes a shot.
      t.translation = view.eye;
      t.rotation = view.orientation;
      scene::Camera c;
      c.verticalFovDeg = glm::degrees(view.fovY);
      id = scene::ops::addCamera(doc_, uniqueName("Camera"), t, c);
      break;
    }
    case Create::Sun: {
      t.rotation = scene::fromEulerDegrees({40.0, 0.0, -35.0});
      scene::Light sun;
      sun.castsShadows = true;  // with settings.shadows on, a new sun casts (as in Blender and Unreal)
      id = scene::ops::addLight(doc_, uniqueName("Sun"), t, sun);
      break;
    }
    case Create::PointLight: {
      scene::Light l;
      l.type = scene::Light::Type::Point;
      // As bright as the old default (5 at 1 m in sun units, 2.8 million
      // lumens): it reads in the default daylight exposure within metres.
      l.intensity = float(scene::legacyLightIntensity(scene::Light::Type::Point, 5.0));
      l.range = 20.0f;
      t.translation += glm::dvec3(0.0, 0.0, 1.0);
      id = scene::ops::addLight(doc_, uniqueName("Point Light"), t, l);
      break;
    }
    case Create::SpotLight: {
      // 3 m up, shining straight down (local −Z) in a 45° cone: 450 000 lm
      // are 940 000 cd, about the sun's 100 000 lux where it lands.
      scene::Light l;
      l.type = scene::Light::Type::Spot;
      l.intensity = 4.5e5f;
      l.range = 25.0f;
      t.translation += glm::dvec3(0.0, 0.0, 3.0);
      t.rotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
      id = scene::ops::addLight(doc_, uniqueName("Spot Light"), t, l);
      break;
    }
  }
  selection_->select(id);
}

void MainWindow::deleteSelection() {
  if (selection_->empty()) return;
  scene::ops::remove(doc_, selection_->ids());
}

void MainWindow::duplicateSelection() {
  if (selection_->empty()) return;
  const std::vector<scene::EntityId> copies = scene::ops::duplicate(doc_, selection_->ids());
  if (!copies.empty()) selection_->set(copies);
}

void MainWindow::editAutosaveInterval() {
  bool ok = false;
  const double minutes =
      QInputDialog::getDouble(this, "Autosave", "Save a recovery copy every (minutes, 0 = never):",
                              Autosave::intervalMinutesSetting(), 0.0, 120.0, 1, &ok);
  if (!ok) return;
  Autosave::setIntervalMinutesSetting(minutes);
  autosave_->start();
  messages_->info(minutes > 0 ? QString("Autosave every %1 min").arg(minutes) : QString("Autosave turned off"));
}

void MainWindow::showControls() {
  QMessageBox box(this);
  box.setWindowTitle("Viewport Controls");
  box.setTextFormat(Qt::RichText);
  box.setText(
      "<table cellpadding=3>"
      "<tr><td><b>Right mouse + W A S D</b></td><td>fly (Q/E down/up, Shift faster, wheel: speed)</td></tr>"
      "<tr><td><b>Alt + left mouse</b></td><td>orbit around the pivot</td></tr>"
      "<tr><td><b>Middle mouse</b> (or Alt + middle)</td><td>pan</td></tr>"
      "<tr><td><b>Wheel</b> / Alt + right mouse</td><td>dolly towards the pivot</td></tr>"
      "<tr><td><b>Click</b></td><td>select (Shift adds, Ctrl toggles)</td></tr>"
      "<tr><td><b>Q W E R</b></td><td>select / move / rotate / scale gizmo</td></tr>"
      "<tr><td><b>X</b></td><td>world / local gizmo axes</td></tr>"
      "<tr><td><b>Ctrl while dragging</b></td><td>invert snapping</td></tr>"
      "<tr><td><b>Esc while dragging</b></td><td>cancel the drag</td></tr>"
      "<tr><td><b>F</b> / Home</td><td>frame selection / everything</td></tr>"
      "</table>");
  box.exec();
}

void MainWindow::showAbout() {
  QMessageBox::about(this, "About Hybridscape",
                     QString("<b>Hybridscape</b> %1<br>Authoring large outdoor scenes for stereo films.<br><br>"
                             "Qt %2<br>OpenGL: %3")
                         .arg(QCoreApplication::applicationVersion(), qVersion(),
                              viewport_->glDescription().isEmpty() ? QString("not available")
                                                                   : viewport_->glDescription()));
}

namespace {

// The local file a drag carries, if it is one the editor can take.
QString droppableFile(const QMimeData* mime) {
  if (!mime || !mime->hasUrls() || mime->urls().size() != 1 || !mime->urls().first().isLocalFile()) return {};
  const QString path = mime->urls().first().toLocalFile();
  const QString suffix = "." + QFileInfo(path).suffix().toLower();
  if (suffix == ".hscene") return path;
  for (const std::string& ext : mesh::supportedExtensions())
    if (suffix == QString::fromStdString(ext)) return path;
  return {};
}

}  // namespace

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
  if (!isBusy() && !droppableFile(e->mimeData()).isEmpty()) e->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* e) {
  const QString path = droppableFile(e->mimeData());
  if (path.isEmpty() || isBusy()) return;
  e->acceptProposedAction();
  // Not inside the drop: the questions and the progress dialog need the
  // drag to be over.
  QTimer::singleShot(0, this, [this, path] {
    if (path.endsWith(".hscene", Qt::CaseInsensitive)) {
      if (maybeSave()) openSceneFile(path, false);
    } else {
      importMeshFile(path, false);
    }
  });
}

void MainWindow::closeEvent(QCloseEvent* e) {
  if (importJob_ && importJob_->isRunning()) {
    importJob_->cancel();
    importJob_->waitForFinished();
  }
  // A save cannot be cancelled (it is one transaction); let it finish.
  if (docJob_ && docJob_->isRunning()) {
    docJob_->cancel();
    docJob_->waitForFinished();
  }
  if (!maybeSave()) {
    e->ignore();
    return;
  }
  saveLayout();
  autosave_->finishCleanly();
  e->accept();
}

}  // namespace hs::app
