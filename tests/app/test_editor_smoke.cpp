// GUI smoke test of the editor: import, edit, undo/redo, pick, gizmo drag,
// save, reopen, unsaved-changes questions, bad input and crash recovery,
// all through the code paths the menus and the mouse use. Dialogs are
// answered by RecordingPrompts so nothing can wait for a click.
#include <cmath>

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QMimeData>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QLabel>
#include <QRegularExpression>
#include <QTest>
#include <QMenu>
#include <QToolButton>
#include <QTreeView>
#include <QWheelEvent>

#include "app/app_settings.h"
#include "app/autosave.h"
#include "app/field_editors.h"
#include "app/gizmo.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/outliner_model.h"
#include "app/outliner_panel.h"
#include "app/prompts.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/settings_panel.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "mesh/mesh_import.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/transform.h"
#include "scene/world_bounds.h"

using namespace hs;
using hs::app::MainWindow;

namespace {

class RecordingPrompts : public app::Prompts {
 public:
  SaveChoice saveAnswer = SaveChoice::Cancel;
  bool yesNoAnswer = false;
  int saveQuestions = 0;
  int yesNoQuestions = 0;
  QStringList errors;

  SaveChoice askSaveChanges(QWidget*, const QString&) override {
    ++saveQuestions;
    return saveAnswer;
  }
  void showError(QWidget*, const QString& title, const QString& text) override { errors << title + ": " + text; }
  bool askYesNo(QWidget*, const QString&, const QString&, const QString&, const QString&) override {
    ++yesNoQuestions;
    return yesNoAnswer;
  }
  QString askOpenFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
  QString askSaveFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
};

scene::EntityId findByName(const scene::SceneState& s, const std::string& name) { return s.findByName(name); }

}  // namespace

class EditorSmokeTest : public QObject {
  Q_OBJECT
 public:
  // Runs before QApplication exists (QTEST_MAIN calls it).
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase();
  void startsWithDemoScene();
  void importBunny();
  void propertyEditIsOneUndoStepAndUndoIsExact();
  void refusedPropertyValueReachesMessages();
  void componentsAddAndRemoveAreUndoable();
  void gizmoDragMovesAlongAxisAsOneUndoStep();
  void clickPicksTheBunny();
  void cameraFlyOrbitDollyAndIdle();
  void saveAndReopen();
  void unsavedChangesAreAskedAbout();
  void outlinerDropReparentsKeepingWorldPlace();
  void sceneSettingsEditIsUndoable();
  void spotLightAndFogFromTheEditor();
  void badImportReportsAndChangesNothing();
  void badOpenKeepsTheDocument();
  void autosaveAndRecovery();
  void cleanupTestCase();

 private:
  scene::Document& doc() { return w_->document(); }
  const scene::Entity& bunny() { return *doc().state().find(bunny_); }

  std::unique_ptr<MainWindow> w_;
  RecordingPrompts* prompts_ = nullptr;
  QTemporaryDir tmp_;
  scene::EntityId bunny_ = scene::kNoEntity;
  const QString bunnyPath_ = QString(HS_SOURCE_DIR) + "/resources/demo/stanford-bunny.obj";
};

void EditorSmokeTest::initTestCase() {
  app::initApplicationSettings();
  QVERIFY(app::settingsSandboxed());
  QVERIFY(tmp_.isValid());
  w_ = std::make_unique<MainWindow>();
  auto prompts = std::make_unique<RecordingPrompts>();
  prompts_ = prompts.get();
  w_->setPrompts(std::move(prompts));
  w_->resize(1100, 760);  // small enough that llvmpipe frames stay quick
  w_->loadDemoScene();
  w_->show();
  QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->framesRendered() > 0 || !w_->viewport()->rendererError().isEmpty(), 30000);
  QVERIFY2(w_->viewport()->rendererReady(), qPrintable(w_->viewport()->rendererError()));
}

