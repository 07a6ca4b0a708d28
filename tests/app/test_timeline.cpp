// The editor's timeline under Xvfb, driven the way a user drives it: key
// buttons and field edits in Properties, key drags in the dope sheet, a
// tangent handle in the curve view, copy/paste/delete, undo, scrubbing on the
// ruler (the viewport then shows exactly scene::animatedState at that time),
// Auto Key with a gizmo drag, playback at the frame rate, every stereo
// preview mode with its comfort readout, and an export from the Export
// dialog (off the UI thread) that resumes and matches `hybridscape-cli render`.
#include <QApplication>
#include <QComboBox>
#include <QLineEdit>
#include <QProcess>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>

#include "app/app_settings.h"
#include "app/export_dialog.h"
#include "app/field_editors.h"
#include "app/gizmo.h"
#include "app/main_window.h"
#include "app/prompts.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/stereo_preview.h"
#include "app/timeline_clock.h"
#include "app/timeline_keying.h"
#include "app/timeline_panel.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "file_bytes.h"
#include "scene/animation.h"
#include "scene/object_tracks.h"

using namespace hs;
using hs::app::MainWindow;
using sequencer::KeyRef;

namespace {

// Transforms and camera fields of every entity, compared exactly.
bool sameAnimatedValues(const scene::SceneState& a, const scene::SceneState& b, QString& why) {
  for (const auto& [id, e] : a.entities) {
    const scene::Entity* o = b.find(id);
    if (!o || !(e.transform == o->transform) || e.camera != o->camera || e.visible != o->visible) {
      why = QString::fromStdString("'" + e.name + "' differs");
      return false;
    }
  }
  return a.entities.size() == b.entities.size();
}

}  // namespace

class TimelineTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase();
  void demoFlightIsOnTheTimeline();
  void keyButtonAndAnimatedFieldEdit();
  void dragKeyRetimesAsOneUndoStep();
  void copyPasteDeleteKeys();
  void curveHandleSetsAUserTangent();
  void scrubShowsWhatExportWrites();
  void autoKeyWithTheGizmo();
  void playsAtTheFrameRate();
  void stereoPreviewModesRender();
  void exportDialogResumesAndMatchesTheCli();
  void cleanupTestCase();

 private:
  scene::Document& doc() { return w_->document(); }
  app::TimelineClock& clock() { return *w_->timelineClock(); }
  scene::EntityId id(const char* name) { return doc().state().findByName(name); }
  std::vector<double> times(scene::EntityId e, const std::string& p) {
    return sequencer::keyTimes(doc().state().sequence, e, p);
  }
  void waitForFrame() { test::waitForNextFrame(*w_->viewport()); }

  std::unique_ptr<MainWindow> w_;
  QTemporaryDir tmp_;
};

void TimelineTest::initTestCase() {
  app::initApplicationSettings();
  QVERIFY(app::settingsSandboxed());
  QVERIFY(tmp_.isValid());
  w_ = std::make_unique<MainWindow>();
  test::setQuietPrompts(*w_, test::QuietPrompts::Errors::Warn);
  w_->resize(1100, 760);
  w_->loadDemoScene();
  w_->show();
  QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->framesRendered() > 0 || !w_->viewport()->rendererError().isEmpty(), 30000);
  QVERIFY2(w_->viewport()->rendererReady(), qPrintable(w_->viewport()->rendererError()));
  QVERIFY(w_->timeline());
}

void TimelineTest::demoFlightIsOnTheTimeline() {
  const auto& rows = w_->timeline()->dopeSheet()->rows();
  QVERIFY(rows.size() >= 5);
  QCOMPARE(rows[0].label, QString("Flight Camera"));
  QVERIFY(std::any_of(rows.begin(), rows.end(), [](const app::TimelineRow& r) { return r.property == "path.progress"; }));
  QCOMPARE(clock().frame(), int64_t(0));
  QCOMPARE(doc().state().sequence.endFrame, int64_t(599));
}

