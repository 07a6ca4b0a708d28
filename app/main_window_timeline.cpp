// MainWindow's timeline side: the clock (current frame, playback), keying
// (key buttons in Properties, keys that follow edits, Auto Key), the Timeline
// dock, the viewport's animated view and stereo preview, camera paths (the
// Camera Path dock, path points in the viewport, the timeline's Follow
// Path), and File > Export Frames…. Kept apart from main_window.cpp, which
// builds the rest of the window.
#include <QAction>
#include <QActionGroup>
#include <QDockWidget>
#include <QInputDialog>
#include <QLayout>
#include <QMenu>

#include <set>

#include "app/camera_path_panel.h"
#include "app/export_dialog.h"
#include "app/form_widgets.h"
#include "app/lights_panel.h"
#include "app/main_window.h"
#include "app/materials_panel.h"
#include "app/message_panel.h"
#include "app/path_editor.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/settings_panel.h"
#include "app/stereo_preview.h"
#include "app/timeline_clock.h"
#include "app/timeline_keying.h"
#include "app/timeline_cut_track.h"
#include "app/timeline_panel.h"
#include "app/viewport_widget.h"
#include "scene/sequence_edits.h"
#include "sequencer/binding_target.h"

namespace hs::app {

void MainWindow::createTimeline() {
  keying_ = new Keying(doc_, *clock_, this);  // clock_ is made first, in the constructor
  stereo_ = new StereoPreviewSettings(this);
  viewport_->setTimeline(clock_, stereo_);

  // Properties show the scene at the current time, with a key button beside
  // each animatable field; edits of animated fields (or any, with Auto Key)
  // set keys in the same undo step.
  properties_->setStateSource([this]() -> const scene::SceneState& { return clock_->state(); });
  properties_->setRowDecorator([this](const std::string& path, QWidget* editor, QWidget* parent) -> QWidget* {
    std::string error;
    if (!scene::animationTarget(path, error)) return editor;
    QWidget* row = editorRow(parent, editor);
    row->layout()->addWidget(new KeyButton(*keying_, *selection_, *clock_, path, row));
    return row;
  });
  properties_->setEditedHook([this](const std::vector<scene::EntityId>& ids, const std::string& path, const QString& key) {
    keying_->afterEdit(ids, {path}, key);
  });
  connect(clock_, &TimelineClock::frameChanged, properties_, &PropertyPanel::refreshValues);
  // The same for material fields and the scene settings (scene/object_tracks.h).
  materials_->enableKeying(*keying_, *clock_);
  settings_->enableKeying(*keying_, *clock_);
  post_->enableKeying(*keying_, *clock_);
  lights_->setStateSource([this]() -> const scene::SceneState& { return clock_->state(); });
  lights_->setEditedHook([this](scene::EntityId id, const std::string& path, const QString& key) {
    keying_->afterEdit({id}, {path}, key);
  });
  connect(clock_, &TimelineClock::stateChanged, lights_, &LightsPanel::refreshValues);
  lights_->enableKeying(*keying_, *clock_);
  connect(viewport_, &ViewportWidget::transformsEdited, keying_,
          [this](const std::vector<scene::EntityId>& ids, const std::vector<std::string>& fields, const QString& key) {
            keying_->afterEdit(ids, fields, key);
          });
  // Focus picking (depth of field) keys the focus like a Properties edit.
  connect(viewport_, &ViewportWidget::focusPicked, keying_, [this](scene::EntityId camera, const QString& key) {
    keying_->afterEdit({camera}, {"camera.focus_distance_m"}, key);
  });

  timeline_ = new TimelinePanel(doc_, *clock_, *keying_, *selection_, *stereo_, this);
  // A material's or the settings' row shows that object in its dock.
  connect(timeline_->dopeSheet(), &TimelineDopeSheet::objectActivated, this, [this](uint64_t target) {
    const bool material = sequencer::targetKind(target) == sequencer::TargetKind::Material;
    if (material) materials_->select(scene::MaterialId(sequencer::targetMaterial(target)));
    if (auto* d = findChild<QDockWidget*>(material ? "materialsDock" : "settingsDock")) {
      d->show();
      d->raise();
    }
  });
  auto* dock = new QDockWidget("Timeline", this);
  dock->setObjectName("timelineDock");
  dock->setWidget(timeline_);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable | QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::BottomDockWidgetArea, dock);
  // Messages and Timeline share the bottom as tabs (as Unreal's Output Log
  // and Sequencer do): side by side, the timeline's tool row and the
  // messages' width forced the window wider than a 1600-pixel screen and
  // squeezed the Outliner and Properties. The Messages tab names its
  // warnings and errors, and an error brings it to the front.
  if (QDockWidget* messages = findChild<QDockWidget*>("messagesDock")) {
    tabifyDockWidget(messages, dock);
    // The rows it showed before the tab bar came, and the camera-cut strip over them.
    resizeDocks({dock}, {260 + TimelineCutTrack::kHeight}, Qt::Vertical);
    dock->raise();
    connect(messages_, &MessagePanel::countsChanged, messages, [this, messages] {
      const int w = messages_->count(MessageLevel::Warning), e = messages_->count(MessageLevel::Error);
      QStringList parts;
      if (w) parts << tr("%n warning(s)", nullptr, w);
      if (e) parts << tr("%n error(s)", nullptr, e);
      messages->setWindowTitle(parts.isEmpty() ? tr("Messages") : tr("Messages (%1)").arg(parts.join(", ")));
      if (e > errorsShown_) messages->raise();
      errorsShown_ = e;
    });
  }
  createCameraPathDock();

