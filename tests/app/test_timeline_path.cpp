// Camera paths in the editor under Xvfb, driven the way a user drives them:
// the timeline's Follow Path on the selected camera, Add at View in the
// Camera Path panel, a point dragged in the viewport with the mouse (one
// undo step; Esc cancels and leaves none), Delete on a selected point, the
// aim and banking chosen in the panel, the viewport showing the camera on
// the path at the playhead, and undo of every step back to no path.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QListWidget>
#include <QPushButton>
#include <QTest>
#include <QToolButton>

#include "app/app_settings.h"
#include "app/camera_path_panel.h"
#include "app/main_window.h"
#include "app/path_editor.h"
#include "app/path_point_drag.h"
#include "app/prompts.h"
#include "app/selection.h"
#include "app/timeline_clock.h"
#include "app/timeline_panel.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "scene/animation.h"
#include "scene/camera_path_edits.h"
#include "scene/world_bounds.h"

using namespace hs;
using hs::app::MainWindow;

class TimelinePathTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase();
  void followPathFromTheTimeline();
  void addPointAtTheView();
  void dragAPointInTheViewport();
  void escapeCancelsADrag();
  void deleteKeyRemovesTheSelectedPoint();
  void aimAndBankingFromThePanel();
  void viewportShowsTheCameraOnThePath();
  void undoEverythingBackToNoPath();
  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  app::PathEditor& editor() { return *w_->pathEditor(); }
  const sequencer::PathFollow* path() { return scene::findPath(doc().state(), cam_); }
  std::vector<glm::dvec3> points() { return path() ? path()->path.points : std::vector<glm::dvec3>{}; }
  template <class T>
  T* panelChild(const char* name) {
    T* c = w_->cameraPathPanel()->findChild<T*>(name);
    if (!c) qFatal("no %s in the Camera Path panel", name);
    return c;
  }
  // Frames the path's points in the viewport and waits for the picture.
  void framePath() {
    scene::WorldBox box;
    for (const glm::dvec3& p : points()) {
      box.extend(p - glm::dvec3(1.0));
      box.extend(p + glm::dvec3(1.0));
    }
    w_->viewport()->camera().frame(box);
    test::waitForNextFrame(*w_->viewport());
  }

  std::unique_ptr<MainWindow> w_;
  scene::EntityId cam_ = scene::kNoEntity;
  int startIndex_ = 0;
  glm::dvec3 camStart_{0.0};
};

void TimelinePathTest::initTestCase() {
  app::initApplicationSettings();
  QVERIFY(app::settingsSandboxed());
  w_ = std::make_unique<MainWindow>();
  test::setQuietPrompts(*w_, test::QuietPrompts::Errors::Warn);
  w_->resize(1200, 800);
  w_->newScene();
  w_->show();
  QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->framesRendered() > 0 || !w_->viewport()->rendererError().isEmpty(), 30000);
  QVERIFY2(w_->viewport()->rendererReady(), qPrintable(w_->viewport()->rendererError()));
  cam_ = doc().state().findByName("Camera");
  QVERIFY(cam_ != scene::kNoEntity);
  QVERIFY(w_->pathEditor() && w_->cameraPathPanel());
}

void TimelinePathTest::followPathFromTheTimeline() {
  w_->selection().select(cam_);
  w_->timelineClock()->setFrame(0);
  startIndex_ = doc().undoStack()->index();
  camStart_ = doc().state().find(cam_)->transform.translation;
  auto* follow = w_->timeline()->findChild<QToolButton*>("timelineFollowPath");
  QVERIFY(follow);
  QTest::mouseClick(follow, Qt::LeftButton);
  QCOMPARE(doc().undoStack()->index(), startIndex_ + 1);
  const std::vector<glm::dvec3> p = points();
  QCOMPARE(p.size(), size_t(2));
  // From where the camera is, 10 m along its view.
  const glm::dmat4 world = doc().state().worldMatrix(cam_);
  QVERIFY(glm::length(p[0] - glm::dvec3(world[3])) < 1e-9);
  QVERIFY(glm::length(p[1] - (p[0] - glm::normalize(glm::dvec3(world[2])) * 10.0)) < 1e-9);
  // Constant speed over the playback range.
  const auto [t0, t1] = scene::playbackTimes(doc().state().sequence);
  QCOMPARE(path()->progress, sequencer::constantSpeedProgress(t0, t1));
  QVERIFY(w_->findChild<QDockWidget*>("cameraPathDock")->isVisible());
  QCOMPARE(w_->cameraPathPanel()->pointList()->count(), 2);
  QCOMPARE(editor().selectedPoint(), 1);
  // A second press only shows the panel: no second path, no step.
  QTest::mouseClick(follow, Qt::LeftButton);
  QCOMPARE(doc().undoStack()->index(), startIndex_ + 1);
}