void EditorSmokeTest::startsWithDemoScene() {
  QVERIFY(findByName(doc().state(), "Stanford Bunny") != scene::kNoEntity);
  QVERIFY(!doc().state().assets.empty());
  QVERIFY(!doc().isModified());
  QVERIFY(doc().filePath().isEmpty());
  QVERIFY(w_->windowTitle().startsWith("Demo"));
  QCOMPARE(w_->viewport()->lastStats().trianglesDrawn > 0, true);
  // Hovering the frame time lists the passes that ran, with a GPU time once
  // a frame has measured them (the first frame does).
  auto* frameLabel = w_->findChild<QLabel*>("statusFrame");
  QVERIFY(frameLabel);
  QTRY_VERIFY2(frameLabel->toolTip().contains("<td>opaque</td>"), qPrintable(frameLabel->toolTip()));
  QVERIFY(frameLabel->toolTip().contains("<td>tonemap</td>"));
  QVERIFY(frameLabel->toolTip().contains(
      QRegularExpression("<td>opaque</td><td align=right>[0-9.]+</td><td align=right>[0-9.]+</td>")));
  // The demo's spot light is in view: the clustered light list says so.
  size_t localLights = 0;
  for (const auto& [id, e] : doc().state().entities)
    if (e.light && e.light->type != scene::Light::Type::Sun) ++localLights;
  QVERIFY(localLights > 0);
  const size_t inView = w_->viewport()->lastStats().lightsInView;
  QVERIFY2(inView > 0 && inView <= localLights, qPrintable(QString::number(inView)));
  QVERIFY2(frameLabel->toolTip().contains(QString("%1 point/spot lights in view").arg(inView)),
           qPrintable(frameLabel->toolTip()));
  // File > New with nothing to save asks nothing and gives the starter scene.
  w_->requestNew();
  QCOMPARE(prompts_->saveQuestions, 0);
  QCOMPARE(doc().state().entities.size(), size_t(2));  // a sun and a camera
  QVERIFY(doc().state().assets.empty());
}

void EditorSmokeTest::importBunny() {
  const size_t entitiesBefore = doc().state().entities.size();
  const int stepsBefore = doc().undoStack()->count();
  mesh::ImportResult reference = mesh::importMesh(bunnyPath_.toStdString(), w_->importOptions());
  QVERIFY(reference.ok());

  QVERIFY(w_->importMeshFile(bunnyPath_, true));

  QCOMPARE(doc().state().entities.size(), entitiesBefore + 1);
  QCOMPARE(doc().undoStack()->count(), stepsBefore + 1);  // one undo step
  bunny_ = findByName(doc().state(), "stanford-bunny");
  QVERIFY(bunny_ != scene::kNoEntity);
  QVERIFY(bunny().mesh.has_value());
  const scene::MeshAsset* asset = doc().state().findAsset(bunny().mesh->mesh);
  QVERIFY(asset && asset->data);
  QCOMPARE(asset->data->triangleCount(), reference.mesh->triangleCount());
  QVERIFY(asset->data->triangleCount() > 1000);
  // Selected, and the user was told.
  QCOMPARE(w_->selection().primary(), bunny_);
  QVERIFY(w_->messages()->lastText().contains("stanford-bunny.obj"));
  QVERIFY(doc().isModified());
  QVERIFY(w_->isWindowModified());
  // The outliner shows it (after its deferred rebuild).
  QTRY_VERIFY(w_->outliner()->model()->indexOf(bunny_).isValid());
  // Framed: the bunny's centre is in view.
  QPoint p;
  QVERIFY(w_->viewport()->projectToWidget(scene::worldBounds(doc().state(), {bunny_}).centre(), p));
}

void EditorSmokeTest::propertyEditIsOneUndoStepAndUndoIsExact() {
  QCOMPARE(w_->selection().primary(), bunny_);
  auto* spin = w_->properties()->findChild<app::ScrubSpinBox*>("transform.translation.x");
  QVERIFY(spin);
  const scene::Transform before = bunny().transform;
  const int steps = doc().undoStack()->count();

  // One gesture (typing, then correcting) = one undo step.
  spin->setValue(before.translation.x + 0.5);
  spin->setValue(before.translation.x + 1.25);
  emit spin->editingFinished();
  QCOMPARE(doc().undoStack()->count(), steps + 1);
  const glm::dvec3 moved = bunny().transform.translation;
  QCOMPARE(moved.x, spin->value());
  // What the spin box shows is what the document holds: the typed value to
  // the displayed precision.
  QVERIFY(std::abs(moved.x - (before.translation.x + 1.25)) <= 0.5 * std::pow(10.0, -spin->decimals()) + 1e-12);
  QCOMPARE(moved.y, before.translation.y);
  QCOMPARE(moved.z, before.translation.z);

  // The next gesture is a step of its own.
  spin->setValue(moved.x + 1.0);
  emit spin->editingFinished();
  QCOMPARE(doc().undoStack()->count(), steps + 2);
  doc().undoStack()->undo();
  QVERIFY(bunny().transform.translation == moved);

  doc().undoStack()->undo();
  QVERIFY(bunny().transform == before);  // exactly, every component
  QCOMPARE(spin->value(), spin->valueFromText(spin->textFromValue(before.translation.x)));  // the panel follows
  doc().undoStack()->redo();
  QVERIFY(bunny().transform.translation == moved);
}