void TimelineTest::keyButtonAndAnimatedFieldEdit() {
  const scene::EntityId cam = id("Main Camera");
  w_->selection().select(cam);
  clock().setFrame(0);
  auto* button = w_->properties()->findChild<app::KeyButton*>("key_camera.fov_deg");
  QVERIFY(button);
  QCOMPARE(button->keyState(), app::Keying::KeyState::NotAnimated);
  const int steps = doc().undoStack()->index();
  QTest::mouseClick(button, Qt::LeftButton);
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  QCOMPARE(times(cam, "camera.fov_deg"), std::vector<double>{0.0});
  QCOMPARE(button->keyState(), app::Keying::KeyState::KeyHere);

  // At frame 120 the field is animated: an edit sets a key there, in the
  // edit's own undo step.
  clock().setFrame(120);
  QCOMPARE(button->keyState(), app::Keying::KeyState::Animated);
  auto* spin = w_->properties()->findChild<app::ScrubSpinBox*>("camera.fov_deg");
  QVERIFY(spin);
  spin->setValue(30.0);
  emit spin->editingFinished();
  QCOMPARE(doc().undoStack()->index(), steps + 2);
  QCOMPARE(times(cam, "camera.fov_deg"), (std::vector<double>{0.0, 2.0}));
  QCOMPARE(clock().state().find(cam)->camera->verticalFovDeg, 30.0);
  clock().setFrame(60);
  const double mid = clock().state().find(cam)->camera->verticalFovDeg;
  QVERIFY(mid < 40.0 && mid > 30.0);
  QCOMPARE(spin->value(), spin->valueFromText(spin->textFromValue(mid)));  // the panel shows the animated value
  doc().undoStack()->undo();
  QCOMPARE(times(cam, "camera.fov_deg"), std::vector<double>{0.0});
  QCOMPARE(doc().state().find(cam)->camera->verticalFovDeg, 40.0);
  doc().undoStack()->redo();
  QCOMPARE(times(cam, "camera.fov_deg").size(), size_t(2));
}

void TimelineTest::dragKeyRetimesAsOneUndoStep() {
  const scene::EntityId cam = id("Main Camera");
  app::TimelineDopeSheet* ds = w_->timeline()->dopeSheet();
  // The demo's sun and spinning bunny tracks folded, so the camera's rows
  // (added last) are on screen in this window.
  ds->setCollapsed(id("Sun"), true);
  ds->setCollapsed(id("Bunny (instance)"), true);
  // So are its material's and the settings' (the slab's relief, the fog).
  const uint64_t slab = scene::materialTarget(doc().state().findMaterialByName("Rock slab (parallax) / surface"));
  ds->setCollapsed(slab, true);
  ds->setCollapsed(scene::settingsTarget(), true);
  ds->setCollapsed(id("Flight Camera"), true);  // and the flight camera's focus pull (scene/demo_dof.cpp)
  const KeyRef key{cam, "camera.fov_deg", 1};
  const auto pos = ds->keyPosition(key);
  QVERIFY2(pos, "the key is not on screen");
  const double pps = ds->axis().pixelsPerSecond();
  const QPoint from = pos->toPoint();
  const QPoint to = from + QPoint(int(std::lround(pps * 1.0)), 0);  // one second later
  const int steps = doc().undoStack()->index();
  QTest::mousePress(ds, Qt::LeftButton, Qt::NoModifier, from);
  for (int i = 1; i <= 5; ++i) QTest::mouseMove(ds, from + (to - from) * i / 5);
  QTest::mouseRelease(ds, Qt::LeftButton, Qt::NoModifier, to);
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  const double expected = sequencer::frameTime(
      sequencer::frameAtTime(2.0 + (to.x() - from.x()) / pps, doc().state().sequence.rate), doc().state().sequence.rate);
  QCOMPARE(times(cam, "camera.fov_deg"), (std::vector<double>{0.0, expected}));
  QVERIFY(std::abs(expected - 3.0) < 0.05);
  QVERIFY(w_->timeline()->keySelection().contains(key));  // still selected where it went
  doc().undoStack()->undo();
  QCOMPARE(times(cam, "camera.fov_deg"), (std::vector<double>{0.0, 2.0}));
  ds->setCollapsed(id("Sun"), false);
  ds->setCollapsed(id("Bunny (instance)"), false);
  ds->setCollapsed(slab, false);
  ds->setCollapsed(scene::settingsTarget(), false);
  ds->setCollapsed(id("Flight Camera"), false);
}