void TimelinePathTest::addPointAtTheView() {
  // Fly somewhere else (the view starts at the camera, the path's first point).
  render::RenderView v = w_->viewport()->currentView();
  v.eye += glm::dvec3(8.0, 6.0, 3.0);
  w_->viewport()->camera().setView(v, 10.0);
  const glm::dvec3 eye = w_->viewport()->currentView().eye;
  QTest::mouseClick(panelChild<QPushButton>("pathAddAtView"), Qt::LeftButton);
  QCOMPARE(doc().undoStack()->index(), startIndex_ + 2);
  QCOMPARE(points().size(), size_t(3));
  QCOMPARE(points()[2], eye);  // after the selected (last) point
  QCOMPARE(editor().selectedPoint(), 2);
  QCOMPARE(w_->cameraPathPanel()->pointList()->count(), 3);
  QCOMPARE(w_->cameraPathPanel()->pointList()->currentRow(), 2);
}

void TimelinePathTest::dragAPointInTheViewport() {
  app::ViewportWidget* vp = w_->viewport();
  editor().selectPoint(-1);  // grab a point that is not selected: picking it selects it
  framePath();
  const glm::dvec3 before = points()[1];
  QPoint from;
  QVERIFY(vp->projectToWidget(before, from));
  const QPoint to = from + QPoint(60, -30);
  const int steps = doc().undoStack()->index();
  QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, from);
  QCOMPARE(editor().selectedPoint(), 1);  // picked
  for (int i = 1; i <= 6; ++i) QTest::mouseMove(vp, from + (to - from) * i / 6);
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, to);
  QCOMPARE(doc().undoStack()->index(), steps + 1);  // the whole drag: one step
  const glm::dvec3 after = points()[1];
  // Dragged in the view plane through the point, to under the cursor.
  const render::RenderView view = vp->currentView();
  QVERIFY(glm::length(after - before) > 0.1);
  QVERIFY(std::abs(glm::dot(after - before, view.forward())) < 1e-6 * (1.0 + glm::length(after - before)));
  QPoint landed;
  QVERIFY(vp->projectToWidget(after, landed));
  QVERIFY2((landed - to).manhattanLength() <= 2, qPrintable(QString("landed at %1,%2").arg(landed.x()).arg(landed.y())));
  // The panel shows the moved point.
  QVERIFY(w_->cameraPathPanel()->pointList()->item(1)->text().contains(QString::number(after.x, 'f', 2)));
  doc().undoStack()->undo();
  QCOMPARE(points()[1], before);
  doc().undoStack()->redo();
  QCOMPARE(points()[1], after);
  // The point's move handles replace the camera's gizmo while it is selected.
  QVERIFY(vp->pathPointDrag()->showsHandles());
}

void TimelinePathTest::escapeCancelsADrag() {
  app::ViewportWidget* vp = w_->viewport();
  editor().selectPoint(2);  // grabbed by its handles' centre this time
  const std::vector<glm::dvec3> before = points();
  QPoint from;
  QVERIFY(vp->projectToWidget(before[2], from));
  const int steps = doc().undoStack()->index();
  QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, from);
  QTest::mouseMove(vp, from + QPoint(20, 20));
  QTest::mouseMove(vp, from + QPoint(40, 30));
  QVERIFY(points()[2] != before[2]);
  QTest::keyClick(vp, Qt::Key_Escape);
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, from + QPoint(40, 30));
  QCOMPARE(points(), before);
  QCOMPARE(doc().undoStack()->index(), steps);  // no step left behind
  QCOMPARE(doc().undoStack()->count(), steps);
}