// A value the field's rule refuses is not applied, and Messages says why
// (was: the panel silently showed the old value again).
void EditorSmokeTest::refusedPropertyValueReachesMessages() {
  w_->selection().select(bunny_);
  auto* spin = w_->properties()->findChild<app::ScrubSpinBox*>("transform.scale.y");
  QVERIFY(spin);
  const scene::Transform before = bunny().transform;
  const int steps = doc().undoStack()->count();
  const int warnings = w_->messages()->count(app::MessageLevel::Warning);
  spin->setValue(0.0);
  emit spin->editingFinished();
  QVERIFY(bunny().transform == before);
  QCOMPARE(doc().undoStack()->count(), steps);
  QCOMPARE(w_->messages()->count(app::MessageLevel::Warning), warnings + 1);
  const QString text = w_->messages()->lastText();
  QVERIFY2(text.contains(QString::fromStdString(bunny().name) + ": Scale") && text.contains("must be non-zero") &&
               text.contains("not applied"),
           qPrintable(text));
}

void EditorSmokeTest::componentsAddAndRemoveAreUndoable() {
  w_->selection().select(bunny_);
  auto* add = w_->properties()->findChild<QToolButton*>("addComponent");
  QVERIFY(add && add->menu());
  QAction* camera = nullptr;
  for (QAction* a : add->menu()->actions())
    if (a->text() == "Camera") camera = a;
  QVERIFY(camera);
  const int steps = doc().undoStack()->index();
  camera->trigger();
  QVERIFY(bunny().camera.has_value());
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  // The panel now shows the camera's fields and offers to remove it.
  QVERIFY(w_->properties()->editorFor("camera.fov_deg"));
  QTRY_VERIFY(w_->properties()->findChild<QToolButton*>("remove_camera"));
  QToolButton* remove = w_->properties()->findChild<QToolButton*>("remove_camera");
  remove->click();
  QVERIFY(!bunny().camera.has_value());
  QCOMPARE(doc().undoStack()->index(), steps + 2);
  doc().undoStack()->undo();
  QVERIFY(bunny().camera.has_value());
  doc().undoStack()->undo();
  QVERIFY(!bunny().camera.has_value());
  QVERIFY(bunny().mesh.has_value());
}

void EditorSmokeTest::gizmoDragMovesAlongAxisAsOneUndoStep() {
  app::ViewportWidget* vp = w_->viewport();
  vp->gizmo().setMode(app::GizmoMode::Translate);
  vp->gizmo().setSpace(app::GizmoSpace::World);
  vp->gizmo().snap().enabled = false;
  w_->selection().select(bunny_);
  vp->frameSelection();
  const render::RenderView view = vp->currentView();
  app::GizmoFrame f;
  QVERIFY(vp->gizmo().frame(doc().state(), w_->selection().ids(), view, f));
  // Grab the X arrow two thirds along and drag it along its own screen direction.
  const glm::dvec3 grabWorld = f.origin + f.axes[0] * (0.66 * f.length);
  const glm::dvec3 tipWorld = f.origin + f.axes[0] * (1.0 * f.length);
  QPoint grab, tip;
  QVERIFY(vp->projectToWidget(grabWorld, grab));
  QVERIFY(vp->projectToWidget(tipWorld, tip));
  QCOMPARE(vp->gizmo().hitTest(doc().state(), w_->selection().ids(), view, glm::dvec2(grab.x() + 0.5, grab.y() + 0.5)),
           app::GizmoHandle::X);

  const scene::Transform before = bunny().transform;
  const int steps = doc().undoStack()->index();
  const QPoint dir = tip - grab;
  QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, grab);
  QVERIFY(vp->gizmo().dragging());
  for (int i = 1; i <= 6; ++i) QTest::mouseMove(vp, grab + dir * i);
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, grab + dir * 6);
  QVERIFY(!vp->gizmo().dragging());

  const glm::dvec3 after = bunny().transform.translation;
  QCOMPARE(doc().undoStack()->index(), steps + 1);  // the whole drag is one step
  QCOMPARE(doc().undoStack()->count(), steps + 1);
  // Six times the grab-to-tip distance along +X (a third of the handle each):
  // about 2 handle lengths, pixel rounding aside.
  QVERIFY2(after.x - before.translation.x > 1.5 * f.length && after.x - before.translation.x < 2.5 * f.length,
           qPrintable(QString("moved %1, handle %2").arg(after.x - before.translation.x).arg(f.length)));
  QCOMPARE(after.y, before.translation.y);
  QCOMPARE(after.z, before.translation.z);
  QVERIFY(bunny().transform.rotation == before.rotation);

  doc().undoStack()->undo();
  QVERIFY(bunny().transform == before);
  doc().undoStack()->redo();
  QVERIFY(bunny().transform.translation == after);

  // Esc during a drag puts everything back and leaves no undo step.
  vp->frameSelection();
  const render::RenderView view2 = vp->currentView();
  QVERIFY(vp->gizmo().frame(doc().state(), w_->selection().ids(), view2, f));
  QVERIFY(vp->projectToWidget(f.origin + f.axes[0] * (0.66 * f.length), grab));
  QVERIFY(vp->projectToWidget(f.origin + f.axes[0] * (1.0 * f.length), tip));
  const scene::Transform beforeCancel = bunny().transform;
  const int stepsBeforeCancel = doc().undoStack()->index();
  QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, grab);
  QTest::mouseMove(vp, tip + (tip - grab) * 3);
  QVERIFY(!(bunny().transform == beforeCancel));
  QTest::keyClick(vp, Qt::Key_Escape);
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, tip);
  QVERIFY(bunny().transform == beforeCancel);
  QCOMPARE(doc().undoStack()->index(), stepsBeforeCancel);
  QCOMPARE(doc().undoStack()->count(), stepsBeforeCancel);
}

