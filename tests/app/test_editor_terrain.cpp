// The editor's terrain tools, driven as a user drives them: a terrain made
// through the Terrain panel, a Raise stroke painted with the mouse in the
// viewport (one undo step; undo gives back the heights bit for bit), the
// brush shortcuts, a paint stroke, whole-terrain erosion on a worker, a DEM
// import with its nodata report, export, and save/reopen keeping the tiles.
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QLabel>

#include <glm/gtc/quaternion.hpp>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>

#include "app/app_settings.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/selection.h"
#include "app/terrain_panel.h"
#include "app/viewport_widget.h"
#include "scene/terrain_ops.h"
#include "terrain_compare.h"

using namespace hs;
using hs::app::MainWindow;

namespace {

class QuietPrompts : public app::Prompts {
 public:
  QStringList errors;
  SaveChoice askSaveChanges(QWidget*, const QString&) override { return SaveChoice::Discard; }
  void showError(QWidget*, const QString& title, const QString& text) override { errors << title + ": " + text; }
  bool askYesNo(QWidget*, const QString&, const QString&, const QString&, const QString&) override { return false; }
  QString askOpenFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
  QString askSaveFile(QWidget*, const QString&, const QString&, const QString&) override { return {}; }
};

}  // namespace

class EditorTerrainTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() {
    qputenv("HS_SETTINGS_SANDBOX", "1");
    app::applyDefaultSurfaceFormat();
  }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(tmp_.isValid());
    w_ = std::make_unique<MainWindow>();
    auto prompts = std::make_unique<QuietPrompts>();
    prompts_ = prompts.get();
    w_->setPrompts(std::move(prompts));
    w_->resize(1000, 700);
    w_->newScene();
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_.get()));
    QTRY_VERIFY_WITH_TIMEOUT(w_->viewport()->framesRendered() > 0 || !w_->viewport()->rendererError().isEmpty(), 30000);
    QVERIFY2(w_->viewport()->rendererReady(), qPrintable(w_->viewport()->rendererError()));
    panel_ = w_->terrainPanel();
    QVERIFY(panel_);
  }

  void newTerrainFromThePanel() {
    scene::ops::NewTerrain spec;
    spec.name = "Valley";
    spec.samplesX = spec.samplesY = 257;
    spec.sizeMetres = glm::dvec2(256.0);
    spec.heightRange = {0.0f, 0.0f};
    const int steps = doc().undoStack()->count();
    terrain_ = panel_->createTerrain(spec);
    QVERIFY(terrain_ != scene::kNoEntity);
    QCOMPARE(doc().undoStack()->count(), steps + 1);
    QCOMPARE(w_->selection().primary(), terrain_);
    QCOMPARE(panel_->current(), terrain_);
    QVERIFY(panel_->findChild<QLabel*>("terrainInfo")->text().contains("256.0 × 256.0 m"));
  }

  void strokeWithTheMouseIsOneUndoStep() {
    app::ViewportWidget* vp = w_->viewport();
    // Look down on the terrain's centre from 150 m.
    render::RenderView v = vp->currentView();
    v.eye = {0.0, -60.0, 150.0};
    v.orientation = glm::quatLookAt(glm::normalize(glm::dvec3(0.0, 60.0, -150.0)), glm::dvec3(0, 0, 1));
    vp->camera().setView(v, 160.0);
    vp->update();
    // Raise, radius 15 m, 4 m at the centre.
    panel_->findChild<QToolButton*>("terrainTool_Raise")->click();
    QCOMPARE(panel_->tool()->kind(), app::TerrainToolKind::Raise);
    panel_->findChild<QDoubleSpinBox*>("terrainRadius")->setValue(15.0);
    panel_->findChild<QDoubleSpinBox*>("terrainStrength")->setValue(4.0);
    QCOMPARE(panel_->tool()->settings().radius, 15.0);

    QPoint p;
    QVERIFY(vp->projectToWidget(glm::dvec3(0.0, 0.0, 0.0), p));
    const terrain::Terrain before = data().terrain().clone();
    const int steps = doc().undoStack()->count();
    QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, p);
    QVERIFY(panel_->tool()->stroking());
    for (int i = 1; i <= 5; ++i) QTest::mouseMove(vp, p + QPoint(8 * i, 0));
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, p + QPoint(40, 0));
    QVERIFY(!panel_->tool()->stroking());
    QCOMPARE(doc().undoStack()->count(), steps + 1);  // the whole stroke, one step
    const float raised = data().heights().heightAtLocal({128.0, 128.0});
    QVERIFY2(raised > 3.0f, qPrintable(QString::number(raised)));
    QVERIFY(doc().terrainUndo().bytesUsed() > 0);
    QVERIFY(panel_->findChild<QLabel*>("terrainUndoMemory")->text().contains("1 step"));
    // The stroke did not select anything or move the terrain.
    QCOMPARE(w_->selection().primary(), terrain_);
    const terrain::Terrain after = data().terrain().clone();
    // Undo gives back the heights exactly; redo the stroke's.
    doc().undoStack()->undo();
    QString diff = QString::fromStdString(test::terrainDifference(data().terrain(), before));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    doc().undoStack()->redo();
    diff = QString::fromStdString(test::terrainDifference(data().terrain(), after));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QTRY_VERIFY(vp->lastStats().terrainTriangles > 0);
  }

  void brushShortcuts() {
    app::ViewportWidget* vp = w_->viewport();
    vp->setFocus();
    const double r = panel_->tool()->settings().radius;
    const float s = panel_->tool()->settings().strength;
    QTest::keyClick(vp, Qt::Key_BracketRight);
    QVERIFY(std::abs(panel_->tool()->settings().radius - r * 1.25) < 1e-9);
    QTest::keyClick(vp, Qt::Key_BracketLeft);
    QVERIFY(std::abs(panel_->tool()->settings().radius - r) < 1e-9);
    QTest::keyClick(vp, Qt::Key_BracketLeft, Qt::ShiftModifier);
    QVERIFY(panel_->tool()->settings().strength < s);
    QTest::keyClick(vp, Qt::Key_BracketRight, Qt::ShiftModifier);
    QVERIFY(std::abs(panel_->tool()->settings().strength - s) < 1e-4f);
    // The widgets follow.
    QCOMPARE(panel_->findChild<QDoubleSpinBox*>("terrainRadius")->value(), r);
  }

  void paintStrokeChangesWeights() {
    app::ViewportWidget* vp = w_->viewport();
    panel_->findChild<QToolButton*>("terrainTool_Paint")->click();
    panel_->findChild<QComboBox*>("terrainLayer")->setCurrentIndex(2);
    panel_->findChild<QDoubleSpinBox*>("terrainStrength")->setValue(1.0);
    QPoint p;
    QVERIFY(vp->projectToWidget(glm::dvec3(-30.0, 20.0, 0.0), p));
    QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, p);
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, p);
    QVERIFY(data().terrain().paint.weight(2, 98, 148) > 0.9f);
    // Back to selecting: a click selects again.
    panel_->findChild<QToolButton*>("terrainTool_Select")->click();
    QVERIFY(!panel_->tool()->active());
  }

  void erosionRunsOnAWorkerAsOneStep() {
    terrain::ThermalParams p;
    p.iterations = 20;
    p.talusDegrees = 10.0;
    const int steps = doc().undoStack()->count();
    const terrain::Terrain before = data().terrain().clone();
    QVERIFY(panel_->erode(false, p, {}, {}, true));
    QCOMPARE(doc().undoStack()->count(), steps + 1);
    QVERIFY(w_->messages()->lastText().contains("mass error"));
    doc().undoStack()->undo();
    QVERIFY(test::terrainDifference(data().terrain(), before).empty());
  }

  void demImportReportsNodata() {
    app::DemImportRequest r;
    r.options.samplesX = r.options.samplesY = 129;
    const size_t before = doc().state().terrains.size();
    QVERIFY(panel_->importDem(HS_TEST_DATA_DIR "/terrain/dem_wgs84.tif", r, true));
    QCOMPARE(doc().state().terrains.size(), before + 1);
    bool nodata = false;
    for (int i = 0; i < w_->messages()->total(); ++i) nodata = nodata || w_->messages()->text(i).contains("nodata:");
    QVERIFY(nodata);
    const scene::EntityId dem = w_->selection().primary();
    const auto& hf = scene::terrainOf(doc().state(), dem)->data->heights();
    QVERIFY(hf.geo().valid());
    QVERIFY(hf.sizeMetres().x > 25000.0);  // true ground size, not degrees
    // A bad file: a clear error, nothing added.
    QVERIFY(!panel_->importDem(HS_TEST_DATA_DIR "/terrain/ATTRIBUTION.md", r, true));
    QCOMPARE(doc().state().terrains.size(), before + 1);
    QVERIFY(!prompts_->errors.isEmpty());
    doc().undoStack()->undo();  // the import
    w_->selection().select(terrain_);
  }

  void exportAndSaveReopen() {
    const QString png = tmp_.filePath("heights.png");
    QVERIFY(panel_->exportHeightmap(png, true));
    QVERIFY(QFileInfo(png).size() > 1000);
    QVERIFY(panel_->exportWeights(tmp_.filePath("weights"), true));
    QCOMPARE(QDir(tmp_.filePath("weights")).entryList(QDir::Files).size(), 8);
    const QString file = tmp_.filePath("terrain.hscene");
    QVERIFY(w_->saveSceneTo(file, true));
    const terrain::Terrain saved = data().terrain().clone();
    QVERIFY(w_->openSceneFile(file, true));
    const scene::EntityId t = doc().state().findByName("Valley");
    QVERIFY(t != scene::kNoEntity);
    terrain_ = t;
    const QString diff = QString::fromStdString(test::terrainDifference(data().terrain(), saved));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  scene::TerrainData& data() { return *scene::terrainOf(doc().state(), terrain_)->data; }

  std::unique_ptr<MainWindow> w_;
  QuietPrompts* prompts_ = nullptr;
  app::TerrainPanel* panel_ = nullptr;
  QTemporaryDir tmp_;
  scene::EntityId terrain_ = scene::kNoEntity;
};

QTEST_MAIN(EditorTerrainTest)
#include "test_editor_terrain.moc"
