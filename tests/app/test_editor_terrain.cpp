// The editor's terrain tools, driven as a user drives them: a terrain made
// through the Terrain panel, a Raise stroke painted with the mouse in the
// viewport (one undo step; undo gives back the heights bit for bit), the
// brush shortcuts, a paint stroke, whole-terrain erosion on a worker, a DEM
// import with its nodata report, export, and save/reopen keeping the tiles;
// then the paint rules editor, adding/removing/editing layers, a texture
// that cannot be read reaching Messages, and choosing the terrain a
// Terrain component shows (Properties).
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QCheckBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QScrollArea>
#include <QPushButton>

#include <glm/gtc/quaternion.hpp>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>

#include "app/app_settings.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "app/property_panel.h"
#include "app/terrain_component_picker.h"
#include "app/terrain_layers_editor.h"
#include "app/terrain_rules_editor.h"
#include "app/selection.h"
#include "app/terrain_panel.h"
#include "app/viewport_widget.h"
#include "scene/operations.h"
#include "scene/scene_json.h"
#include "scene/terrain_ops.h"
#include "editor_fixture.h"
#include "terrain_compare.h"

using namespace hs;
using hs::app::MainWindow;

class EditorTerrainTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    QVERIFY(tmp_.isValid());
    w_ = std::make_unique<MainWindow>();
    prompts_ = test::setQuietPrompts(*w_);
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

  // The rules editor: add, edit (a stepped spin box is one step), reorder,
  // turn off, remove, each one undo step; undo gives the rules back exactly;
  // Apply Paint Rules paints on a worker as one step.
  void paintRulesEditor() {
    auto* rules = panel_->findChild<app::TerrainRulesEditor*>("terrainRulesEditor");
    QVERIFY(rules);
    {
      QTest::qWait(100);
      QWidget* content = panel_->findChild<QScrollArea*>()->widget();
      content->resize(340, content->sizeHint().height());
      content->grab().save("/tmp/terrain_panel.png");
      w_->properties()->grab().save("/tmp/props.png");
    }
    const std::vector<terrain::PaintRule> original = asset().paintRules;
    QCOMPARE(rules->findChild<QListWidget*>("terrainRules")->count(), int(original.size()));
    const int base = doc().undoStack()->index();

    rules->findChild<QToolButton*>("terrainRuleAdd")->click();
    QCOMPARE(asset().paintRules.size(), original.size() + 1);
    QCOMPARE(doc().undoStack()->index(), base + 1);
    QCOMPARE(rules->currentRule(), int(original.size()));
    // Three steps up of the slope minimum and one of the layer: two undo steps.
    auto* slopeMin = rules->findChild<QDoubleSpinBox*>("terrainRuleSlopeMin");
    for (int i = 0; i < 3; ++i) slopeMin->stepBy(1);
    QCOMPARE(asset().paintRules.back().slopeMin, 33.0);
    rules->findChild<QComboBox*>("terrainRuleLayer")->setCurrentIndex(3);
    QCOMPARE(asset().paintRules.back().layer, 3);
    QCOMPARE(doc().undoStack()->index(), base + 3);
    // The preview follows the rule: steep ground covers part of the hills.
    QVERIFY(rules->previewCoverage() >= 0.0 && rules->previewCoverage() < 1.0);
    QVERIFY(!rules->findChild<QLabel*>("terrainRuleCoverage")->text().isEmpty());
    // Earlier in the order, then off (its check box), then gone.
    rules->findChild<QToolButton*>("terrainRuleUp")->click();
    QCOMPARE(asset().paintRules[original.size() - 1].layer, 3);
    QCOMPARE(rules->currentRule(), int(original.size()) - 1);
    auto* list = rules->findChild<QListWidget*>("terrainRules");
    list->item(int(original.size()) - 1)->setCheckState(Qt::Unchecked);
    QVERIFY(!asset().paintRules[original.size() - 1].enabled);
    QVERIFY(rules->removeRule(0));
    QCOMPARE(asset().paintRules.size(), original.size());
    QCOMPARE(doc().undoStack()->index(), base + 6);
    while (doc().undoStack()->index() > base) doc().undoStack()->undo();
    QCOMPARE(asset().paintRules, original);
    QCOMPARE(list->count(), int(original.size()));
    // Apply: one step on a worker; undo gives the weights back.
    const terrain::Terrain before = data().terrain().clone();
    const int steps = doc().undoStack()->index();
    QVERIFY(panel_->applyPaintRules(true));
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QVERIFY(w_->messages()->lastText().contains("paint rules"));
    doc().undoStack()->undo();
    QVERIFY(test::terrainDifference(data().terrain(), before).empty());
  }

  // Layers: add, rename, edit, remove from the panel, each one undo step;
  // weights still sum to exactly 1 after a removal; the brush's layer list
  // follows; undo gives everything back.
  void paintLayersEditor() {
    auto* layers = panel_->findChild<app::TerrainLayersEditor*>("terrainLayers");
    QVERIFY(layers);
    const std::string json = scene::canonicalJson(doc().state());
    const terrain::Terrain before = data().terrain().clone();
    const int base = doc().undoStack()->index();
    layers->findChild<QToolButton*>("terrainLayerAdd")->click();
    QCOMPARE(asset().materials.size(), size_t(9));
    QCOMPARE(data().terrain().paint.layerCount(), 9);
    QCOMPARE(layers->currentLayer(), 8);
    QCOMPARE(panel_->findChild<QComboBox*>("terrainLayer")->count(), 9);  // the brush can paint it
    auto* name = layers->findChild<QLineEdit*>("terrainMaterialName");
    name->setText("Lichen");
    emit name->editingFinished();
    QCOMPARE(asset().materials[8].name, std::string("Lichen"));
    layers->findChild<QDoubleSpinBox*>("terrainMaterialTiling")->setValue(12.5);
    QCOMPARE(asset().materials[8].tilingMetres, 12.5f);
    QCOMPARE(doc().undoStack()->index(), base + 3);
    // Remove the layer painted earlier (2, sandstone): its weight goes to the others.
    layers->setCurrentLayer(2);
    QVERIFY(data().terrain().paint.weight(2, 98, 148) > 0.9f);
    layers->findChild<QToolButton*>("terrainLayerRemove")->click();
    QCOMPARE(asset().materials.size(), size_t(8));
    QCOMPARE(asset().materials[2].name, std::string("Conglomerate"));
    QCOMPARE(test::paintSumError(data().terrain().paint), 0L);
    QCOMPARE(doc().undoStack()->index(), base + 4);
    QVERIFY(w_->messages()->lastText().contains("Removed paint layer 'Sandstone'"));
    QTRY_VERIFY(w_->viewport()->lastStats().terrainTriangles > 0);  // draws the new layers
    while (doc().undoStack()->index() > base) doc().undoStack()->undo();
    QCOMPARE(scene::canonicalJson(doc().state()), json);
    const QString diff = QString::fromStdString(test::terrainDifference(data().terrain(), before));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QCOMPARE(panel_->findChild<QComboBox*>("terrainLayer")->count(), 8);
  }

  // A texture the renderer cannot read reaches Messages, naming the file
  // and the layer; clearing it is one more undo step.
  void unreadableTextureReachesMessages() {
    auto* layers = panel_->findChild<app::TerrainLayersEditor*>("terrainLayers");
    layers->setCurrentLayer(1);
    const QString missing = tmp_.filePath("no_such_grass.png");
    QVERIFY(layers->setTexture(false, missing));
    QCOMPARE(asset().materials[1].albedoTexture, missing.toStdString());
    w_->viewport()->update();
    auto reported = [&] {
      for (int i = 0; i < w_->messages()->total(); ++i) {
        const QString t = w_->messages()->text(i);
        if (t.contains("no_such_grass.png") && t.contains("'Grass'")) return true;
      }
      return false;
    };
    QTRY_VERIFY_WITH_TIMEOUT(reported(), 20000);
    QVERIFY(layers->setTexture(false, {}));
    QVERIFY(asset().materials[1].albedoTexture.empty());
    doc().undoStack()->undo();
    doc().undoStack()->undo();
    QVERIFY(asset().materials[1].albedoTexture.empty());
  }

  // Properties: Add Component > Terrain offers the scene's terrains (and New
  // Terrain…); the component's Terrain row chooses which one it shows.
  void terrainComponentChoosesItsTerrain() {
    const scene::EntityId marker = scene::ops::addEmpty(doc(), "Marker");
    w_->selection().select(marker);
    settle();
    auto* add = w_->properties()->findChild<QToolButton*>("addComponent");
    QVERIFY(add && add->menu());
    QMenu* sub = add->menu()->findChild<QMenu*>("addTerrainComponentMenu");
    QVERIFY(sub);
    QAction* show = nullptr;
    bool offersNew = false;
    for (QAction* a : sub->actions()) {
      if (a->text() == "Show Valley") show = a;
      offersNew = offersNew || a->objectName() == "addNewTerrainComponent";
    }
    QVERIFY(show);
    QVERIFY(offersNew);
    const int steps = doc().undoStack()->index();
    show->trigger();
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QCOMPARE(scene::terrainOf(doc().state(), marker), &asset());
    settle();
    auto* picker = w_->properties()->findChild<app::TerrainPicker*>("terrainPicker");
    QVERIFY(picker);
    QCOMPARE(picker->currentText(), QString("Valley"));
    // A new terrain made on the entity (what the dialog's OK does), then back to Valley.
    scene::ops::NewTerrain spec;
    spec.name = "Ridge";
    spec.samplesX = spec.samplesY = 65;
    spec.sizeMetres = glm::dvec2(64.0);
    spec.showOn = marker;
    QCOMPARE(panel_->createTerrain(spec), marker);
    QCOMPARE(QString::fromStdString(scene::terrainOf(doc().state(), marker)->name), QString("Ridge"));
    QTRY_COMPARE(picker->currentText(), QString("Ridge"));
    const int valley = picker->findText("Valley");
    QVERIFY(valley >= 0);
    picker->setCurrentIndex(valley);
    emit picker->activated(valley);
    QCOMPARE(scene::terrainOf(doc().state(), marker), &asset());
    QCOMPARE(doc().state().terrains.size(), size_t(1));  // nothing shows Ridge any more
    doc().undoStack()->undo();
    QCOMPARE(doc().state().terrains.size(), size_t(2));
    doc().undoStack()->undo();
    doc().undoStack()->undo();
    QVERIFY(!doc().state().find(marker)->terrain);
    w_->selection().select(terrain_);
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  scene::TerrainData& data() { return *scene::terrainOf(doc().state(), terrain_)->data; }
  const scene::TerrainAsset& asset() { return *scene::terrainOf(doc().state(), terrain_); }
  // Widgets the panels replaced are deleted later: let that happen.
  static void settle() {
    QCoreApplication::processEvents();
    QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
  }

  std::unique_ptr<MainWindow> w_;
  test::QuietPrompts* prompts_ = nullptr;
  app::TerrainPanel* panel_ = nullptr;
  QTemporaryDir tmp_;
  scene::EntityId terrain_ = scene::kNoEntity;
};

QTEST_MAIN(EditorTerrainTest)
#include "test_editor_terrain.moc"