void TimelineTest::copyPasteDeleteKeys() {
  const scene::EntityId spin = id("Bunny (instance)");
  app::TimelineDopeSheet* ds = w_->timeline()->dopeSheet();
  const KeyRef key{spin, "transform.rotation", 3};
  const auto pos = ds->keyPosition(key);
  QVERIFY(pos);
  QTest::mouseClick(ds, Qt::LeftButton, Qt::NoModifier, pos->toPoint());
  QVERIFY(w_->timeline()->keySelection().contains(key));
  QCOMPARE(w_->timeline()->keySelection().keys().size(), size_t(1));
  QTest::keyClick(ds, Qt::Key_C, Qt::ControlModifier);
  clock().setFrame(650);  // past the last key at 10 s
  QTest::keyClick(ds, Qt::Key_V, Qt::ControlModifier);
  std::vector<double> t = times(spin, "transform.rotation");
  QCOMPARE(t.size(), size_t(14));
  QCOMPARE(t.back(), sequencer::frameTime(650, doc().state().sequence.rate));
  const auto& rot = std::get<sequencer::RotationTrack>(doc().state().sequence.findBinding(spin)->tracks[0]);
  QVERIFY(rot.keys.back().value == rot.keys[3].value);
  QVERIFY(w_->timeline()->keySelection().contains({spin, "transform.rotation", 13}));  // the pasted key
  QTest::keyClick(ds, Qt::Key_Delete);
  QCOMPARE(times(spin, "transform.rotation").size(), size_t(13));
  doc().undoStack()->undo();  // the delete
  QCOMPARE(times(spin, "transform.rotation").size(), size_t(14));
  doc().undoStack()->undo();  // the paste
  QCOMPARE(times(spin, "transform.rotation").size(), size_t(13));
  clock().setFrame(0);
}

void TimelineTest::curveHandleSetsAUserTangent() {
  const scene::EntityId flight = id("Flight Camera");
  app::TimelineDopeSheet* ds = w_->timeline()->dopeSheet();
  // A click on the track's name shows it in the curve view.
  int row = -1;
  for (size_t i = 0; i < ds->rows().size(); ++i)
    if (ds->rows()[i].entity == flight && ds->rows()[i].property == "camera.interaxial_m") row = int(i);
  QVERIFY(row >= 0);
  QTest::mouseClick(ds, Qt::LeftButton, Qt::NoModifier,
                    QPoint(60, app::TimelineDopeSheet::kRulerHeight + row * app::TimelineDopeSheet::kRowHeight + 10));
  app::TimelineCurveView* cv = w_->timeline()->curveView();
  QCOMPARE(cv->entity(), flight);
  QCOMPARE(cv->property(), std::string("camera.interaxial_m"));
  const KeyRef key{flight, "camera.interaxial_m", 0};
  w_->timeline()->keySelection().set({key});
  const auto handle = cv->handlePoint(key, 0, true);
  QVERIFY(handle);
  const int steps = doc().undoStack()->index();
  const QPoint from = handle->toPoint();
  QTest::mousePress(cv, Qt::LeftButton, Qt::NoModifier, from);
  for (int i = 1; i <= 4; ++i) QTest::mouseMove(cv, from + QPoint(0, -10 * i));  // up: a steeper rise
  QTest::mouseRelease(cv, Qt::LeftButton, Qt::NoModifier, from + QPoint(0, -40));
  QCOMPARE(doc().undoStack()->index(), steps + 1);
  const auto& track = std::get<sequencer::ScalarTrack>(doc().state().sequence.findBinding(flight)->tracks[0]);
  QCOMPARE(track.keys[0].tangentMode, sequencer::TangentMode::User);
  QVERIFY(track.keys[0].outSlope > 0.0);
  QCOMPARE(track.keys[0].inSlope, track.keys[0].outSlope);
  doc().undoStack()->undo();
  QCOMPARE(std::get<sequencer::ScalarTrack>(doc().state().sequence.findBinding(flight)->tracks[0]).keys[0].tangentMode,
           sequencer::TangentMode::Auto);
}

void TimelineTest::scrubShowsWhatExportWrites() {
  app::TimelineDopeSheet* ds = w_->timeline()->dopeSheet();
  const int rendered = w_->viewport()->framesRendered();
  const QPoint a = ds->rulerPoint(300), b = ds->rulerPoint(420);
  QTest::mousePress(ds, Qt::LeftButton, Qt::NoModifier, a);
  QTest::mouseMove(ds, (a + b) / 2);
  QTest::mouseRelease(ds, Qt::LeftButton, Qt::NoModifier, b);
  const double framesPerPixel = doc().state().sequence.rate.fps() / ds->axis().pixelsPerSecond();
  QVERIFY2(std::abs(clock().frame() - 420) <= std::max(1.0, framesPerPixel),
           qPrintable(QString("playhead at %1").arg(clock().frame())));
  QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->framesRendered() > rendered, 20000);
  // What the viewport shows is the pure function the export calls.
  const scene::SceneState expected = scene::animatedState(doc().state(), scene::compileSequence(doc().state()),
                                                          sequencer::frameTime(clock().frame(), doc().state().sequence.rate));
  QString why;
  QVERIFY2(sameAnimatedValues(w_->viewport()->displayedState(), expected, why), qPrintable(why));
  const scene::EntityId flight = id("Flight Camera");
  QVERIFY(!(expected.find(flight)->transform == doc().state().find(flight)->transform));  // it did move
  // The panel shows the animated location.
  w_->selection().select(flight);
  auto* x = w_->properties()->findChild<app::ScrubSpinBox*>("transform.translation.x");
  QVERIFY(x);
  QCOMPARE(x->value(), x->valueFromText(x->textFromValue(expected.find(flight)->transform.translation.x)));
  // A path drives the camera's location: its key button is off.
  auto* key = w_->properties()->findChild<app::KeyButton*>("key_transform.translation");
  QVERIFY(key && !key->isEnabled());
}

