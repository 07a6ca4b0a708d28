// The editor's foliage tools, driven as a user drives them: on a hilly
// terrain made through the Terrain panel, a plant generated through the
// Foliage panel (and its dialog's kind defaults), a type added, a scatter
// from the Scatter dialog's values (instances appear, the override does not
// stick to the type, undo removes them), Clear; then brush strokes with the
// mouse in the viewport: Paint adds instances as ONE undo step, Erase
// removes them, Select (a click, then a Shift-drag) with Delete and
// Reapply, a click on a drawn instance; a type edited through its dialog (and a refused combination);
// the Foliage menu; one brush active at a time.
#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QMenu>
#include <QMenuBar>
#include <QProgressDialog>
#include <QPushButton>
#include <QSpinBox>
#include <QTest>
#include <QTimer>
#include <QToolButton>
#include <QTreeWidget>

#include <glm/gtc/quaternion.hpp>

#include "app/app_settings.h"
#include "app/foliage_dialogs.h"
#include "app/foliage_panel.h"
#include "app/foliage_tool.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/status_bar.h"
#include "app/param_form.h"
#include "app/selection.h"
#include "app/terrain_panel.h"
#include "app/terrain_tool.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "foliage/surface.h"
#include "scene/foliage_data.h"
#include "scene/foliage_ground.h"
#include "scene/foliage_ops.h"
#include "scene/impostor_key.h"
#include "scene/impostor_ops.h"
#include "scene/terrain_ops.h"
#include "scene/terrain_pick.h"

using namespace hs;
using hs::app::MainWindow;

class EditorFoliageTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private:
  std::unique_ptr<MainWindow> w_;
  test::QuietPrompts* prompts_ = nullptr;
  app::FoliagePanel* panel_ = nullptr;
  scene::EntityId terrain_ = scene::kNoEntity;

  scene::Document& doc() { return w_->document(); }
  const foliage::FoliageStore& store() { return doc().foliage().store(); }
  // The undo position: one more per step pushed (count() would also hold
  // undone steps that a push drops).
  int steps() { return doc().undoStack()->index(); }

  // The widget pixel over the terrain's surface at world XY.
  QPoint pixelAt(const glm::dvec2& xy) {
    const auto z = scene::terrainSurfaceAt(doc().state(), terrain_, xy);
    if (!z) qFatal("no terrain at %g, %g", xy.x, xy.y);
    QPoint p;
    if (!w_->viewport()->projectToWidget(glm::dvec3(xy, *z), p)) qFatal("%g, %g is not in view", xy.x, xy.y);
    return p;
  }

  // A press, five moves of `step` pixels and a release.
  void stroke(const QPoint& from, const QPoint& step, Qt::KeyboardModifiers mods = Qt::NoModifier) {
    app::ViewportWidget* vp = w_->viewport();
    QTest::mousePress(vp, Qt::LeftButton, mods, from);
    for (int i = 1; i <= 5; ++i) QTest::mouseMove(vp, from + step * i);
    QTest::mouseRelease(vp, Qt::LeftButton, mods, from + step * 5);
  }

  void chooseTool(const char* label) {
    auto* b = panel_->findChild<QToolButton*>(QString("foliageTool_%1").arg(label));
    QVERIFY(b);
    b->click();
  }

  // The share of a preview's pixels that differ from its corner (the
  // backdrop): the part the drawn mesh covers.
  static double coveredShare(const QImage& img) {
    if (img.isNull()) return 0.0;
    const QColor bg = img.pixelColor(0, 0);
    size_t n = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) {
        const QColor c = img.pixelColor(x, y);
        if (std::abs(c.red() - bg.red()) + std::abs(c.green() - bg.green()) + std::abs(c.blue() - bg.blue()) > 24) ++n;
      }
    return double(n) / double(img.width() * img.height());
  }

  // The number in a Messages line such as "Paint foliage: 40 placed, 0 removed in 7 dab(s)".
  int dabsInLastMessage() {
    const QString t = w_->messages()->lastText();
    const int end = t.indexOf(" dab(s)");
    if (end < 0) return -1;
    const int start = t.lastIndexOf(' ', end - 1);
    return t.mid(start + 1, end - start - 1).toInt();
  }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
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
    panel_ = w_->foliagePanel();
    QVERIFY(panel_);
    // A valley like the demo's: 256 m of fractal hills up to 12 m.
    scene::ops::NewTerrain spec;
    spec.name = "Valley";
    spec.samplesX = spec.samplesY = 257;
    spec.sizeMetres = glm::dvec2(256.0);
    spec.heightRange = {0.0f, 12.0f};
    spec.start = scene::ops::NewTerrain::Start::Hills;
    terrain_ = w_->terrainPanel()->createTerrain(spec);
    QVERIFY(terrain_ != scene::kNoEntity);
  }

  void cleanupTestCase() { w_.reset(); }

  void generatePlantThroughThePanel() {
    // The dialog puts each kind's defaults in its fields.
    app::PlantDialog d(nullptr, "Boulder");
    auto* kind = qobject_cast<QComboBox*>(d.form()->field("kind"));
    QVERIFY(kind);
    kind->setCurrentIndex(kind->findData("rock"));
    const foliage::PlantParams rock = foliage::defaultPlant(foliage::PlantKind::Rock);
    QCOMPARE(qobject_cast<QDoubleSpinBox*>(d.form()->field("height_m"))->value(), rock.height);
    qobject_cast<QDoubleSpinBox*>(d.form()->field("height_m"))->setValue(1.2);
    qobject_cast<QSpinBox*>(d.form()->field("seed"))->setValue(7);
    const foliage::PlantParams p = d.params();
    QCOMPARE(p.kind, foliage::PlantKind::Rock);
    QCOMPARE(p.height, 1.2);
    QCOMPARE(p.seed, uint64_t(7));
    // The live preview shows the plant the fields grow: a rock against the
    // backdrop, drawn again after an edit.
    QTRY_VERIFY_WITH_TIMEOUT(d.previewsShown() >= 1, 30000);
    const int shown = d.previewsShown();
    QVERIFY(!d.preview()->pixmap().isNull());
    QCOMPARE(coveredShare(d.preview()->pixmap().toImage()) > 0.1, true);
    qobject_cast<QSpinBox*>(d.form()->field("seed"))->setValue(8);
    QTRY_VERIFY_WITH_TIMEOUT(d.previewsShown() > shown, 30000);
    qobject_cast<QSpinBox*>(d.form()->field("seed"))->setValue(7);

    const int before = steps();
    const scene::AssetId id = panel_->generatePlant(d.name(), p);
    QVERIFY(id != scene::kNoAsset);
    QCOMPARE(steps(), before + 1);
    const scene::MeshAsset* a = doc().state().findAsset(id);
    QCOMPARE(a->name, std::string("Boulder"));
    QVERIFY(a->data->triangleCount() > 100);
    QVERIFY(!a->lods.empty());
    QVERIFY(w_->messages()->lastText().contains("Boulder"));
    // The same name again is refused with a message, nothing added.
    QVERIFY(panel_->generatePlant("Boulder", p) == scene::kNoAsset);
    QCOMPARE(steps(), before + 1);
    QVERIFY(!prompts_->errors.isEmpty() && prompts_->errors.last().contains("exists"));
  }

  void addType() {
    foliage::FoliageType t;
    t.name = "Rocks";
    t.mesh = "Boulder";
    t.densityPerHa = 2000.0;
    t.spacing = 1.0;
    const int before = steps();
    QVERIFY(panel_->addType(t));
    QCOMPARE(steps(), before + 1);
    QCOMPARE(store().types().size(), size_t(1));
    auto* list = panel_->findChild<QTreeWidget*>("foliageTypes");
    QCOMPARE(list->topLevelItemCount(), 1);
    QCOMPARE(list->topLevelItem(0)->text(0), QString("Rocks"));
    QCOMPARE(list->topLevelItem(0)->text(1), QString("Boulder"));
    QCOMPARE(list->topLevelItem(0)->text(2), QString("0"));
    QCOMPARE(panel_->currentType(), 0);
    QCOMPARE(panel_->brushTypes(), foliage::TypeSet{0});
    // The type's thumbnail: its mesh drawn small on a worker.
    QTRY_VERIFY_WITH_TIMEOUT(!list->topLevelItem(0)->icon(0).isNull(), 30000);
    const QImage thumb = list->topLevelItem(0)->icon(0).pixmap(40, 40).toImage();
    QVERIFY2(coveredShare(thumb) > 0.1, qPrintable(QString::number(coveredShare(thumb))));
    // A type drawing a mesh the scene lacks is refused.
    t.name = "Ghosts";
    t.mesh = "No such mesh";
    QVERIFY(!panel_->addType(t));
    QCOMPARE(store().types().size(), size_t(1));
    QVERIFY(prompts_->errors.last().contains("No such mesh"));
  }

  void scatterAndUndo() {
    app::FoliageScatterDialog d(nullptr, store().types(), 0, {});
    QCOMPARE(d.types(), foliage::TypeSet{0});
    qobject_cast<QSpinBox*>(d.form()->field("seed"))->setValue(5);
    const int before = steps();
    QVERIFY(panel_->scatter(d.types(), d.values()));
    QCOMPARE(steps(), before + 1);
    const size_t n = store().instanceCount();
    // 6.6 ha at 2000 per hectare, less what the spacing refuses.
    QVERIFY2(n > 5000 && n < 14000, qPrintable(QString::number(n)));
    qInfo("scatter: %zu instances", n);
    auto* list = panel_->findChild<QTreeWidget*>("foliageTypes");
    QCOMPARE(list->topLevelItem(0)->text(2), QLocale().toString(qulonglong(n)));
    // Memory: 16 bytes in the store and 32 on the GPU an instance.
    QCOMPARE(list->topLevelItem(0)->text(3), app::formatBytes(n * 48));
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), size_t(0));
    QCOMPARE(list->topLevelItem(0)->text(2), QString("0"));
    doc().undoStack()->redo();
    QCOMPARE(store().instanceCount(), n);

    // Clear: the type's instances go in one step; undo brings them back.
    QVERIFY(panel_->clear(0));
    QCOMPARE(store().instanceCount(), size_t(0));
    QCOMPARE(steps(), before + 2);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), n);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), size_t(0));

    // A density override is for this scatter only.
    d.form()->setChecked("density_per_ha", true);
    qobject_cast<QDoubleSpinBox*>(d.form()->field("density_per_ha"))->setValue(200.0);
    QVERIFY(panel_->scatter(d.types(), d.values()));
    const size_t thin = store().instanceCount();
    QVERIFY2(thin > n / 20 && thin < n / 5, qPrintable(QString("%1 of %2").arg(thin).arg(n)));
    QCOMPARE(store().type(0).densityPerHa, 2000.0);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), size_t(0));
  }

  // Scatter runs on a worker under a progress dialog: its Cancel changes
  // nothing (a million-per-hectare override: seconds of work otherwise).
  void scatterCancels() {
    app::FoliageScatterDialog d(nullptr, store().types(), 0, {});
    d.form()->setChecked("density_per_ha", true);
    qobject_cast<QDoubleSpinBox*>(d.form()->field("density_per_ha"))->setValue(1e6);
    const size_t before = store().instanceCount();
    const int step0 = steps();
    int dialogs = 0;
    QTimer::singleShot(0, w_.get(), [&] {
      for (QProgressDialog* p : w_->findChildren<QProgressDialog*>())
        if (p->windowTitle() == "Scatter") {
          ++dialogs;
          emit p->canceled();
        }
    });
    QVERIFY(panel_->scatter(d.types(), d.values()));
    QCOMPARE(dialogs, 1);
    QCOMPARE(steps(), step0);
    QCOMPARE(store().instanceCount(), before);
    QVERIFY2(w_->messages()->lastText().contains("cancelled: nothing changed"), qPrintable(w_->messages()->lastText()));
  }

  void paintStrokeIsOneUndoStep() {
    app::ViewportWidget* vp = w_->viewport();
    // Look down on the valley's centre from 150 m.
    render::RenderView v = vp->currentView();
    v.eye = {0.0, -60.0, 150.0};
    v.orientation = glm::quatLookAt(glm::normalize(glm::dvec3(0.0, 60.0, -150.0)), glm::dvec3(0, 0, 1));
    vp->camera().setView(v, 160.0);
    vp->update();
    w_->terrainPanel()->findChild<QToolButton*>("terrainTool_Raise")->click();
    chooseTool("Paint");
    QCOMPARE(panel_->tool()->kind(), app::FoliageToolKind::Paint);
    QVERIFY(!w_->terrainPanel()->tool()->active());  // one brush at a time
    panel_->findChild<QDoubleSpinBox*>("foliageRadius")->setValue(5.0);
    QCOMPARE(panel_->tool()->brush().radius, 5.0);

    const QPoint p = pixelAt({0.0, 0.0});
    const int before = steps();
    QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, p);
    QVERIFY(panel_->tool()->stroking());
    QVERIFY(store().instanceCount() > 0);  // the first dab is in the store already ...
    QCOMPARE(steps(), before);             // ... its undo step comes at release
    for (int i = 1; i <= 5; ++i) QTest::mouseMove(vp, p + QPoint(12 * i, 0));
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, p + QPoint(60, 0));
    QVERIFY(!panel_->tool()->stroking());
    QCOMPARE(steps(), before + 1);  // the whole stroke, one step
    const int dabs = dabsInLastMessage();
    QVERIFY2(dabs >= 3, qPrintable(w_->messages()->lastText()));
    const size_t painted = store().instanceCount();
    QVERIFY2(painted > 30, qPrintable(QString::number(painted)));
    qInfo("paint stroke: %d dabs, %zu instances", dabs, painted);
    // Along the stroke: right of the start, within the radius of the path
    // (which bends a little with the hills under a fixed pixel row).
    for (const foliage::Instance& in : store().allInstances()) {
      QVERIFY(in.position.x > -5.01 && in.position.x < 40.0);
      QVERIFY(std::abs(in.position.y) < 15.0);
      QCOMPARE(in.surface, foliage::Surface::Terrain);
    }
    // The stroke selected nothing and did not move the terrain entity.
    QCOMPARE(w_->selection().primary(), terrain_);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), size_t(0));
    doc().undoStack()->redo();
    QCOMPARE(store().instanceCount(), painted);
  }

  void eraseStrokeRemovesThem() {
    chooseTool("Erase");
    panel_->findChild<QDoubleSpinBox*>("foliageRadius")->setValue(12.0);
    const QPoint p = pixelAt({0.0, 0.0});
    const int before = steps();
    stroke(p, QPoint(12, 0));
    QCOMPARE(steps(), before + 1);
    QCOMPARE(store().instanceCount(), size_t(0));
    doc().undoStack()->undo();
    QVERIFY(store().instanceCount() > 30);
  }

  void selectDeleteAndReapply() {
    chooseTool("Select");
    panel_->findChild<QDoubleSpinBox*>("foliageRadius")->setValue(3.0);
    const QPoint p = pixelAt({5.0, 0.0});
    app::ViewportWidget* vp = w_->viewport();
    const size_t all = store().instanceCount();
    const int before = steps();
    // A click: the nearest instance within the radius.
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
    QCOMPARE(panel_->tool()->selection().size(), size_t(1));
    QCOMPARE(panel_->findChild<QLabel*>("foliageSelectionInfo")->text(), QString("1 selected"));
    // A Shift-drag adds everything under the brush.
    stroke(p, QPoint(3, 0), Qt::ShiftModifier);
    const size_t selected = panel_->tool()->selection().size();
    QVERIFY2(selected > 5 && selected < all, qPrintable(QString("%1 of %2").arg(selected).arg(all)));
    qInfo("selected %zu of %zu", selected, all);
    QCOMPARE(steps(), before);  // selecting changes no document

    // Reapply: rotations and scales drawn again, the instances stay (one step).
    const std::vector<foliage::Instance> was = store().allInstances();
    panel_->findChild<QPushButton*>("foliageReapply")->click();
    QCOMPARE(steps(), before + 1);
    QCOMPARE(store().instanceCount(), all);
    QCOMPARE(panel_->tool()->selection().size(), selected);
    // The selected ones turned (a new random yaw), the others did not.
    size_t turned = 0;
    for (const foliage::Instance& in : store().allInstances())
      for (const foliage::Instance& old : was)
        if (old.id == in.id && std::abs(glm::dot(old.rotation, in.rotation)) < 0.9999) ++turned;
    QVERIFY2(turned > selected / 2 && turned <= selected, qPrintable(QString("%1 of %2").arg(turned).arg(selected)));

    auto* del = panel_->findChild<QPushButton*>("foliageDeleteSelection");
    QVERIFY(del->isEnabled());
    del->click();
    QCOMPARE(steps(), before + 2);
    QCOMPARE(store().instanceCount(), all - selected);
    QVERIFY(panel_->tool()->selection().empty());
    QVERIFY(!del->isEnabled());
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), all);
    chooseTool("Off");
    QVERIFY(!panel_->tool()->active());
  }

  // Select's click takes the instance drawn under the cursor (the
  // renderer's id pass): clicking a boulder's side from close by, where the
  // ground behind it lies half a metre beyond the smallest radius, selects
  // that boulder; the ground rule alone would take none there.
  void clickOnADrawnInstanceSelectsIt() {
    app::ViewportWidget* vp = w_->viewport();
    const render::RenderView saved = vp->currentView();
    // The boulder nearest to (10, 0), looked at from 4 m south and 6 m up.
    const std::vector<foliage::Instance> all = store().allInstances();
    QVERIFY(!all.empty());
    const foliage::Instance* target = &all[0];
    for (const foliage::Instance& in : all)
      if (glm::length(glm::dvec2(in.position) - glm::dvec2(10, 0)) <
          glm::length(glm::dvec2(target->position) - glm::dvec2(10, 0)))
        target = &in;
    const glm::dvec3 aim = target->position + glm::dvec3(0.0, 0.0, 0.5 * 1.2 * target->scale.z);
    render::RenderView v = saved;
    v.eye = target->position + glm::dvec3(0.0, -4.0, 6.0);
    v.orientation = glm::quatLookAt(glm::normalize(aim - v.eye), glm::dvec3(0, 0, 1));
    vp->camera().setView(v, glm::length(aim - v.eye));
    vp->update();
    chooseTool("Select");
    panel_->findChild<QDoubleSpinBox*>("foliageRadius")->setValue(app::FoliageTool::kMinRadius);
    QPoint p;
    QVERIFY(vp->projectToWidget(aim, p));
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
    QCOMPARE(panel_->tool()->selection().size(), size_t(1));
    QCOMPARE(panel_->tool()->selection().ids(), std::vector<uint32_t>{target->id});
    // Beside it, on bare ground: the ground rule, which finds none within 0.1 m.
    QVERIFY(vp->projectToWidget(target->position + glm::dvec3(0.0, -1.2, 0.0), p));
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, p);
    QVERIFY(panel_->tool()->selection().empty());
    chooseTool("Off");
    vp->camera().setView(saved, 160.0);
    vp->update();
  }

  // A press, moves through `corners` (each edge in 6 steps) and a release
  // at the last: a loop on the ground for Lasso and Fill, a drag for Move.
  void trace(const std::vector<glm::dvec2>& corners, Qt::KeyboardModifiers mods = Qt::NoModifier) {
    app::ViewportWidget* vp = w_->viewport();
    QTest::mousePress(vp, Qt::LeftButton, mods, pixelAt(corners[0]));
    for (size_t c = 1; c < corners.size(); ++c)
      for (int i = 1; i <= 6; ++i) QTest::mouseMove(vp, pixelAt(glm::mix(corners[c - 1], corners[c], i / 6.0)));
    QTest::mouseRelease(vp, Qt::LeftButton, mods, pixelAt(corners.back()));
  }

  // Fill paints the loop drawn on the ground up to the type's density (one
  // step); Lasso selects what lies inside its loop; Move drags the
  // selection over the ground, each instance back on the terrain.
  void fillLassoAndMove() {
    // The view of paintStrokeIsOneUndoStep: 150 m above the valley's centre;
    // a pixel there is about 0.2 m, so loops are checked to 0.5 m.
    const size_t before = store().instanceCount();
    QVERIFY(before > 30);
    const int step0 = steps();
    auto inside = [](const glm::dvec3& p, glm::dvec2 lo, glm::dvec2 hi, double margin) {
      return p.x >= lo.x - margin && p.x <= hi.x + margin && p.y >= lo.y - margin && p.y <= hi.y + margin;
    };

    // Fill: a 30 m square west of the painted stroke, empty so far.
    chooseTool("Fill");
    QCOMPARE(panel_->tool()->kind(), app::FoliageToolKind::Fill);
    const glm::dvec2 flo(-60.0, -15.0), fhi(-30.0, 15.0);
    trace({flo, {fhi.x, flo.y}, fhi, {flo.x, fhi.y}, flo});
    QVERIFY(panel_->tool()->polygon().empty());
    QCOMPARE(steps(), step0 + 1);
    const size_t filled = store().instanceCount() - before;
    // 900 m2 at 2000 per hectare: 180, less what the 1 m spacing refuses.
    QVERIFY2(filled > 140 && filled <= 190, qPrintable(QString::number(filled)));
    size_t inSquare = 0;
    for (const foliage::Instance& in : store().allInstances())
      if (inside(in.position, flo, fhi, 0.5)) ++inSquare;
    QCOMPARE(inSquare, filled);  // every new one inside the loop, none before there
    qInfo("fill: %zu instances in the 30 m square", filled);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), before);

    // A click without a loop (one point, no area) fills nothing and says why.
    trace({flo, flo});
    QCOMPARE(steps(), step0);
    QVERIFY(w_->messages()->lastText().contains("draw a loop"));
    // Fill with no type chosen: refused at the first click, before any loop.
    const foliage::TypeSet types = panel_->tool()->types();
    panel_->tool()->setTypes({});
    trace({flo, {fhi.x, flo.y}, fhi, {flo.x, fhi.y}, flo});
    QCOMPARE(steps(), step0);
    QCOMPARE(store().instanceCount(), before);
    QVERIFY(w_->messages()->lastText().contains("no type chosen"));
    panel_->tool()->setTypes(types);

    // Lasso: a loop around part of the stroke selects what it holds.
    chooseTool("Lasso");
    const glm::dvec2 llo(-5.0, -15.0), lhi(15.0, 15.0);
    trace({llo, {lhi.x, llo.y}, lhi, {llo.x, lhi.y}, llo});
    QCOMPARE(steps(), step0);  // selecting changes no document
    const std::vector<uint32_t> ids = panel_->tool()->selection().ids();
    QVERIFY2(ids.size() > 5 && ids.size() < before, qPrintable(QString::number(ids.size())));
    const std::vector<foliage::Instance> was = store().allInstances();
    for (const foliage::Instance& in : was) {
      const bool selected = std::binary_search(ids.begin(), ids.end(), in.id);
      if (inside(in.position, llo, lhi, -0.5)) QVERIFY2(selected, qPrintable(QString::number(in.id)));
      if (!inside(in.position, llo, lhi, 0.5)) QVERIFY2(!selected, qPrintable(QString::number(in.id)));
    }

    // Move: the selection 20 m north, over the hills; each instance back on the terrain.
    chooseTool("Move");
    const int step1 = steps();
    app::ViewportWidget* vp = w_->viewport();
    QTest::mousePress(vp, Qt::LeftButton, Qt::NoModifier, pixelAt({5.0, 0.0}));
    for (int i = 1; i <= 5; ++i) QTest::mouseMove(vp, pixelAt({5.0, 4.0 * i}));
    QVERIFY(std::abs(panel_->tool()->moveOffset().y - 20.0) < 0.5);  // the overlay's preview
    QTest::mouseRelease(vp, Qt::LeftButton, Qt::NoModifier, pixelAt({5.0, 20.0}));
    QCOMPARE(steps(), step1 + 1);
    QCOMPARE(store().instanceCount(), before);
    QCOMPARE(panel_->tool()->selection().ids(), ids);  // the selection follows them
    const double sink = store().type(0).sinkDepth;
    const scene::FoliageGround ground(doc().state());
    for (const foliage::Instance& in : store().allInstances()) {
      const auto old = std::find_if(was.begin(), was.end(), [&](const foliage::Instance& o) { return o.id == in.id; });
      QVERIFY(old != was.end());
      if (!std::binary_search(ids.begin(), ids.end(), in.id)) {
        QCOMPARE(in.position, old->position);
        continue;
      }
      const glm::dvec2 moved = glm::dvec2(in.position - old->position);
      QVERIFY2(std::abs(moved.x) < 0.5 && std::abs(moved.y - 20.0) < 0.5, qPrintable(QString("%1 %2").arg(moved.x).arg(moved.y)));
      const glm::dvec3 anchor = in.position + in.rotation * glm::dvec3(0.0, 0.0, sink);
      // The terrain's triangles (foliage::terrainSurface: what the renderer
      // draws), not the bilinear height terrainSurfaceAt gives the brush.
      const auto sp = foliage::terrainSurface(ground.ground().terrain->height, glm::dvec2(anchor));
      QVERIFY(sp);
      QVERIFY2(std::abs(anchor.z - sp->position.z) < 1e-3, qPrintable(QString::number(anchor.z - sp->position.z)));
    }
    doc().undoStack()->undo();
    const std::vector<foliage::Instance> back = store().allInstances();
    QCOMPARE(back.size(), was.size());
    for (size_t i = 0; i < back.size(); ++i) {
      QCOMPARE(back[i].id, was[i].id);
      QCOMPARE(back[i].position, was[i].position);
    }

    // Move Selected Instances By…: an exact offset (multiples of the
    // store's 2^-10 m grid, so exact), kept height: up by exactly 2 m. The
    // selection still names the cells the undone drag put them in: the
    // move finds them where they are now.
    QVERIFY(panel_->moveSelectionBy(Json{{"offset_m", {3.25, -1.5, 2.0}}, {"keep_height", true}}));
    QCOMPARE(steps(), step1 + 1);
    for (const foliage::Instance& in : store().allInstances()) {
      const auto old = std::find_if(was.begin(), was.end(), [&](const foliage::Instance& o) { return o.id == in.id; });
      QVERIFY(old != was.end());
      const glm::dvec3 expect = std::binary_search(ids.begin(), ids.end(), in.id)
                                    ? old->position + glm::dvec3(3.25, -1.5, 2.0)
                                    : old->position;
      QVERIFY2(glm::length(in.position - expect) < 1e-9, qPrintable(QString::number(in.id)));
    }
    doc().undoStack()->undo();
    QCOMPARE(store().allInstances().front().position, was.front().position);

    // Move with nothing selected: said, no step.
    panel_->tool()->clearSelection();
    QTest::mouseClick(vp, Qt::LeftButton, Qt::NoModifier, pixelAt({5.0, 0.0}));
    QCOMPARE(steps(), step1);
    QVERIFY(w_->messages()->lastText().contains("nothing selected"));
    chooseTool("Off");
  }

  // Fill Paint Layer: the type painted where the grass layer (put there by
  // the terrain's paint rules) weighs at least half, one undo step; a
  // layer the terrain lacks is refused by name.
  void fillPaintLayerThroughThePanel() {
    QVERIFY(w_->terrainPanel()->applyPaintRules(true));
    const size_t before = store().instanceCount();
    const int step0 = steps();
    QVERIFY(panel_->fillLayer({0}, Json{{"layer", "Grass"}, {"min_weight", 0.5}, {"seed", 3}}));
    QCOMPARE(steps(), step0 + 1);
    const size_t filled = store().instanceCount() - before;
    QVERIFY2(filled > 50, qPrintable(QString::number(filled)));
    QVERIFY(w_->messages()->lastText().contains("Fill Paint Layer"));
    // The panel's fill ran on a worker, into a copy: it placed what the
    // operation on the document itself places.
    const std::vector<foliage::Instance> worked = store().allInstances();
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), before);
    QVERIFY(scene::ops::fillFoliageLayer(doc(), scene::FoliageGround(doc().state()), {0}, "Grass", 0.5, 3).ok);
    const std::vector<foliage::Instance> direct = store().allInstances();
    QCOMPARE(direct.size(), worked.size());
    for (size_t i = 0; i < direct.size(); ++i)
      QVERIFY(direct[i].id == worked[i].id && direct[i].position == worked[i].position);
    doc().undoStack()->undo();
    QCOMPARE(store().instanceCount(), before);
    QVERIFY(!panel_->fillLayer({0}, Json{{"layer", "Lava"}, {"min_weight", 0.5}}));
    QVERIFY(prompts_->errors.last().contains("Lava"));
    QCOMPARE(steps(), step0);
    doc().undoStack()->undo();  // the paint rules
  }

  void editTypeThroughTheDialog() {
    const foliage::FoliageType before = store().type(0);
    app::FoliageTypeDialog d(nullptr, {"Boulder"}, {}, &before);
    QCOMPARE(d.nameField()->text(), QString("Rocks"));
    auto* spacing = qobject_cast<QDoubleSpinBox*>(d.form()->field("spacing_m"));
    QVERIFY(spacing);
    QCOMPARE(spacing->value(), 1.0);
    foliage::FoliageType t;
    std::string error;
    // Opened and taken as it is, the dialog gives the type back unchanged.
    QVERIFY2(d.type(t, error), error.c_str());
    QVERIFY(t == before);
    spacing->setValue(3.0);
    auto* mode = qobject_cast<QComboBox*>(d.form()->field("scale_mode"));
    mode->setCurrentIndex(mode->findData("xy_z"));
    QVERIFY2(d.type(t, error), error.c_str());
    const int steps0 = steps();
    QVERIFY(panel_->editType(0, t));
    QCOMPARE(steps(), steps0 + 1);
    QCOMPARE(store().type(0).spacing, 3.0);
    QCOMPARE(store().type(0).scaleMode, foliage::ScaleMode::XyZ);
    QCOMPARE(store().type(0).densityPerHa, before.densityPerHa);  // the rest as it was
    doc().undoStack()->undo();
    QVERIFY(store().type(0) == before);

    // A combination the CLI refuses too: the dialog names it and stays open.
    qobject_cast<QDoubleSpinBox*>(d.form()->field("fade_m"))->setValue(5000.0);
    QVERIFY(!d.type(t, error));
    QVERIFY2(QString::fromStdString(error).contains("fade_m"), error.c_str());
    d.accept();
    QVERIFY(d.result() != QDialog::Accepted);
    QVERIFY(!d.findChild<QLabel*>("foliageTypeError")->isHidden());
  }

  // Bake Impostors: the types' meshes baked on a worker and stored as one
  // step; a second bake finds nothing to do; undo takes them out.
  void bakeImpostorsStoresThemAsOneStep() {
    const std::vector<scene::AssetId> ids = scene::ops::impostorsToBake(doc().state(), false);
    QVERIFY(!ids.empty());
    const int step0 = steps();
    QVERIFY(panel_->bakeImpostors(false));
    QCOMPARE(steps(), step0 + 1);
    for (scene::AssetId id : ids)
      QCOMPARE(scene::impostorStatus(doc().state(), *doc().state().findAsset(id)), scene::ImpostorStatus::Stored);
    QVERIFY2(w_->messages()->lastText().contains(QString("%1 impostor(s) baked").arg(ids.size())),
             qPrintable(w_->messages()->lastText()));
    QVERIFY(panel_->bakeImpostors(false));
    QCOMPARE(steps(), step0 + 1);
    QVERIFY(w_->messages()->lastText().contains("nothing baked"));
    doc().undoStack()->undo();
    QCOMPARE(scene::impostorStatus(doc().state(), *doc().state().findAsset(ids.front())), scene::ImpostorStatus::None);
  }

  // [ and ] (and with Shift) scale the active brush: the foliage one while
  // a foliage tool is on (its density factor for strength), the terrain's
  // otherwise, never both.
  void brushShortcutsScaleTheActiveBrush() {
    auto trigger = [&](const char* text) {
      for (QAction* a : w_->actions())
        if (a->text().remove('&') == text) {
          a->trigger();
          return true;
        }
      return false;
    };
    chooseTool("Paint");
    const double radius = panel_->tool()->brush().radius, density = panel_->tool()->brush().densityFactor;
    const double terrainRadius = w_->terrainPanel()->tool()->settings().radius;
    QVERIFY(trigger("Brush Radius Larger"));
    QVERIFY(trigger("Brush Strength Lower"));
    QCOMPARE(panel_->tool()->brush().radius, radius * 1.25);
    QCOMPARE(panel_->tool()->brush().densityFactor, density / 1.25);
    QCOMPARE(w_->terrainPanel()->tool()->settings().radius, terrainRadius);
    auto* spin = panel_->findChild<QDoubleSpinBox*>("foliageRadius");
    QVERIFY(spin);
    QVERIFY(std::abs(spin->value() - radius * 1.25) < 0.01);  // the panel shows it
    chooseTool("Off");
    QVERIFY(trigger("Brush Radius Smaller"));
    QCOMPARE(panel_->tool()->brush().radius, radius * 1.25);
    QCOMPARE(w_->terrainPanel()->tool()->settings().radius, terrainRadius / 1.25);
    QVERIFY(trigger("Brush Radius Larger"));  // the terrain's back as it was
  }

  void foliageMenuOffersEveryCommand() {
    QMenu* menu = nullptr;
    for (QAction* a : w_->menuBar()->actions())
      if (a->text().remove('&') == "Foliage") menu = a->menu();
    QVERIFY(menu);
    QStringList texts;
    for (QAction* a : menu->actions()) texts << a->text().remove('&');
    for (const char* t : {"Generate Plant…", "New Foliage Type…", "Edit Foliage Type…", "Scatter…", "Fill Paint Layer…", "Clear Type",
                          "Bake Impostors", "Paint Brush", "Erase Brush", "Select Brush", "Foliage Tool Off", "Lasso Select", "Fill Area",
                          "Move Selected Instances", "Move Selected Instances By…", "Delete Selected Instances",
                          "Reapply to Selected Instances"})
      QVERIFY2(texts.contains(t), t);
    // The menu's brush entries drive the same tool as the panel's buttons.
    for (QAction* a : menu->actions())
      if (a->text().remove('&') == "Erase Brush") a->trigger();
    QCOMPARE(panel_->tool()->kind(), app::FoliageToolKind::Erase);
    QVERIFY(panel_->findChild<QToolButton*>("foliageTool_Erase")->isChecked());
    // Choosing a terrain tool turns the foliage brush off.
    w_->terrainPanel()->findChild<QToolButton*>("terrainTool_Smooth")->click();
    QVERIFY(!panel_->tool()->active());
    QVERIFY(panel_->findChild<QToolButton*>("foliageTool_Off")->isChecked());
    w_->terrainPanel()->findChild<QToolButton*>("terrainTool_Select")->click();
  }
};

QTEST_MAIN(EditorFoliageTest)
#include "test_editor_foliage.moc"