void EditorSmokeTest::clickPicksTheBunny() {
  app::ViewportWidget* vp = w_->viewport();
  vp->frameSelection();
  // Select mode: with the move gizmo its centre handle would take the click.
  vp->gizmo().setMode(app::GizmoMode::Select);
  w_->selection().clear();
  QPoint centre;
  QVERIFY(vp->projectToWidget(scene::worldBounds(doc().state(), {bunny_}).centre(), centre));
  QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, centre);
  QCOMPARE(w_->selection().primary(), bunny_);
  QCOMPARE(w_->selection().size(), size_t(1));
  // Ctrl-click toggles it off again; a click on the sky clears.
  QTest::mouseClick(vp, Qt::LeftButton, Qt::ControlModifier, centre);
  QVERIFY(w_->selection().empty());
  QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, centre);
  QCOMPARE(w_->selection().primary(), bunny_);
  QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, QPoint(4, 4));
  QVERIFY(w_->selection().empty());
  // The outliner follows the shared selection.
  w_->selection().select(bunny_);
  const QModelIndexList rows = w_->outliner()->view()->selectionModel()->selectedRows();
  QCOMPARE(rows.size(), 1);
  QCOMPARE(w_->outliner()->model()->idOf(rows.first()), bunny_);
  vp->gizmo().setMode(app::GizmoMode::Translate);
}