void TimelinePathTest::deleteKeyRemovesTheSelectedPoint() {
  app::ViewportWidget* vp = w_->viewport();
  editor().selectPoint(2);
  const std::vector<glm::dvec3> before = points();
  vp->setFocus();
  QTest::keyClick(vp, Qt::Key_Delete);
  QCOMPARE(points().size(), size_t(2));
  QVERIFY(doc().state().find(cam_));  // the point went, not the camera
  QCOMPARE(editor().selectedPoint(), 1);
  doc().undoStack()->undo();
  QCOMPARE(points(), before);
}

void TimelinePathTest::aimAndBankingFromThePanel() {
  auto* aim = panelChild<QComboBox>("pathAim");
  const int steps = doc().undoStack()->index();
  emit aim->activated(2);  // At an entity: the first in the list
  QCOMPARE(path()->aim, sequencer::PathAim::Entity);
  QCOMPARE(path()->targetEntity, doc().state().findByName("Sun"));
  auto* target = panelChild<QComboBox>("pathTargetEntity");
  QCOMPARE(target->currentText(), QString("Sun"));
  emit aim->activated(1);  // At a point: the middle of the points
  QCOMPARE(path()->aim, sequencer::PathAim::Point);
  auto* bank = panelChild<QCheckBox>("pathBank");
  QTest::mouseClick(bank, Qt::LeftButton, Qt::NoModifier, QPoint(8, bank->height() / 2));  // on the box
  QVERIFY(path()->bank);
  QCOMPARE(path()->maxBankDeg, 30.0);
  QCOMPARE(doc().undoStack()->index(), steps + 3);  // one step each
}

void TimelinePathTest::viewportShowsTheCameraOnThePath() {
  app::TimelineClock& clock = *w_->timelineClock();
  const auto [t0, t1] = scene::playbackTimes(doc().state().sequence);
  clock.setFrame(sequencer::frameAtTime(0.5 * (t0 + t1), doc().state().sequence.rate));
  const sequencer::PathSampler sampler(points());
  const double share = *sequencer::evaluate(path()->progress, clock.time());
  const glm::dvec3 shown(w_->viewport()->displayedState().worldMatrix(cam_)[3]);
  QVERIFY(glm::length(shown - sampler.position(share * sampler.length())) < 1e-9);
  // Keying progress in the panel moves the camera there at this frame.
  auto* progress = w_->cameraPathPanel()->findChild<QDoubleSpinBox*>("path.progress_pct");
  QVERIFY(progress);
  QVERIFY(editor().keyProgress(0.25));
  const glm::dvec3 keyed(w_->viewport()->displayedState().worldMatrix(cam_)[3]);
  QVERIFY(glm::length(keyed - sampler.position(0.25 * sampler.length())) < 1e-9);
  QCOMPARE(progress->value(), 25.0);
  doc().undoStack()->undo();
  clock.setFrame(0);
}

void TimelinePathTest::undoEverythingBackToNoPath() {
  while (doc().undoStack()->index() > startIndex_) doc().undoStack()->undo();
  QVERIFY(!path());
  QVERIFY(doc().state().sequence.bindings.empty());
  QCOMPARE(doc().state().find(cam_)->transform.translation, camStart_);
  QVERIFY(panelChild<QPushButton>("pathCreate")->isVisibleTo(w_->cameraPathPanel()));
  // And forward again to the finished path.
  while (doc().undoStack()->canRedo()) doc().undoStack()->redo();
  QCOMPARE(points().size(), size_t(3));
  QVERIFY(path()->bank && path()->aim == sequencer::PathAim::Point);
}

QTEST_MAIN(TimelinePathTest)
#include "test_timeline_path.moc"