void TimelineTest::autoKeyWithTheGizmo() {
  const scene::EntityId bunny = id("Stanford Bunny");
  app::ViewportWidget* vp = w_->viewport();
  clock().setFrame(60);
  clock().setAutoKey(true);
  vp->gizmo().setMode(app::GizmoMode::Translate);
  vp->gizmo().setSpace(app::GizmoSpace::World);
  vp->gizmo().snap().enabled = false;
  w_->selection().select(bunny);
  vp->frameSelection();
  app::GizmoFrame f;
  QVERIFY(vp->gizmo().frame(vp->displayedState(), w_->selection().ids(), vp->currentView(), f));
  QPoint grab, tip;
  QVERIFY(vp->projectToWidget(f.origin + f.axes[0] * (0.66 * f.length), grab));
  QVERIFY(vp->projectToWidget(f.origin + f.axes[0] * f.length, tip));
  const scene::Transform before = doc().state().find(bunny)->transform;
  const int steps = doc().undoStack()->index();
  QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, grab);
  for (int i = 1; i <= 4; ++i) QTest::mouseMove(vp, grab + (tip - grab) * i);
  QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, grab + (tip - grab) * 4);
  QCOMPARE(doc().undoStack()->index(), steps + 1);  // the move and its key: one step
  QCOMPARE(times(bunny, "transform.translation"), std::vector<double>{1.0});
  QVERIFY(times(bunny, "transform.rotation").empty());  // a move keys the location only
  const glm::dvec3 moved = doc().state().find(bunny)->transform.translation;
  QVERIFY(moved.x > before.translation.x);
  QVERIFY(clock().state().find(bunny)->transform.translation == moved);
  doc().undoStack()->undo();
  QVERIFY(times(bunny, "transform.translation").empty());
  QVERIFY(doc().state().find(bunny)->transform == before);
  clock().setAutoKey(false);
}

void TimelineTest::playsAtTheFrameRate() {
  // Playback follows real time at 60 fps: never ahead of it, and behind it
  // only by the redraw in progress (llvmpipe draws slower than the film, so
  // frames are skipped rather than the film slowed down).
  clock().setFrame(0);
  QElapsedTimer t;
  clock().play();
  t.start();
  QVERIFY(clock().playing());
  double worstBehind = 0.0, worstAllowed = 0.0;
  qint64 last = 0;
  while (t.elapsed() < 1000) {
    QTest::qWait(20);
    const qint64 now = t.elapsed();
    const double expected = now / 1000.0 * 60.0;
    const double f = double(clock().frame());
    QVERIFY2(f <= expected + 1.0, qPrintable(QString("frame %1 ahead of real time (%2)").arg(f).arg(expected)));
    // Behind by at most the time the UI thread was away (a redraw, which
    // on a loaded llvmpipe can take most of a second) plus a frame or two:
    // frames are skipped, the film is never slowed.
    const double allowed = double(now - last) / 1000.0 * 60.0 + 2.0;
    QVERIFY2(expected - f <= allowed, qPrintable(QString("frame %1 is %2 frames behind real time after a gap of %3 ms")
                                                     .arg(f)
                                                     .arg(expected - f)
                                                     .arg(now - last)));
    worstBehind = std::max(worstBehind, expected - f);
    worstAllowed = std::max(worstAllowed, allowed);
    last = now;
  }
  clock().pause();
  qInfo("played 1 s at 60 fps: ended on frame %lld, at most %.1f frames behind real time (allowed up to %.1f)",
        static_cast<long long>(clock().frame()), worstBehind, worstAllowed);
  QVERIFY(clock().frame() > 0);
  QVERIFY(!clock().playing());
}