void EditorSmokeTest::cameraFlyOrbitDollyAndIdle() {
  app::ViewportWidget* vp = w_->viewport();
  vp->gizmo().setMode(app::GizmoMode::Translate);
  const QPoint c = vp->rect().center();

  // Fly: right mouse held + E (up) and W (forward). The keys steer the
  // camera instead of switching gizmo tools while flying.
  // Each key is held until the camera has moved (a loaded machine may take
  // long for the first frame), so the test does not depend on timing.
  const render::RenderView v0 = vp->currentView();
  QTest::mousePress(vp, Qt::RightButton, Qt::NoModifier, c);
  QTest::keyPress(vp, Qt::Key_W);
  QTRY_VERIFY_WITH_TIMEOUT(glm::dot(vp->currentView().eye - v0.eye, v0.forward()) > 1e-3, 10000);
  QTest::keyRelease(vp, Qt::Key_W);
  QTest::qWait(50);
  const render::RenderView vw = vp->currentView();
  QTest::keyPress(vp, Qt::Key_E);
  QTRY_VERIFY_WITH_TIMEOUT(vp->currentView().eye.z - vw.eye.z > 1e-3, 10000);
  QTest::keyRelease(vp, Qt::Key_E);
  QTest::mouseRelease(vp, Qt::RightButton, Qt::NoModifier, c);
  QTest::qWait(50);
  const render::RenderView v1 = vp->currentView();
  QCOMPARE(vp->gizmo().mode(), app::GizmoMode::Translate);
  QVERIFY2(glm::dot(vw.eye - v0.eye, v0.forward()) > 0.0, "W flies forward");
  const glm::dvec3 up = v1.eye - vw.eye;
  QVERIFY2(up.z > 0.0 && glm::length(glm::dvec2(up)) < 1e-9 * (1.0 + up.z), "E flies straight up");
  QVERIFY(v1.orientation == v0.orientation);  // no mouse movement: no turn

  // Idle: nothing moves, nothing is drawn.
  QTest::qWait(100);
  const int frames = vp->framesRendered();
  QTest::qWait(300);
  QCOMPARE(vp->framesRendered(), frames);

  // Orbit (Alt + left drag) turns around the pivot at a fixed distance.
  const glm::dvec3 pivot = vp->camera().pivot();
  const double distance = vp->camera().pivotDistance();
  QTest::mousePress(vp, Qt::LeftButton, Qt::AltModifier, c);
  QTest::mouseMove(vp, c + QPoint(60, 20));
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::AltModifier, c + QPoint(60, 20));
  const render::RenderView v2 = vp->currentView();
  QVERIFY(glm::length(v2.eye - v1.eye) > 1e-6 * distance);
  QVERIFY(glm::length(vp->camera().pivot() - pivot) < 1e-9 * std::max(1.0, glm::length(pivot)) + 1e-9);
  QVERIFY(std::abs(glm::length(pivot - v2.eye) - distance) < 1e-9 * distance);

  // Wheel dollies towards the pivot.
  QWheelEvent wheel(QPointF(c), vp->mapToGlobal(QPointF(c)), QPoint(), QPoint(0, 120), Qt::NoButton, Qt::NoModifier,
                    Qt::NoScrollPhase, false);
  QApplication::sendEvent(vp, &wheel);
  QVERIFY(vp->camera().pivotDistance() < distance);
  QVERIFY(glm::length(vp->camera().pivot() - pivot) < 1e-9 * std::max(1.0, glm::length(pivot)) + 1e-9);
  vp->frameSelection();
}

void EditorSmokeTest::saveAndReopen() {
  const QString path = tmp_.filePath("smoke.hscene");
  const glm::dvec3 position = bunny().transform.translation;
  const size_t entities = doc().state().entities.size();
  const size_t triangles = doc().state().findAsset(bunny().mesh->mesh)->data->triangleCount();
  QVERIFY(doc().isModified());

  QVERIFY(w_->saveSceneTo(path, true));
  QVERIFY(!doc().isModified());
  QCOMPARE(doc().filePath(), QFileInfo(path).absoluteFilePath());
  QVERIFY(w_->windowTitle().startsWith("smoke.hscene"));
  QVERIFY(!w_->isWindowModified());

  // A save that cannot be written says so and leaves the document modified.
  scene::ops::rename(doc(), bunny_, "stanford-bunny");  // no change: not a step
  QVERIFY(!doc().isModified());
  QVERIFY(scene::ops::rename(doc(), bunny_, "renamed before a failed save"));
  const int errors = prompts_->errors.size();
  QVERIFY(!w_->saveSceneTo(tmp_.filePath("no-such-dir/x.hscene"), true));
  QCOMPARE(prompts_->errors.size(), errors + 1);
  QVERIFY(prompts_->errors.last().contains("x.hscene"));
  QVERIFY(doc().isModified());
  QCOMPARE(doc().filePath(), QFileInfo(path).absoluteFilePath());
  doc().undoStack()->undo();
  QVERIFY(!doc().isModified());

  w_->newScene();
  QCOMPARE(findByName(doc().state(), "stanford-bunny"), scene::kNoEntity);

  QVERIFY(w_->openSceneFile(path, true));
  QCOMPARE(doc().filePath(), QFileInfo(path).absoluteFilePath());
  QVERIFY(!doc().isModified());
  QCOMPARE(doc().undoStack()->count(), 0);
  QCOMPARE(doc().state().entities.size(), entities);
  bunny_ = findByName(doc().state(), "stanford-bunny");
  QVERIFY(bunny_ != scene::kNoEntity);
  QVERIFY(bunny().transform.translation == position);
  const scene::MeshAsset* asset = doc().state().findAsset(bunny().mesh->mesh);
  QVERIFY(asset && asset->data);
  QCOMPARE(asset->data->triangleCount(), triangles);
  QVERIFY(doc().state().validate().empty());
}

