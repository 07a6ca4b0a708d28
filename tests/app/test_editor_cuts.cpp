// The camera-cut track in the editor, under Xvfb (app/timeline_cut_track.h):
// Add Cut for the selected camera at the playhead, a transition set from
// the context actions, a cut dragged by its body and trimmed by its end
// with the mouse (each gesture one undo step, frames snapped), a drag that
// would overlap the next cut not taken, Remove; and Export Frames offering
// the cuts as its camera.
#include <QComboBox>
#include <QTest>

#include "app/export_dialog.h"
#include "app/main_window.h"
#include "app/selection.h"
#include "app/timeline_clock.h"
#include "app/timeline_cut_track.h"
#include "app/timeline_panel.h"
#include "editor_fixture.h"

using namespace hs;
using hs::app::MainWindow;

namespace {

scene::SceneState twoCameras() {
  scene::SceneState s;
  s.sequence.rate = {10, 1};
  s.sequence.startFrame = 0;
  s.sequence.endFrame = 199;
  for (scene::EntityId id : {1, 2}) {
    scene::Entity cam;
    cam.id = id;
    cam.name = id == 1 ? "Drone" : "Crane";
    cam.camera = scene::Camera{};
    cam.transform.translation = {0.0, -10.0 * double(id), 2.0};
    s.entities[id] = cam;
    s.roots.push_back(id);
  }
  return s;
}

}  // namespace

class CutsEditorTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(app::settingsSandboxed());
    w_ = std::make_unique<MainWindow>();
    test::setQuietPrompts(*w_, test::QuietPrompts::Errors::Warn);
    w_->resize(1200, 800);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    doc().reset(twoCameras(), QString());
    track_ = w_->timeline()->cutTrack();
    QVERIFY(track_ && track_->isVisible());
    QTRY_VERIFY(track_->width() > 400);  // laid out
  }

  void addCutsAndATransition() {
    w_->selection().set({2});
    w_->timelineClock()->setFrame(30);
    QVERIFY(track_->addCutAtPlayhead());  // Crane: frames 30-79 (5 s at 10 fps)
    w_->selection().set({1});
    w_->timelineClock()->setFrame(0);
    QVERIFY(track_->addCutAtPlayhead());  // Drone: 0 up to the Crane's cut, 29
    const auto& cuts = doc().state().sequence.cuts;
    QCOMPARE(cuts.size(), size_t(2));
    QCOMPARE(cuts[0].camera, uint64_t(1));
    QCOMPARE(cuts[0].end, int64_t(29));
    QCOMPARE(cuts[1].start, int64_t(30));
    QCOMPARE(cuts[1].end, int64_t(79));
    QVERIFY(track_->setTransition(1, sequencer::Transition::Crossfade, 10));
    QCOMPARE(doc().state().sequence.cuts[1].transitionFrames, int64_t(10));
    QVERIFY(track_->setEase(1, sequencer::Ease::Out));
    QCOMPARE(doc().state().sequence.cuts[1].ease, sequencer::Ease::Out);
    QVERIFY(!track_->setEase(0, sequencer::Ease::In));  // a plain cut has no transition to ease
    // Longer than the shot before (29 frames after its first): refused, nothing changes.
    QVERIFY(!track_->setTransition(1, sequencer::Transition::DipToBlack, 40));
    QCOMPARE(doc().state().sequence.cuts[1].transition, sequencer::Transition::Crossfade);
    // A stylised transition, one undo step, drawn named on its ramp.
    const int before = doc().undoStack()->index();
    QVERIFY(track_->setTransition(1, sequencer::Transition::WaterDrop, 10));
    QCOMPARE(doc().state().sequence.cuts[1].transition, sequencer::Transition::WaterDrop);
    track_->grab();  // paints the ramp with its name
    doc().undoStack()->undo();
    QCOMPARE(doc().undoStack()->index(), before);
    QCOMPARE(doc().state().sequence.cuts[1].transition, sequencer::Transition::Crossfade);
    // No camera selected: nothing to add.
    w_->selection().clear();
    QVERIFY(!track_->addCutAtPlayhead());
  }

  void dragMovesAndTrimsAsOneStep() {
    const int steps = doc().undoStack()->index();
    // Trim the second cut's end (8 s) right by 1.5 s, in four moves.
    const QRectF r = track_->cutRect(1);
    QVERIFY(!r.isEmpty());
    const double px = track_->axis().pixelsPerSecond();
    const QPoint from(int(r.right()) - 1, int(r.center().y()));
    QTest::mousePress(track_, Qt::LeftButton, Qt::NoModifier, from);
    for (int k = 1; k <= 4; ++k) QTest::mouseMove(track_, from + QPoint(int(k * 0.375 * px), 0));
    QTest::mouseRelease(track_, Qt::LeftButton, Qt::NoModifier, from + QPoint(int(1.5 * px), 0));
    const int64_t end = doc().state().sequence.cuts[1].end;
    QVERIFY2(std::abs(end - 94) <= 1, qPrintable(QString("end %1").arg(end)));
    QCOMPARE(doc().undoStack()->index(), steps + 1);  // one step for the gesture
    doc().undoStack()->undo();
    QCOMPARE(doc().state().sequence.cuts[1].end, int64_t(79));
    // Moving the first cut right would overlap the second: not taken.
    const QRectF first = track_->cutRect(0);
    const QPoint mid(int(first.center().x()), int(first.center().y()));
    QTest::mousePress(track_, Qt::LeftButton, Qt::NoModifier, mid);
    QTest::mouseMove(track_, mid + QPoint(int(2.0 * px), 0));
    QTest::mouseRelease(track_, Qt::LeftButton, Qt::NoModifier, mid + QPoint(int(2.0 * px), 0));
    QCOMPARE(doc().state().sequence.cuts[0].start, int64_t(0));
    QCOMPARE(doc().state().sequence.cuts[0].end, int64_t(29));
  }

  void exportOffersTheCuts() {
    app::ExportDialog* dialog = w_->exportDialog();
    QVERIFY(dialog);
    dialog->resetFromDocument();
    auto* camera = dialog->findChild<QComboBox*>("exportCamera");
    QVERIFY(camera);
    QVERIFY2(camera->currentText().startsWith("Camera cuts"), qPrintable(camera->currentText()));
    QCOMPARE(camera->currentData().toULongLong(), qulonglong(0));
  }

  void removeTakesACut() {
    QVERIFY(track_->removeCut(0));
    QCOMPARE(doc().state().sequence.cuts.size(), size_t(1));
    // The crossfade lost the shot before it.
    QCOMPARE(doc().state().sequence.cuts[0].transition, sequencer::Transition::Cut);
    doc().undoStack()->undo();
    QCOMPARE(doc().state().sequence.cuts.size(), size_t(2));
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  std::unique_ptr<MainWindow> w_;
  app::TimelineCutTrack* track_ = nullptr;
};

QTEST_MAIN(CutsEditorTest)
#include "test_editor_cuts.moc"