void TimelineTest::stereoPreviewModesRender() {
  app::StereoPreviewSettings* stereo = w_->stereoPreview();
  app::ViewportWidget* vp = w_->viewport();
  w_->selection().clear();  // the active camera: the shot camera (Flight Camera)
  clock().setFrame(0);
  for (auto mode : {app::StereoPreviewMode::Left, app::StereoPreviewMode::Right, app::StereoPreviewMode::SideBySide,
                    app::StereoPreviewMode::Anaglyph}) {
    stereo->setMode(mode);
    waitForFrame();
    QVERIFY2(vp->lastComfort().has_value(), qPrintable(app::StereoPreviewSettings::modeName(mode)));
    QVERIFY(vp->lastComfort()->hasPixels);
    QVERIFY(vp->lastComfort()->withinBudget);
    auto* readout = vp->findChild<app::ComfortReadout*>("comfortReadout");
    QVERIFY(readout && readout->isVisible() && !readout->outsideBudget());
    QVERIFY2(readout->text().contains("nearest"), qPrintable(readout->text()));
    const QImage img = vp->grabFramebuffer();
    QVERIFY(!img.isNull());
    // Not one flat colour: the scene is there.
    QSet<QRgb> colours;
    for (int y = 0; y < img.height(); y += 17)
      for (int x = 0; x < img.width(); x += 13) colours.insert(img.pixel(x, y));
    QVERIFY2(colours.size() > 20, qPrintable(app::StereoPreviewSettings::modeName(mode)));
  }
  // A tight budget turns the readout red.
  const sequencer::ComfortBudget saved = stereo->budget();
  stereo->setBudget({-0.001, 0.001});
  waitForFrame();
  QVERIFY(!vp->lastComfort()->withinBudget);
  QVERIFY(vp->findChild<app::ComfortReadout*>("comfortReadout")->outsideBudget());
  stereo->setBudget(saved);
  // A mono camera selected: its view, and no parallax.
  w_->selection().select(id("Main Camera"));
  waitForFrame();
  QVERIFY(vp->findChild<app::ComfortReadout*>("comfortReadout")->text().contains("Mono camera"));
  stereo->setMode(app::StereoPreviewMode::Off);
  waitForFrame();
  QVERIFY(!vp->findChild<app::ComfortReadout*>("comfortReadout")->isVisible());
}

void TimelineTest::exportDialogResumesAndMatchesTheCli() {
  const QString scenePath = tmp_.filePath("exported.hscene");
  QVERIFY(w_->saveSceneTo(scenePath, true));
  app::ExportDialog* d = w_->exportDialog();
  d->resetFromDocument();
  d->framesEdit()->setText("0-3");
  d->widthBox()->setValue(64);
  d->heightBox()->setValue(36);
  const QString out = tmp_.filePath("editor") + "/f_%05d.png";
  d->outputEdit()->setText(out);
  QVERIFY2(d->startExport(), qPrintable(d->statusText()));
  QVERIFY(d->job().isRunning());
  QApplication::processEvents();  // the UI thread stays free while it runs
  d->job().waitForFinished();
  const app::ExportOutcome& o = d->job().outcome();
  QVERIFY2(o.setupError.empty() && o.result.ok, qPrintable(QString::fromStdString(o.setupError + o.result.error)));
  QCOMPARE(o.result.written, int64_t(4));
  QVERIFY(d->statusText().contains("Exported 4 frame(s)"));
  // Again: everything is kept.
  QVERIFY(d->startExport());
  d->job().waitForFinished();
  QCOMPARE(d->job().outcome().result.kept, int64_t(4));
  QCOMPARE(d->job().outcome().result.written, int64_t(0));
  // The CLI renders the saved scene to the same bytes.
  QProcess cli;
  const QString cliOut = tmp_.filePath("cli") + "/f_%05d.png";
  cli.start(HS_BINARY_DIR "/cli/hybridscape-cli",
            {"render", scenePath, "--frames", "0-3", "--size", "64x36", "--out", cliOut});
  QVERIFY(cli.waitForFinished(120000));
  QVERIFY2(cli.exitCode() == 0, cli.readAllStandardError().constData());
  for (int f = 0; f < 4; ++f) {
    const std::string a = test::readFile(QString(out).replace("%05d", QString::asprintf("%05d", f)).toStdString());
    const std::string b = test::readFile(QString(cliOut).replace("%05d", QString::asprintf("%05d", f)).toStdString());
    QVERIFY2(!a.empty() && a == b, qPrintable(QString("frame %1: the editor and the CLI wrote different files").arg(f)));
  }
}

void TimelineTest::cleanupTestCase() { w_.reset(); }

QTEST_MAIN(TimelineTest)
#include "test_timeline.moc"
