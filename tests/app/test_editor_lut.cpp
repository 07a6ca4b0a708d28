// The grading LUT in the editor, under Xvfb: the Scene Settings dock's LUT
// row (Import LUT..., the stored file's name, Remove) after the LUT fields.
// Importing a .cube is one undo step and changes the viewport's picture; a
// file OpenColorIO refuses is shown as an error naming the file and line,
// and the scene stays as it was. The Post dock holds the whole chain.
// View > Post Before/After splits the viewport into the frame without and
// with its effects. Automatic exposure from the dock meters the viewport.
// Import OCIO config... stores a studio config as one undo step, fills the
// Display and View boxes with the config's names and changes the viewport;
// choosing a view from the box is a settings edit.
#include <QCheckBox>
#include <QComboBox>
#include <QToolButton>
#include <QLabel>
#include <QPushButton>
#include <QTemporaryDir>
#include <QTest>

#include <QAction>
#include <algorithm>

#include "app/field_editors.h"
#include "app/main_window.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/viewport_widget.h"
#include "app/settings_panel.h"
#include "app/timeline_rows.h"
#include "editor_fixture.h"
#include "scene/fields.h"
#include "scene/operations.h"
#include "lut_files.h"
#include "ocio_files.h"

using namespace hs;
using hs::app::MainWindow;

class LutEditorTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(app::settingsSandboxed());
    QVERIFY(tmp_.isValid());
    w_ = std::make_unique<MainWindow>();
    prompts_ = test::setQuietPrompts(*w_);
    w_->resize(1100, 760);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    panel_ = w_->findChild<app::SettingsPanel*>("postPanel");
    QVERIFY(panel_);
    test::waitForNextFrame(*w_->viewport());
  }

  // The Post dock holds the chain (the tone map and every post.* field, in
  // their declared order), Scene Settings the rest; each field in one of them.
  void thePostDockHoldsTheChain() {
    QCOMPARE(panel_, w_->postSettings());
    app::SettingsPanel* scene = w_->sceneSettings();
    for (const auto& f : scene::settingsFields()) {
      const bool post = app::SettingsPanel::inPostPanel(f.key);
      QVERIFY2(bool(panel_->editorFor(f.key)) == post, f.key.c_str());
      QVERIFY2(bool(scene->editorFor(f.key)) == !post, f.key.c_str());
    }
    for (const char* key : {"tonemap", "post.bloom.enabled", "post.kuwahara.radius_px", "post.dither.mode",
                            "post.outlines.color"})
      QVERIFY2(panel_->editorFor(key), key);
    QVERIFY(panel_->findChild<QLabel*>("stylisedHeading"));
  }

  void theRowIsThere() {
    QVERIFY(panel_->editorFor("post.lut.enabled"));
    QVERIFY(panel_->editorFor("post.lut.intensity"));
    QLabel* name = panel_->findChild<QLabel*>("lutName");
    QVERIFY(name);
    QCOMPARE(name->text(), QString("none"));
    QVERIFY(!panel_->findChild<QPushButton*>("lutRemove")->isEnabled());
  }

  void importGradesTheViewportAsOneStep() {
    const QImage before = w_->viewport()->grabFramebuffer();
    const QString file = tmp_.filePath("look.cube");
    QVERIFY(test::writeText(file.toStdString(), test::cube3dText(17, test::tealOrangeLook)));
    prompts_->openAnswer = file;
    const int steps = doc().undoStack()->index();
    panel_->findChild<QPushButton*>("lutImport")->click();
    QVERIFY(prompts_->errors.isEmpty());
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QCOMPARE(doc().state().settings.post.lut.fileName, std::string("look.cube"));
    QVERIFY(doc().state().settings.post.lutEnabled);
    QVERIFY(panel_->findChild<QLabel*>("lutName")->text().startsWith("look.cube ("));
    QVERIFY(panel_->findChild<QPushButton*>("lutRemove")->isEnabled());
    test::waitForNextFrame(*w_->viewport());
    const QImage after = w_->viewport()->grabFramebuffer();
    QCOMPARE(after.size(), before.size());
    int worst = 0;
    for (int y = 0; y < after.height(); y += 4)
      for (int x = 0; x < after.width(); x += 4) {
        const QRgb a = before.pixel(x, y), b = after.pixel(x, y);
        worst = std::max({worst, std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                          std::abs(qBlue(a) - qBlue(b))});
      }
    QVERIFY2(worst > 10, qPrintable(QString("the graded viewport differs by %1 at most").arg(worst)));
    doc().undoStack()->undo();
    QVERIFY(doc().state().settings.post.lut.empty());
    QCOMPARE(panel_->findChild<QLabel*>("lutName")->text(), QString("none"));
    doc().undoStack()->redo();
  }

  // View > Post Before/After: the viewport draws the frame without its
  // effects over its left half (the demo's LUT and bloom are on).
  void beforeAfterSplit() {
    QAction* split = w_->findChild<QAction*>("postSplitAction");
    QVERIFY(split && split->isCheckable());
    split->trigger();
    QVERIFY(w_->viewport()->postSplit());
    QTRY_VERIFY_WITH_TIMEOUT(std::any_of(w_->viewport()->lastStats().passes.begin(),
                                         w_->viewport()->lastStats().passes.end(),
                                         [](const render::PassStats& p) { return p.name == "post_split"; }),
                             30000);
    split->trigger();
    QVERIFY(!w_->viewport()->postSplit());
    QTRY_VERIFY_WITH_TIMEOUT(std::none_of(w_->viewport()->lastStats().passes.begin(),
                                          w_->viewport()->lastStats().passes.end(),
                                          [](const render::PassStats& p) { return p.name == "post_split"; }),
                             30000);
  }

  // Automatic exposure's box in the Post dock: one undo step; the viewport
  // then meters what it drew and shows another exposure.
  void automaticExposureFromThePostDock() {
    test::waitForNextFrame(*w_->viewport());
    const QImage before = w_->viewport()->grabFramebuffer();
    QVERIFY(panel_->editorFor("post.auto_exposure.speed_up"));
    auto* box = panel_->editorFor("post.auto_exposure.enabled")->findChild<QCheckBox*>();
    QVERIFY(box);
    const int steps = doc().undoStack()->index();
    const size_t probes = w_->viewport()->exposureMeterings();
    box->click();
    QVERIFY(doc().state().settings.post.autoExposure);
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    test::waitForNextFrame(*w_->viewport());
    QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->exposureMeterings() > probes, 30000);
    const QImage after = w_->viewport()->grabFramebuffer();
    double meanBefore = 0.0, meanAfter = 0.0;
    for (int y = 0; y < after.height(); y += 4)
      for (int x = 0; x < after.width(); x += 4) {
        meanBefore += qGray(before.pixel(x, y));
        meanAfter += qGray(after.pixel(x, y));
      }
    QVERIFY2(std::abs(meanAfter - meanBefore) > 0.01 * meanBefore,
             qPrintable(QString("mean grey %1 before, %2 after").arg(meanBefore).arg(meanAfter)));
    doc().undoStack()->undo();
    QVERIFY(!doc().state().settings.post.autoExposure);
  }

  void ocioConfigFromThePostDock() {
    test::waitForNextFrame(*w_->viewport());
    const QImage before = w_->viewport()->grabFramebuffer();
    QCOMPARE(panel_->findChild<QLabel*>("ocioName")->text(), QString("none"));
    // Without a config the display is free text.
    QVERIFY(!panel_->findChild<QComboBox*>("settings.post.view_transform.display.choices")->isVisibleTo(panel_));
    prompts_->openAnswer = QString::fromStdString(test::writeStudioConfig(tmp_.filePath("studio").toStdString()));
    const int steps = doc().undoStack()->index();
    panel_->findChild<QPushButton*>("ocioImport")->click();
    QVERIFY2(prompts_->errors.isEmpty(), qPrintable(prompts_->errors.join("\n")));
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QVERIFY(doc().state().settings.post.viewTransform);
    QVERIFY(panel_->findChild<QLabel*>("ocioName")->text().startsWith("studio.ocio (2 files"));
    auto* displays = panel_->findChild<QComboBox*>("settings.post.view_transform.display.choices");
    auto* views = panel_->findChild<QComboBox*>("settings.post.view_transform.view.choices");
    QVERIFY(displays && views && displays->isVisibleTo(panel_));
    QCOMPARE(displays->count(), 3);  // the default, then both displays
    QCOMPARE(displays->itemText(0), QString("Default (Studio sRGB)"));
    QCOMPARE(views->count(), 3);  // the default, Film, Raw
    test::waitForNextFrame(*w_->viewport());
    const QImage after = w_->viewport()->grabFramebuffer();
    int worst = 0;
    for (int y = 0; y < after.height(); y += 4)
      for (int x = 0; x < after.width(); x += 4)
        worst = std::max(worst, std::abs(qGray(before.pixel(x, y)) - qGray(after.pixel(x, y))));
    QVERIFY2(worst > 10, qPrintable(QString("the viewed viewport differs by %1 at most").arg(worst)));
    // The Raw view from the box: one settings edit.
    const int raw = views->findData(QString("Raw"));
    QVERIFY(raw > 0);
    emit views->activated(raw);
    QCOMPARE(doc().state().settings.post.view, std::string("Raw"));
    QCOMPARE(doc().undoStack()->index(), steps + 2);
    // Projector has no Raw view: the view goes back to its default, the
    // box offers Film only.
    emit displays->activated(displays->findData(QString("Projector")));
    QCOMPARE(doc().state().settings.post.display, std::string("Projector"));
    QVERIFY(doc().state().settings.post.view.empty());
    QCOMPARE(views->count(), 2);
    QCOMPARE(views->currentIndex(), 0);
    doc().undoStack()->undo();
    doc().undoStack()->undo();
    doc().undoStack()->undo();
    QVERIFY(doc().state().settings.post.ocioConfig.empty());
    QCOMPARE(panel_->findChild<QLabel*>("ocioName")->text(), QString("none"));
  }

  void aRefusedFileIsShownAndChangesNothing() {
    const QString file = tmp_.filePath("broken.cube");
    std::string text = test::cube3dText(4, test::identityLook);
    text.replace(text.find("0.333333 0.000000 0.000000"), 8, "nan");
    QVERIFY(test::writeText(file.toStdString(), text));
    prompts_->openAnswer = file;
    const int steps = doc().undoStack()->index();
    panel_->findChild<QPushButton*>("lutImport")->click();
    QCOMPARE(prompts_->errors.size(), 1);
    QVERIFY2(prompts_->errors[0].contains("broken.cube:5: 'nan' is not a finite number"), qPrintable(prompts_->errors[0]));
    QCOMPARE(doc().undoStack()->index(), steps);
    QCOMPARE(doc().state().settings.post.lut.fileName, std::string("look.cube"));  // the one before stays
    prompts_->errors.clear();
    // Cancelled: nothing.
    prompts_->openAnswer.clear();
    panel_->findChild<QPushButton*>("lutImport")->click();
    QCOMPARE(doc().undoStack()->index(), steps);
    // Remove: one step, the row says none.
    panel_->findChild<QPushButton*>("lutRemove")->click();
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QVERIFY(doc().state().settings.post.lut.empty());
    QVERIFY(!doc().state().settings.post.lutEnabled);
    QCOMPARE(panel_->findChild<QLabel*>("lutName")->text(), QString("none"));
  }

  // The Camera section's post settings: choosing one to override copies
  // the scene's value to the camera (one undo step) and shows its row;
  // editing the row changes the camera, not the scene; its reset button
  // gives it back to the scene (one more step).
  void aCameraOverridesAPostSetting() {
    const scene::EntityId cam = scene::ops::addCamera(doc(), "Shot camera", scene::Transform{});
    QVERIFY(cam != scene::kNoEntity);
    w_->selection().select(cam);
    auto* add = w_->properties()->findChild<QComboBox*>("overridePost");
    QVERIFY(add);
    const int index = add->findData(QString("vignette.intensity"));
    QVERIFY(index > 0);
    const double sceneValue = double(doc().state().settings.post.vignetteIntensity);
    const int steps = doc().undoStack()->index();
    emit add->activated(index);
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    const auto& post = [this, cam]() -> const std::map<std::string, scene::FieldValue>& {
      return doc().state().find(cam)->camera->post;
    };
    QCOMPARE(std::get<double>(post().at("vignette.intensity")), sceneValue);
    QTRY_VERIFY(w_->properties()->editorFor("camera.post.vignette.intensity"));
    // The list no longer offers it.
    QTRY_VERIFY(w_->properties()->findChild<QComboBox*>("overridePost") &&
                w_->properties()->findChild<QComboBox*>("overridePost")->findData(QString("vignette.intensity")) < 0);
    auto* spin = w_->properties()->findChild<app::ScrubSpinBox*>("camera.post.vignette.intensity");
    QVERIFY(spin);
    spin->setValue(0.65);
    emit spin->editingFinished();
    QCOMPARE(std::get<double>(post().at("vignette.intensity")), double(0.65f));  // held as the setting holds it
    QCOMPARE(double(doc().state().settings.post.vignetteIntensity), sceneValue);
    QTRY_VERIFY(w_->properties()->findChild<QToolButton*>("resetPost_vignette.intensity"));
    const int before = doc().undoStack()->index();
    w_->properties()->findChild<QToolButton*>("resetPost_vignette.intensity")->click();
    QVERIFY(post().empty());
    QCOMPARE(doc().undoStack()->index(), before + 1);
    doc().undoStack()->undo();
    QCOMPARE(std::get<double>(post().at("vignette.intensity")), double(0.65f));  // held as the setting holds it
    while (doc().undoStack()->index() > steps) doc().undoStack()->undo();
    QVERIFY(post().empty());
    // A track on an override is named as the camera's, not the scene's setting.
    QCOMPARE(app::propertyLabel("camera.post.vignette.intensity"), QString("Post: Vignette intensity"));
    QCOMPARE(app::propertyLabel("camera.fov_deg"), QString("Vertical field of view"));
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  QTemporaryDir tmp_;
  std::unique_ptr<MainWindow> w_;
  test::QuietPrompts* prompts_ = nullptr;
  app::SettingsPanel* panel_ = nullptr;
};

QTEST_MAIN(LutEditorTest)
#include "test_editor_lut.moc"