void EditorSmokeTest::unsavedChangesAreAskedAbout() {
  QVERIFY(!doc().isModified());
  // Rename in place, as the outliner's editor does.
  QTRY_VERIFY(w_->outliner()->model()->indexOf(bunny_).isValid());
  const QModelIndex index = w_->outliner()->model()->indexOf(bunny_);
  QVERIFY(w_->outliner()->model()->setData(index, "Bunny renamed", Qt::EditRole));
  QCOMPARE(bunny().name, std::string("Bunny renamed"));
  QVERIFY(doc().isModified());

  // New with Cancel: asked once, nothing changes.
  prompts_->saveAnswer = app::Prompts::SaveChoice::Cancel;
  const int asked = prompts_->saveQuestions;
  w_->requestNew();
  QCOMPARE(prompts_->saveQuestions, asked + 1);
  QVERIFY(doc().state().find(bunny_));
  QVERIFY(doc().isModified());
  // Closing with Cancel keeps the window.
  QVERIFY(!w_->close());
  QVERIFY(w_->isVisible());
  QCOMPARE(prompts_->saveQuestions, asked + 2);

  // Undo back to the saved state: clean again, and New asks nothing.
  doc().undoStack()->undo();
  QVERIFY(!doc().isModified());
  QVERIFY(!w_->isWindowModified());
  doc().undoStack()->redo();
  QVERIFY(doc().isModified());

  // Discard: New goes ahead.
  prompts_->saveAnswer = app::Prompts::SaveChoice::Discard;
  w_->requestNew();
  QCOMPARE(prompts_->saveQuestions, asked + 3);
  QVERIFY(!doc().state().find(bunny_) || doc().state().find(bunny_)->name != "Bunny renamed");
  QVERIFY(!doc().isModified());

  // Reopen for the remaining tests.
  QVERIFY(w_->openSceneFile(tmp_.filePath("smoke.hscene"), true));
  bunny_ = findByName(doc().state(), "stanford-bunny");
  QVERIFY(bunny_ != scene::kNoEntity);
}

void EditorSmokeTest::outlinerDropReparentsKeepingWorldPlace() {
  app::OutlinerModel* model = w_->outliner()->model();
  // A group at some offset to drop the bunny into.
  scene::Transform groupAt;
  groupAt.translation = glm::dvec3(5.0, -2.0, 1.0);
  groupAt.rotation = scene::fromEulerDegrees({0.0, 0.0, 30.0});
  const scene::EntityId group = scene::ops::addEmpty(doc(), "Group", groupAt);
  QTRY_VERIFY(model->indexOf(group).isValid());
  QTRY_VERIFY(model->indexOf(bunny_).isValid());
  const glm::dvec3 worldBefore(doc().state().worldMatrix(bunny_)[3]);
  const int steps = doc().undoStack()->index();

  std::unique_ptr<QMimeData> mime(model->mimeData({model->indexOf(bunny_)}));
  QVERIFY(model->canDropMimeData(mime.get(), Qt::MoveAction, -1, 0, model->indexOf(group)));
  model->dropMimeData(mime.get(), Qt::MoveAction, -1, 0, model->indexOf(group));
  QTRY_COMPARE(bunny().parent, group);
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  const glm::dvec3 worldAfter(doc().state().worldMatrix(bunny_)[3]);
  QVERIFY(glm::length(worldAfter - worldBefore) < 1e-9);
  // The tree shows it under the group.
  QTRY_COMPARE(model->idOf(model->parent(model->indexOf(bunny_))), group);
  // A group cannot be dropped into its own child.
  std::unique_ptr<QMimeData> groupMime(model->mimeData({model->indexOf(group)}));
  QVERIFY(!model->canDropMimeData(groupMime.get(), Qt::MoveAction, -1, 0, model->indexOf(bunny_)));

  doc().undoStack()->undo();
  QCOMPARE(bunny().parent, scene::kNoEntity);
  doc().undoStack()->undo();  // the group
  QVERIFY(!doc().state().find(group));
}

