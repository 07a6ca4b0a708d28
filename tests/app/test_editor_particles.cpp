// The editor's Particles panel, driven as a user drives it: a preset added
// through the panel (at the view's pivot, one undo step, its emitters
// listed), the Add Particles dialog's form, the current emitter's fields
// edited in the form (each change one undo step, a spin box's successive
// values merged), a refused value named in Messages with the document
// unchanged, a keyed list typed as JSON, the live counts following the
// playhead (against scene::liveParticleCounts at that time), Remove with
// Undo, the Particles menu, and the selection choosing the current emitter.
#include <QAction>
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
#include "app/camera_controller.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/param_form.h"
#include "app/particles_panel.h"
#include "app/selection.h"
#include "app/timeline_clock.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
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