  // What the timeline cannot apply (a track for a missing entity, an aim at
  // nothing), each message once.
  connect(clock_, &TimelineClock::stateChanged, this, [this] {
    static std::set<std::string> reported;
    clock_->state();
    for (const std::string& w : clock_->warnings())
      if (reported.insert(w).second) messages_->warning("Timeline: " + QString::fromStdString(w));
  });
}

void MainWindow::createCameraPathDock() {
  pathEditor_ = new PathEditor(doc_, *clock_, *selection_, this);
  viewport_->setPathEditor(pathEditor_);
  connect(pathEditor_, &PathEditor::problem, messages_, &MessagePanel::warning);
  cameraPath_ = new CameraPathPanel(*pathEditor_, [this] { return viewport_->currentView().eye; }, this);
  auto* dock = new QDockWidget("Camera Path", this);
  dock->setObjectName("cameraPathDock");
  dock->setWidget(cameraPath_);
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable | QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  // Beside Scene Settings (a tab), so the Properties above stay in view.
  if (QDockWidget* settings = findChild<QDockWidget*>("settingsDock")) tabifyDockWidget(settings, dock);
  connect(timeline_, &TimelinePanel::followPathRequested, this, [this, dock] {
    if (pathEditor_->entity() != scene::kNoEntity && !pathEditor_->path()) pathEditor_->createAhead();
    dock->show();
    dock->raise();
  });
}

ExportDialog* MainWindow::exportDialog() {
  if (!exportDialog_) {
    exportDialog_ = new ExportDialog(doc_, *stereo_, this);
    connect(exportDialog_, &ExportDialog::exportFinished, this, [this](const QString& message, bool ok) {
      if (ok) messages_->info(message);
      else messages_->error(message);
    });
  }
  return exportDialog_;
}

void MainWindow::addTimelineMenus(QMenu* file, QMenu* view) {
  auto* exportAct = new QAction("&Export Frames…", this);
  exportAct->setShortcut(QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_E));
  exportAct->setStatusTip("Render the timeline's frames as a stereo image sequence or a film");
  connect(exportAct, &QAction::triggered, this, [this] {
    ExportDialog* d = exportDialog();
    d->resetFromDocument();
    d->show();
    d->raise();
    d->activateWindow();
  });
  file->insertAction(quitAct_, exportAct);
  file->insertSeparator(quitAct_);

  QMenu* stereo = view->addMenu("&Stereo Preview");
  auto* group = new QActionGroup(this);
  for (auto m : {StereoPreviewMode::Off, StereoPreviewMode::Left, StereoPreviewMode::Right,
                 StereoPreviewMode::SideBySide, StereoPreviewMode::Anaglyph}) {
    QAction* a = stereo->addAction(StereoPreviewSettings::modeName(m), this, [this, m] { stereo_->setMode(m); });
    a->setCheckable(true);
    a->setChecked(m == stereo_->mode());
    a->setData(int(m));
    group->addAction(a);
  }
  connect(stereo_, &StereoPreviewSettings::changed, group, [this, group] {
    for (QAction* a : group->actions()) a->setChecked(a->data().toInt() == int(stereo_->mode()));
  });
  stereo->addSeparator();
  stereo->addAction("Comfort &Budget…", this, [this] {
    const sequencer::ComfortBudget b = stereo_->budget();
    bool ok = false;
    const QString text = QInputDialog::getText(
        this, "Comfort Budget", "Parallax allowed, in percent of the image width: nearest (in front), farthest (behind)",
        QLineEdit::Normal, QString("%1,%2").arg(b.nearest * 100.0).arg(b.farthest * 100.0), &ok);
    if (!ok) return;
    const QStringList parts = text.split(',');
    bool a = false, c = false;
    const double n = parts.value(0).trimmed().toDouble(&a), f = parts.value(1).trimmed().toDouble(&c);
    if (parts.size() != 2 || !a || !c || n > 0.0 || f < 0.0) {
      messages_->warning("Comfort budget '" + text + "' is not NEAREST,FARTHEST with NEAREST <= 0 <= FARTHEST (e.g. -1,2)");
      return;
    }
    stereo_->setBudget({n / 100.0, f / 100.0});
  });

  auto* play = view->addAction("&Play / Pause", this, [this] { clock_->togglePlay(); });
  play->setShortcut(QKeySequence(Qt::Key_Space));
  play->setStatusTip("Play the timeline at its frame rate");
  view->addSeparator();
}

}  // namespace hs::app