// The Create menu's spot light (one undo step) and the settings panel's
// exposure and fog fields, generated from the settings declarations.
void EditorSmokeTest::spotLightAndFogFromTheEditor() {
  QAction* spot = nullptr;
  for (QAction* a : w_->findChildren<QAction*>())
    if (a->text() == "Sp&ot Light") spot = a;
  QVERIFY(spot);
  const int steps = doc().undoStack()->index();
  spot->trigger();
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  const scene::EntityId id = findByName(doc().state(), "Spot Light");
  QVERIFY(id != scene::kNoEntity);
  QVERIFY(doc().state().find(id)->light && doc().state().find(id)->light->type == scene::Light::Type::Spot);
  doc().undoStack()->undo();
  QVERIFY(!doc().state().find(id));
  for (const char* key : {"exposure_ev100", "fog_mode", "fog_colour", "fog_k1", "fog_k2", "fog_density",
                          "fog_height_falloff", "fog_height"})
    QVERIFY2(w_->sceneSettings()->editorFor(key), key);
}

void EditorSmokeTest::sceneSettingsEditIsUndoable() {
  auto* spin = w_->sceneSettings()->findChild<app::ScrubSpinBox*>("settings.exposure_ev100");
  QVERIFY(spin);
  const float before = doc().state().settings.exposureEv100;
  const int steps = doc().undoStack()->index();
  spin->setValue(double(before) + 0.25);
  spin->setValue(double(before) + 0.5);
  emit spin->editingFinished();
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  // What the spin box holds: the value rounded to its decimals (the default
  // exposure, 13.5485037, has more digits than it shows).
  const double half = 0.5 * std::pow(10.0, -spin->decimals()) + 1e-9;
  QCOMPARE(doc().state().settings.exposureEv100, float(spin->value()));
  QVERIFY(std::abs(spin->value() - (double(before) + 0.5)) <= half);
  doc().undoStack()->undo();
  QCOMPARE(doc().state().settings.exposureEv100, before);
  // Shown rounded to its decimals (13.549; 15.2 would not show as 15.19999981).
  QVERIFY2(std::abs(spin->value() - double(before)) <= half, qPrintable(QString::number(spin->value())));
}

void EditorSmokeTest::badImportReportsAndChangesNothing() {
  const QString bad = tmp_.filePath("empty.obj");
  {
    QFile f(bad);
    QVERIFY(f.open(QIODevice::WriteOnly));
  }
  const scene::SceneState before = doc().state();
  const int steps = doc().undoStack()->count();
  const bool modified = doc().isModified();
  const int errors = prompts_->errors.size();
  const int panelErrors = w_->messages()->count(app::MessageLevel::Error);

  QVERIFY(!w_->importMeshFile(bad, true));

  QCOMPARE(prompts_->errors.size(), errors + 1);
  QVERIFY2(prompts_->errors.last().contains("empty.obj"), qPrintable(prompts_->errors.last()));
  QCOMPARE(w_->messages()->count(app::MessageLevel::Error), panelErrors + 1);
  QCOMPARE(doc().undoStack()->count(), steps);
  QCOMPARE(doc().isModified(), modified);
  QCOMPARE(doc().state().entities.size(), before.entities.size());
  QCOMPARE(doc().state().assets.size(), before.assets.size());
  QVERIFY(doc().state().roots == before.roots);

  // A file that does not exist: the same, with its name in the message.
  QVERIFY(!w_->importMeshFile(tmp_.filePath("missing.ply"), true));
  QCOMPARE(prompts_->errors.size(), errors + 2);
  QVERIFY(prompts_->errors.last().contains("missing.ply"));
  QCOMPARE(doc().state().entities.size(), before.entities.size());
}

