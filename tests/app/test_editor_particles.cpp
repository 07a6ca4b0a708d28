// The editor's Particles panel, driven as a user drives it: a preset added
// through the panel (at the view's pivot, one undo step, its emitters
// listed), the Add Particles dialog's form, the current emitter's fields
// edited in the form (each change one undo step, a spin box's successive
// values merged), a refused value named in Messages with the document
// unchanged, a keyed list typed as JSON, the over-life curves dragged with
// the mouse (a key added, moved, removed; one undo step per gesture), the
// rate, wind and burst lists over scene time dragged the same way and the
// rate keyed at the playhead, the
// emitter's shape and bound drawn in the viewport's overlay, the live counts following the
// playhead (against scene::liveParticleCounts at that time), Remove with
// Undo, the Particles menu, and the selection choosing the current emitter.
#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QTest>
#include <QTreeWidget>

#include "app/app_settings.h"
#include "app/overlay_builder.h"
#include "app/life_curve_editor.h"
#include "app/camera_controller.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/param_form.h"
#include "app/particles_panel.h"
#include "app/selection.h"
#include "app/time_keys_editor.h"
#include "app/timeline_clock.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "particles/bounds.h"
#include "scene/world_bounds.h"
#include "scene/particle_world.h"

using namespace hs;
using hs::app::MainWindow;

class EditorParticlesTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private:
  std::unique_ptr<MainWindow> w_;
  app::ParticlesPanel* panel_ = nullptr;
  scene::EntityId torch_ = scene::kNoEntity;
  particles::EmitterDesc before_;

  scene::Document& doc() { return w_->document(); }
  int steps() { return doc().undoStack()->index(); }
  app::ParamForm* form() { return panel_->findChild<app::ParamForm*>("particlesForm"); }
  QTreeWidget* list() { return panel_->findChild<QTreeWidget*>("particleEmitters"); }
  const particles::EmitterDesc& current() { return doc().state().find(panel_->currentEmitter())->particles->desc; }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    w_ = std::make_unique<MainWindow>();
    test::setQuietPrompts(*w_);
    w_->resize(1000, 700);
    w_->newScene();
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    panel_ = w_->particlesPanel();
    QVERIFY(panel_ && form() && list());
  }

  void cleanupTestCase() { w_.reset(); }

  void addPresetAtThePivotInOneStep() {
    const int before = steps();
    const glm::dvec3 pivot = w_->viewport()->camera().pivot();
    torch_ = panel_->addPreset(Json{{"preset", "torch"}, {"name", "Gate torch"}});
    QVERIFY(torch_ != scene::kNoEntity);
    QCOMPARE(steps(), before + 1);
    const scene::Entity& group = *doc().state().find(torch_);
    QCOMPARE(group.children.size(), size_t(2));
    // The flame at the pivot, the smoke just above it (the preset's lift).
    QVERIFY(glm::length(scene::emitterInWorld(doc().state(), group.children[0])->origin - pivot) < 1e-9);
    QVERIFY(glm::length(scene::emitterInWorld(doc().state(), group.children[1])->origin - pivot) < 2.0);
    QCOMPARE(list()->topLevelItemCount(), 2);
    QCOMPARE(list()->topLevelItem(0)->text(0), QString("Gate torch flame"));
    QCOMPARE(list()->topLevelItem(0)->text(1), QString("flame, additive"));
    QCOMPARE(panel_->currentEmitter(), group.children.front());
    QVERIFY(w_->messages()->lastText().contains("Gate torch"));
    // The form shows the current emitter's values.
    auto* rate = qobject_cast<QDoubleSpinBox*>(form()->field("rate_per_s"));
    QVERIFY(rate);
    QCOMPARE(rate->value(), current().rate);
    // An unknown preset is refused in Messages; nothing added.
    const int now = steps();
    QCOMPARE(panel_->addPreset(Json{{"preset", "rain"}}), scene::kNoEntity);
    QCOMPARE(steps(), now);
    QVERIFY(w_->messages()->lastText().contains("rain"));
  }

  void dialogFormHasTheDeclaredDefaults() {
    app::ParticlesAddDialog d(nullptr, glm::dvec3(1, 2, 3));
    const Json v = d.values();
    QCOMPARE(v.value("preset", std::string()), std::string("snow"));
    QVERIFY(!v.contains("at"));  // optional rows apply only when checked
    QVERIFY(!v.contains("rate"));
  }

  void fieldEditsAreUndoSteps() {
    auto* rate = qobject_cast<QDoubleSpinBox*>(form()->field("rate_per_s"));
    const double old = current().rate;
    before_ = current();
    const int before = steps();
    rate->setValue(150.0);
    QCOMPARE(current().rate, 150.0);
    rate->setValue(175.0);  // a drag: merged into the same step
    QCOMPARE(current().rate, 175.0);
    QCOMPARE(steps(), before + 1);
    doc().undoStack()->undo();
    QCOMPARE(current().rate, old);
    QCOMPARE(rate->value(), old);  // the form follows the document
    // No other field moved: the form's rounding (replay step 1/120 shown to
    // five decimals) never writes itself back.
    rate->setValue(old + 1.0);
    particles::EmitterDesc expected = before_;
    expected.rate = old + 1.0;
    QVERIFY(current() == expected);
    doc().undoStack()->undo();
  }

  void refusedValueNamedAndNothingChanged() {
    auto* min = qobject_cast<QDoubleSpinBox*>(form()->field("lifetime_s", 0));
    QVERIFY(min);
    const particles::EmitterDesc before = current();
    const int n = steps();
    min->setValue(before.lifetimeMax + 5.0);  // MIN above MAX
    QCOMPARE(steps(), n);
    QVERIFY(current() == before);
    QVERIFY2(w_->messages()->lastText().contains("lifetime_s"), qPrintable(w_->messages()->lastText()));
    QVERIFY(w_->messages()->lastText().contains("Gate torch flame"));
    QVERIFY(panel_->findChild<QLabel*>("particlesError")->isVisibleTo(panel_));
    min->setValue(before.lifetimeMin);
  }

  void keyedListTypedAsJson() {
    auto* keys = panel_->findChild<QLineEdit*>("particles_rate_keys");
    QVERIFY(keys);
    const int n = steps();
    keys->setText("[[0, 10], [5, 50]]");
    emit keys->editingFinished();
    QCOMPARE(steps(), n + 1);
    QCOMPARE(current().rateAt(2.5), 30.0);
    keys->setText("[[0, 10], [0, 50]]");  // coincident keys
    emit keys->editingFinished();
    QCOMPARE(steps(), n + 1);
    QVERIFY2(w_->messages()->lastText().contains("rate_keys"), qPrintable(w_->messages()->lastText()));
  }

  void overLifeCurvesAreDraggedOneStepAGesture() {
    auto* size = panel_->findChild<app::LifeCurveEditor*>("particles_size_over_life_curve");
    auto* colour = panel_->findChild<app::LifeCurveEditor*>("particles_colour_over_life_curve");
    QVERIFY(size && colour);
    for (app::LifeCurveEditor* c : {size, colour})
      if (c->width() < 200 || c->height() < 90) c->resize(260, 110);
    const scene::EntityId id = panel_->currentEmitter();
    QVERIFY(panel_->setValue(id, "size_over_life", Json::parse("[[0, 1], [1, 1]]")));
    QVERIFY(panel_->setValue(id, "colour_over_life", Json::parse("[[0, 1, 1, 1, 1], [1, 0.5, 0.25, 0, 1]]")));
    QCOMPARE(size->keys().size(), size_t(2));  // the document's change reached the curve

    // A click between the keys adds one, dragged to (0.6, 1.2): one step.
    int n = steps();
    const QPoint from = size->pointAt(0.5, 0.3).toPoint(), to = size->pointAt(0.6, 1.2).toPoint();
    QTest::mousePress(size, Qt::LeftButton, {}, from);
    QTest::mouseMove(size, to);
    QTest::mouseRelease(size, Qt::LeftButton, {}, to);
    QCOMPARE(steps(), n + 1);
    const auto& keys = current().sizeOverLife.keys;
    QCOMPARE(keys.size(), size_t(3));
    // Within a pixel of where the mouse let go.
    const double px = 1.0 / (size->width() - 16), py = 1.5 / (size->height() - 12);
    QVERIFY2(std::abs(keys[1].t - 0.6) <= 1.5 * px && std::abs(keys[1].value - 1.2) <= 1.5 * py,
             qPrintable(QString("%1 %2").arg(keys[1].t).arg(keys[1].value)));
    QCOMPARE(current().sizeOverLife.eval(0.0, 1.0), 1.0);
    doc().undoStack()->undo();
    QCOMPARE(current().sizeOverLife.keys.size(), size_t(2));
    doc().undoStack()->redo();
    QCOMPARE(size->keys().size(), size_t(3));
    // A key dragged past its neighbour stops before it (keys stay increasing).
    QTest::mousePress(size, Qt::LeftButton, {}, size->keyPoint(1).toPoint());
    QTest::mouseMove(size, size->pointAt(1.2, 1.0).toPoint());
    QTest::mouseRelease(size, Qt::LeftButton, {}, size->pointAt(1.2, 1.0).toPoint());
    QVERIFY(current().sizeOverLife.keys[1].t < current().sizeOverLife.keys[2].t);
    // Right-click removes it: one more step.
    n = steps();
    QTest::mouseClick(size, Qt::RightButton, {}, size->keyPoint(1).toPoint());
    QCOMPARE(steps(), n + 1);
    QCOMPARE(current().sizeOverLife.keys.size(), size_t(2));

    // Colour: the height is the opacity; the colour is kept.
    n = steps();
    const QPoint k0 = colour->keyPoint(0).toPoint(), half = colour->pointAt(0.0, 0.5).toPoint();
    QTest::mousePress(colour, Qt::LeftButton, {}, k0);
    QTest::mouseMove(colour, half);
    QTest::mouseRelease(colour, Qt::LeftButton, {}, half);
    QCOMPARE(steps(), n + 1);
    const particles::ColourKey& c0 = current().colourOverLife.keys[0];
    QVERIFY2(std::abs(c0.rgba.a - 0.5) <= 1.0 / (colour->height() - 28) * 1.5, qPrintable(QString::number(c0.rgba.a)));
    QCOMPARE(c0.rgba.r, 1.0);
    QCOMPARE(current().colourOverLife.keys[1].rgba.g, 0.25);
  }

  // The lists over scene time: a rate key added and dragged, a wind key's
  // x dragged (its y and z kept), a burst added last and removed, each one
  // undo step; the rate keyed at the playhead with the form's value.
  void timeListsDraggedAndKeyedAtThePlayhead() {
    auto* rate = panel_->findChild<app::TimeKeysEditor*>("particles_rate_keys_curve");
    auto* wind = panel_->findChild<app::TimeKeysEditor*>("particles_wind_keys_curve");
    auto* bursts = panel_->findChild<app::TimeKeysEditor*>("particles_bursts_curve");
    QVERIFY(rate && wind && bursts);
    for (app::TimeKeysEditor* c : {rate, wind, bursts})
      if (c->width() < 200 || c->height() < 80) c->resize(260, 100);
    const int start = steps();
    const particles::EmitterDesc atStart = current();
    const scene::EntityId id = panel_->currentEmitter();
    QVERIFY(panel_->setValue(id, "rate_keys", Json::parse("[[0, 100], [60, 100]]"), false));
    QCOMPARE(rate->keys().size(), size_t(2));
    // The span holds the playback range (0 to 35999 frames at 60 fps).
    QVERIFY(rate->spanStart() <= 0.0 && rate->spanEnd() >= 599.98);
    const double px = (rate->spanEnd() - rate->spanStart()) / (rate->width() - 16);

    int n = steps();
    const QPoint from = rate->pointAt(30.0, 20.0).toPoint(), to = rate->pointAt(45.0, 110.0).toPoint();
    QTest::mousePress(rate, Qt::LeftButton, {}, from);
    QTest::mouseMove(rate, to);
    QTest::mouseRelease(rate, Qt::LeftButton, {}, to);
    QCOMPARE(steps(), n + 1);
    QCOMPARE(current().rateKeys.keys.size(), size_t(3));
    const particles::CurveKey k1 = current().rateKeys.keys[1];
    const double py = 125.0 / (rate->height() - 12);  // the range: 0 to 1.25 x the largest value
    QVERIFY2(std::abs(k1.t - 45.0) <= 1.5 * px && std::abs(k1.value - 110.0) <= 1.5 * py,
             qPrintable(QString("%1 %2").arg(k1.t).arg(k1.value)));
    doc().undoStack()->undo();
    QCOMPARE(current().rateKeys.keys.size(), size_t(2));

    QVERIFY(panel_->setValue(id, "wind_keys", Json::parse("[[0, 1, 0, 0], [60, 1, 0, 0]]"), false));
    n = steps();
    const QPoint grab = wind->keyPoint(1, 0).toPoint(), drop = wind->pointAt(60.0, -0.5).toPoint();
    QTest::mousePress(wind, Qt::LeftButton, {}, grab);
    QTest::mouseMove(wind, drop);
    QTest::mouseRelease(wind, Qt::LeftButton, {}, drop);
    QCOMPARE(steps(), n + 1);
    const particles::WindKey w1 = current().windKeys[1];
    QVERIFY2(std::abs(w1.wind.x + 0.5) <= 1.5 * 2.5 / (wind->height() - 12), qPrintable(QString::number(w1.wind.x)));
    QCOMPARE(w1.wind.y, 0.0);
    QCOMPARE(w1.wind.z, 0.0);

    QVERIFY(panel_->setValue(id, "bursts", Json::parse("[[100, 40], [20, 5]]"), false));
    n = steps();
    QTest::mouseClick(bursts, Qt::LeftButton, {}, bursts->pointAt(300.0, 8.0).toPoint());
    QCOMPARE(steps(), n + 1);
    QCOMPARE(current().bursts.size(), size_t(3));
    QCOMPARE(current().bursts[0].count, int64_t(40));  // the others keep their places (their particles)
    QVERIFY(std::abs(current().bursts[2].t - 300.0) <= 1.5 * px);
    QTest::mouseClick(bursts, Qt::RightButton, {}, bursts->keyPoint(2).toPoint());
    QCOMPARE(steps(), n + 2);
    QCOMPARE(current().bursts.size(), size_t(2));

    // Key at Playhead with the rate: the form's rate at 2 s (frame 120).
    app::TimelineClock* clock = w_->timelineClock();
    clock->setFrame(120);
    QVERIFY(panel_->setValue(id, "rate_per_s", 250.0, false));
    auto* field = panel_->findChild<QComboBox*>("particlesKeyField");
    auto* key = panel_->findChild<QPushButton*>("particlesKey");
    field->setCurrentIndex(field->findData("particles.rate_per_s"));
    QVERIFY(field->currentIndex() >= 0);
    n = steps();
    key->click();
    QCOMPARE(steps(), n + 1);
    QCOMPARE(current().rateKeys.keys.size(), size_t(3));
    QCOMPARE(current().rateKeys.keys[1].t, clock->time());
    QCOMPARE(current().rateKeys.keys[1].value, 250.0);
    QCOMPARE(rate->keys().size(), size_t(3));  // the curve follows the document
    clock->setFrame(0);
    while (steps() > start) doc().undoStack()->undo();
    QVERIFY(current() == atStart);
  }

  // The viewport draws where an emitter's particles are born (its shape at
  // its world origin) and, selected, the sphere that holds all of them.
  void emitterShapeAndBoundAreDrawn() {
    const scene::EntityId id = panel_->currentEmitter();
    QVERIFY(panel_->setValue(id, "shape", "box"));
    QVERIFY(panel_->setValue(id, "box_half_m", Json::array({2.0, 3.0, 0.5})));
    const particles::EmitterDesc d = *scene::emitterInWorld(doc().state(), id);
    scene::WorldBox around;
    around.extend(d.origin - d.boxHalf);
    around.extend(d.origin + d.boxHalf);
    w_->viewport()->camera().frame(around);
    const render::RenderView view = w_->viewport()->currentView();
    auto onBox = [&](const glm::dvec3& p) {
      const glm::dvec3 q = glm::abs(p - d.origin) - d.boxHalf;
      const double outside = std::max({q.x, q.y, q.z});
      return std::abs(outside) < 1e-9;
    };
    render::Overlay unselected, selected;
    app::buildSceneOverlay(doc().state(), {}, view, unselected);
    app::buildSceneOverlay(doc().state(), {id}, view, selected);
    size_t boxEnds = 0;
    for (const render::OverlayVertex& v : unselected.lines) boxEnds += onBox(v.position);
    QCOMPARE(boxEnds, size_t(24));  // the box's twelve edges
    // Selected: the bound's three great circles, all at its radius from its centre.
    const auto b = particles::particleBound(d);
    QVERIFY(b);
    size_t onBound = 0;
    for (const render::OverlayVertex& v : selected.lines)
      onBound += std::abs(glm::length(v.position - (d.origin + b->centre)) - b->radius) < 1e-6 * b->radius;
    QCOMPARE(onBound, size_t(3 * 48 * 2));
    QVERIFY(selected.lines.size() > unselected.lines.size());
    doc().undoStack()->undo();
    doc().undoStack()->undo();
  }

  // A spawn value keyed at the playhead from the panel: one undo step, a
  // track on the emitter's binding with the value's centre at that time.
  void spawnValueKeyedAtThePlayhead() {
    const scene::EntityId id = panel_->currentEmitter();
    QVERIFY(panel_->setValue(id, "size_m", Json::array({0.2, 0.4})));
    app::TimelineClock* clock = w_->timelineClock();
    clock->setFrame(120);
    auto* field = panel_->findChild<QComboBox*>("particlesKeyField");
    auto* key = panel_->findChild<QPushButton*>("particlesKey");
    QVERIFY(field && key);
    field->setCurrentIndex(field->findData("particles.size_m"));
    QVERIFY(field->currentIndex() >= 0);
    const int n = steps();
    key->click();
    QCOMPARE(steps(), n + 1);
    const sequencer::Binding* b = doc().state().sequence.findBinding(id);
    QVERIFY(b);
    bool found = false;
    for (const sequencer::Track& t : b->tracks)
      if (const auto* s = std::get_if<sequencer::ScalarTrack>(&t); s && s->property == "particles.size_m") {
        QCOMPARE(s->keys.size(), size_t(1));
        QCOMPARE(s->keys[0].time, clock->time());
        QVERIFY(std::abs(s->keys[0].value - 0.3) < 1e-12);
        found = true;
      }
    QVERIFY(found);
    // The emitter itself is not changed by the track (it is sampled at births).
    QCOMPARE(current().sizeMin, 0.2);
    doc().undoStack()->undo();
    QVERIFY(!doc().state().sequence.findBinding(id) ||
            doc().state().sequence.findBinding(id)->tracks.empty());
    doc().undoStack()->undo();
    clock->setFrame(0);
  }

  void liveCountsFollowThePlayhead() {
    app::TimelineClock* clock = w_->timelineClock();
    for (int64_t frame : {0, 150, 330}) {
      clock->setFrame(frame);
      QCoreApplication::processEvents();
      const auto counts = scene::liveParticleCounts(doc().state(), clock->time());
      QCOMPARE(int(counts.size()), list()->topLevelItemCount());
      for (int i = 0; i < list()->topLevelItemCount(); ++i)
        QCOMPARE(list()->topLevelItem(i)->text(2).remove(QRegularExpression("[^0-9]")).toULongLong(),
                 qulonglong(counts[size_t(i)].live));
    }
    clock->setFrame(0);
  }

  void selectionChoosesTheCurrentEmitterAndRemoveUndoes() {
    const scene::EntityId smoke = doc().state().find(torch_)->children.back();
    w_->selection().select(smoke);
    QCOMPARE(panel_->currentEmitter(), smoke);
    QCOMPARE(list()->currentItem()->text(0), QString("Gate torch smoke"));
    panel_->findChild<QPushButton*>("particlesRemove")->click();
    QVERIFY(!doc().state().find(smoke));
    QCOMPARE(list()->topLevelItemCount(), 1);
    doc().undoStack()->undo();
    QVERIFY(doc().state().find(smoke));
    QCOMPARE(list()->topLevelItemCount(), 2);
  }

  void particlesMenuOpensTheDialog() {
    QMenu* menu = nullptr;
    for (QAction* a : w_->menuBar()->actions())
      if (a->text().remove('&') == "Particles") menu = a->menu();
    QVERIFY(menu);
    bool found = false;
    for (QAction* a : menu->actions()) found |= a->text().remove('&').startsWith("Add Particles");
    QVERIFY(found);
  }
};

QTEST_MAIN(EditorParticlesTest)
#include "test_editor_particles.moc"
