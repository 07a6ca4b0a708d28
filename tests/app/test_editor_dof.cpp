// Depth of field in the editor, under Xvfb: the Scene Settings dock's
// Depth of field block (the mode, K and N fields after its heading), and
// focus picking: View > Pick Focus Distance, then a click in the viewport
// sets the active camera's focus distance to the depth of the surface
// clicked (tests/common/dof_scene.h: a pole 2 m away before a wall 12 m
// away, looked at through the scene's camera), as one undo step, keyed at
// the playhead when the focus is animated.
#include <QLabel>
#include <QTest>

#include "app/main_window.h"
#include "app/selection.h"
#include "app/settings_panel.h"
#include "app/timeline_clock.h"
#include "app/timeline_keying.h"
#include "dof_scene.h"
#include "editor_fixture.h"
#include "sequencer/key_edit.h"

using namespace hs;
using hs::app::MainWindow;

class DofEditorTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(app::settingsSandboxed());
    w_ = std::make_unique<MainWindow>();
    test::setQuietPrompts(*w_, test::QuietPrompts::Errors::Warn);
    w_->resize(1100, 760);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    const test::DofScene sc = test::partialOcclusionScene();
    camera_ = sc.camera;
    doc().reset(sc.state, QString());  // the viewport looks through the scene's camera
    test::waitForNextFrame(*w_->viewport());
  }

  void settingsHaveADepthOfFieldBlock() {
    app::SettingsPanel* panel = w_->findChild<app::SettingsPanel*>("settingsPanel");
    QVERIFY(panel);
    QVERIFY(panel->findChild<QLabel*>("dofHeading"));
    QVERIFY(panel->editorFor("depth_of_field"));
    QVERIFY(panel->editorFor("dof_layers"));
    QVERIFY(panel->editorFor("dof_reference_samples"));
  }

  void clickSetsTheFocusUndoably() {
    app::ViewportWidget* vp = w_->viewport();
    QAction* pick = vp->focusPickAction();
    QVERIFY(pick);
    QCOMPARE(focus(), 12.0);
    const int steps = doc().undoStack()->index();
    pick->trigger();
    QVERIFY(vp->focusPicking());
    // The pole covers the middle of the view, 2 m from the camera.
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, vp->rect().center());
    QTRY_VERIFY(std::abs(focus() - 2.0) < 0.01);
    QVERIFY(!vp->focusPicking());  // one click, then back to selecting
    QVERIFY(!pick->isChecked());
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    doc().undoStack()->undo();
    QCOMPARE(focus(), 12.0);
    // A click on the wall (a quarter across) focuses at 12 m; on the sky
    // (none here) or without the tool nothing changes.
    vp->setFocusPicking(true);
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, QPoint(vp->width() / 4, vp->height() / 2));
    QTRY_VERIFY(std::abs(focus() - 12.0) < 0.05);
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    doc().undoStack()->undo();
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, vp->rect().center());  // selects the pole
    QCOMPARE(focus(), 12.0);
  }

  void pickKeysAnAnimatedFocus() {
    app::TimelineClock& clock = *w_->timelineClock();
    clock.setFrame(0);
    QVERIFY(w_->keying()->keyField({camera_}, "camera.focus_distance_m"));
    QCOMPARE(keyTimes(), std::vector<double>{0.0});
    clock.setFrame(120);
    app::ViewportWidget* vp = w_->viewport();
    w_->selection().clear();  // the pole's move gizmo would take the click
    test::waitForNextFrame(*vp);
    vp->setFocusPicking(true);
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, vp->rect().center());
    QTRY_COMPARE(keyTimes().size(), size_t(2));
    // At the playhead the timeline shows the picked focus; at frame 0 the old one.
    QVERIFY(std::abs(clock.state().find(camera_)->camera->focusDistance - 2.0) < 0.01);
    clock.setFrame(0);
    QCOMPARE(clock.state().find(camera_)->camera->focusDistance, 12.0);
  }

 private:
  scene::Document& doc() { return w_->document(); }
  double focus() { return doc().state().find(camera_)->camera->focusDistance; }
  std::vector<double> keyTimes() {
    return sequencer::keyTimes(doc().state().sequence, camera_, "camera.focus_distance_m");
  }

  std::unique_ptr<MainWindow> w_;
  scene::EntityId camera_ = 0;
};

QTEST_MAIN(DofEditorTest)
#include "test_editor_dof.moc"