void EditorSmokeTest::badOpenKeepsTheDocument() {
  const QString bad = tmp_.filePath("broken.hscene");
  {
    QFile f(bad);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("this is not an SQLite database\n");
  }
  const QString pathBefore = doc().filePath();
  const size_t entities = doc().state().entities.size();
  const int errors = prompts_->errors.size();
  QVERIFY(!w_->openSceneFile(bad, true));
  QCOMPARE(prompts_->errors.size(), errors + 1);
  QVERIFY(prompts_->errors.last().contains("broken.hscene"));
  QCOMPARE(doc().filePath(), pathBefore);
  QCOMPARE(doc().state().entities.size(), entities);
  QVERIFY(doc().state().find(bunny_));

  // A damaged scene (a copy of the saved one cut short): the error is
  // followed by the offer of a repaired copy (answered No here), and
  // File > Save a Repaired Copy… writes one that opens, leaving the damaged
  // file as it was.
  const QString cut = tmp_.filePath("cut.hscene");
  QVERIFY(QFile::copy(tmp_.filePath("smoke.hscene"), cut));
  QVERIFY(QFile::resize(cut, QFileInfo(cut).size() * 6 / 10));
  QFile cutFile(cut);
  QVERIFY(cutFile.open(QIODevice::ReadOnly));
  const QByteArray cutBytes = cutFile.readAll();
  cutFile.close();
  const int questions = prompts_->yesNoQuestions;
  QVERIFY(!w_->openSceneFile(cut, true));
  QCOMPARE(prompts_->errors.size(), errors + 2);
  QVERIFY2(prompts_->errors.last().contains("damaged"), qPrintable(prompts_->errors.last()));
  QCOMPARE(prompts_->yesNoQuestions, questions + 1);
  const QString repaired = tmp_.filePath("cut-repaired.hscene");
  QVERIFY(w_->repairSceneFile(cut, repaired, true));
  QCOMPARE(prompts_->yesNoQuestions, questions + 2);  // "Open it?"
  QVERIFY(cutFile.open(QIODevice::ReadOnly));
  QVERIFY(cutFile.readAll() == cutBytes);
  std::string error;
  QVERIFY2(scene::loadScene(repaired.toStdString(), error), error.c_str());
  QVERIFY(!w_->repairSceneFile(cut, repaired, true));  // never replaces a file
  QCOMPARE(prompts_->errors.size(), errors + 3);
  QVERIFY(prompts_->errors.last().contains("already exists"));
  QCOMPARE(doc().filePath(), pathBefore);
}

void EditorSmokeTest::autosaveAndRecovery() {
  app::Autosave* autosave = w_->autosave();
  QVERIFY(QFileInfo::exists(autosave->sessionFile()));
  // Nothing unsaved: nothing to write.
  QVERIFY(!doc().isModified());
  QVERIFY(!autosave->saveNow(true));
  QVERIFY(!QFileInfo::exists(autosave->recoveryFile()));

  QVERIFY(w_->outliner()->model()->setData(w_->outliner()->model()->indexOf(bunny_), "Unsaved name", Qt::EditRole));
  QVERIFY(autosave->saveNow(true));
  QVERIFY(QFileInfo::exists(autosave->recoveryFile()));
  // A live session is never offered for recovery.
  QVERIFY(autosave->findOrphans().empty());

  // Simulate a session that crashed: its marker names a process that is gone.
  const QString dir = QFileInfo(autosave->sessionFile()).absolutePath();
  const QString crashed = dir + "/session-999999-1";
  QVERIFY(QFile::copy(autosave->recoveryFile(), crashed + ".hscene"));
  {
    QFile f(crashed + ".session");
    QVERIFY(f.open(QIODevice::WriteOnly));
    QJsonObject o;
    o["pid"] = 999999.0;
    o["start"] = "1";
    o["document"] = tmp_.filePath("smoke.hscene");
    f.write(QJsonDocument(o).toJson());
  }
  const auto orphans = autosave->findOrphans();
  QCOMPARE(orphans.size(), size_t(1));
  QCOMPARE(orphans.front().documentPath, tmp_.filePath("smoke.hscene"));

  // Saving clears this session's copy.
  QVERIFY(w_->saveSceneTo(doc().filePath(), true));
  QVERIFY(!QFileInfo::exists(autosave->recoveryFile()));

  // Start-up offers it; Recover opens it as unsaved work on its original file.
  prompts_->yesNoAnswer = true;
  const int asked = prompts_->yesNoQuestions;
  w_->offerRecovery();
  QCOMPARE(prompts_->yesNoQuestions, asked + 1);
  QTRY_VERIFY_WITH_TIMEOUT(!w_->isBusy(), 30000);
  QVERIFY(doc().isModified());
  QCOMPARE(doc().filePath(), tmp_.filePath("smoke.hscene"));
  QVERIFY(findByName(doc().state(), "Unsaved name") != scene::kNoEntity);
  QVERIFY(!QFileInfo::exists(crashed + ".hscene"));
  QVERIFY(!QFileInfo::exists(crashed + ".session"));
  QVERIFY(autosave->findOrphans().empty());
}

void EditorSmokeTest::cleanupTestCase() {
  if (!w_) return;
  const QString session = w_->autosave()->sessionFile();
  const QString recovery = w_->autosave()->recoveryFile();
  prompts_->saveAnswer = app::Prompts::SaveChoice::Discard;
  QVERIFY(w_->close());
  // A clean exit leaves no recovery copy or session marker behind.
  QVERIFY(!QFileInfo::exists(session));
  QVERIFY(!QFileInfo::exists(recovery));
  w_.reset();
}

QTEST_MAIN(EditorSmokeTest)
#include "test_editor_smoke.moc"
