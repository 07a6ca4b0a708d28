// Material and settings fields on the timeline, and the Lights dock, under
// Xvfb, driven the way a user drives them: the key buttons beside the
// Materials panel's and the Scene Settings dock's fields (a click keys, an
// edit of an animated field keys in its own undo step, the panel shows the
// value at the playhead), the dope sheet's rows for those tracks, and the
// Lights dock (every light with its fields and intensity unit, an edit,
// add and delete with undo, selection shared with the outliner).
#include <QItemSelectionModel>
#include <QTableWidget>
#include <QTest>
#include <QToolButton>
#include <QTreeView>

#include "app/field_editors.h"
#include "app/lights_panel.h"
#include "app/main_window.h"
#include "app/materials_panel.h"
#include "app/outliner_model.h"
#include "app/outliner_panel.h"
#include "app/selection.h"
#include "app/settings_panel.h"
#include "app/timeline_clock.h"
#include "app/timeline_dope_sheet.h"
#include "app/timeline_keying.h"
#include "app/timeline_panel.h"
#include "editor_fixture.h"
#include "scene/object_tracks.h"
#include "sequencer/key_edit.h"

using namespace hs;
using hs::app::MainWindow;

class ObjectTracksTest : public QObject {
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
    w_->loadDemoScene();
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  }

  void materialFieldKeyButtonAndEdit() {
    app::MaterialsPanel* panel = w_->materialsPanel();
    const scene::MaterialId id = doc().state().materials.begin()->first;
    panel->select(id);
    const uint64_t target = scene::materialTarget(id);
    QVERIFY(!panel->keyButtonFor("model"));  // an enum: no key button
    app::KeyButton* button = panel->keyButtonFor("roughness");
    QVERIFY(button);
    clock().setFrame(0);
    QCOMPARE(button->keyState(), app::Keying::KeyState::NotAnimated);
    const int steps = doc().undoStack()->index();
    QTest::mouseClick(button, Qt::LeftButton);
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QCOMPARE(times(target, "material.roughness"), std::vector<double>{0.0});
    QCOMPARE(button->keyState(), app::Keying::KeyState::KeyHere);
    const float base = doc().state().findMaterial(id)->roughness;

    // An edit of the animated field at frame 120 keys it there, one step.
    clock().setFrame(120);
    QCOMPARE(button->keyState(), app::Keying::KeyState::Animated);
    auto* spin = panel->findChild<app::ScrubSpinBox*>("material.roughness");
    QVERIFY(spin);
    const double edited = base > 0.5f ? 0.1 : 0.9;
    spin->setValue(edited);
    emit spin->editingFinished();
    QCOMPARE(doc().undoStack()->index(), steps + 2);
    QCOMPARE(times(target, "material.roughness"), (std::vector<double>{0.0, 2.0}));
    QCOMPARE(double(clock().state().findMaterial(id)->roughness), double(float(edited)));
    // Halfway, the panel shows the value between the keys.
    clock().setFrame(60);
    const double mid = double(clock().state().findMaterial(id)->roughness);
    QVERIFY(mid > std::min(double(base), edited) && mid < std::max(double(base), edited));
    QCOMPARE(spin->value(), spin->valueFromText(spin->textFromValue(mid)));
    // The dope sheet: a row named after the material, its track below.
    const auto& rows = w_->timeline()->dopeSheet()->rows();
    const QString name = QString::fromStdString(doc().state().findMaterial(id)->name);
    QVERIFY(std::any_of(rows.begin(), rows.end(),
                        [&](const app::TimelineRow& r) { return r.entity == target && r.isEntity() && r.label == name; }));
    QVERIFY(std::any_of(rows.begin(), rows.end(), [&](const app::TimelineRow& r) {
      return r.entity == target && r.property == "material.roughness" && r.label == "Roughness";
    }));
    // A click on the material's row shows it in the Materials panel.
    {
      app::TimelineDopeSheet* ds = w_->timeline()->dopeSheet();
      const auto other = std::find_if(doc().state().materials.begin(), doc().state().materials.end(),
                                      [&](const auto& m) { return m.first != id; });
      QVERIFY(other != doc().state().materials.end());
      panel->select(other->first);
      // Fold the other rows so that the material's is in view.
      std::vector<uint64_t> folded;
      for (const app::TimelineRow& r : std::vector<app::TimelineRow>(ds->rows()))
        if (r.isEntity() && r.entity != target) folded.push_back(r.entity);
      for (uint64_t e : folded) ds->setCollapsed(e, true);
      int row = -1;
      for (size_t i = 0; i < ds->rows().size(); ++i)
        if (ds->rows()[i].entity == target && ds->rows()[i].isEntity()) row = int(i);
      QVERIFY(row >= 0);
      const QPoint at(60, app::TimelineDopeSheet::kRulerHeight + row * app::TimelineDopeSheet::kRowHeight + 10);
      QVERIFY2(at.y() < ds->height(), "the material's row is below the dope sheet's visible part");
      const std::vector<scene::EntityId> selected = w_->selection().ids();
      QTest::mouseClick(ds, Qt::LeftButton, Qt::NoModifier, at);
      QCOMPARE(panel->selected(), id);
      QCOMPARE(w_->selection().ids(), selected);  // a material is not an entity to select
      for (uint64_t e : folded) ds->setCollapsed(e, false);
    }
    // Undo takes the second key back, then the first.
    doc().undoStack()->undo();
    QCOMPARE(times(target, "material.roughness"), std::vector<double>{0.0});
    doc().undoStack()->undo();
    QVERIFY(!doc().state().sequence.findBinding(target));
    QCOMPARE(doc().state().findMaterial(id)->roughness, base);
  }

  void settingsFieldKeyButtonAndEdit() {
    app::SettingsPanel* panel = w_->sceneSettings();
    QVERIFY(!panel->keyButtonFor("fog_mode"));
    app::KeyButton* button = panel->keyButtonFor("ao_strength");
    QVERIFY(button);
    const uint64_t target = scene::settingsTarget();
    const float base = doc().state().settings.aoStrength;
    QVERIFY(base != 3.0f);
    clock().setFrame(0);
    const int steps = doc().undoStack()->index();
    QTest::mouseClick(button, Qt::LeftButton);
    QCOMPARE(times(target, "settings.ao_strength"), std::vector<double>{0.0});
    clock().setFrame(240);
    auto* spin = panel->findChild<app::ScrubSpinBox*>("settings.ao_strength");
    QVERIFY(spin);
    spin->setValue(3.0);
    emit spin->editingFinished();
    QCOMPARE(doc().undoStack()->index(), steps + 2);
    QCOMPARE(times(target, "settings.ao_strength"), (std::vector<double>{0.0, 4.0}));
    QCOMPARE(clock().state().settings.aoStrength, 3.0f);
    clock().setFrame(0);
    QCOMPARE(clock().state().settings.aoStrength, base);  // the first key, though the document now holds 3
    QCOMPARE(spin->value(), double(clock().state().settings.aoStrength));
    const auto& rows = w_->timeline()->dopeSheet()->rows();
    QVERIFY(std::any_of(rows.begin(), rows.end(),
                        [&](const app::TimelineRow& r) { return r.entity == target && r.label == "Settings"; }));
    QVERIFY(std::any_of(rows.begin(), rows.end(), [&](const app::TimelineRow& r) {
      return r.entity == target && r.property == "settings.ao_strength" && r.label == "AO strength";
    }));
    doc().undoStack()->undo();
    doc().undoStack()->undo();
    QVERIFY(times(target, "settings.ao_strength").empty());  // the demo's fog track stays
  }

  void lightsDockListsEditsAddsAndDeletes() {
    app::LightsPanel* panel = w_->lightsPanel();
    QVERIFY(panel);
    // Every light of the scene, in the document's order.
    std::vector<scene::EntityId> expected;
    for (scene::EntityId id : doc().state().depthFirstOrder())
      if (doc().state().find(id)->light) expected.push_back(id);
    QVERIFY(expected.size() >= 2);
    QCOMPARE(panel->lights(), expected);
    QCOMPARE(panel->table()->rowCount(), int(expected.size()));
    // One column per field of the light component, after the name.
    QCOMPARE(panel->table()->columnCount(), int(scene::findComponent("light")->fields.size()) + 1);
    // Intensity in lux for a sun, lumens for the others.
    for (scene::EntityId id : expected) {
      const bool sun = doc().state().find(id)->light->type == scene::Light::Type::Sun;
      QCOMPARE(panel->intensityUnit(id), QString(sun ? "lx" : "lm"));
      auto* spin = panel->editorFor(id, "intensity")->findChild<app::ScrubSpinBox*>();
      QVERIFY(spin);
      QVERIFY2(spin->suffix().contains(sun ? "lx" : "lm"), qPrintable(spin->suffix()));
      QCOMPARE(panel->editorFor(id, "outer_cone_deg")->isEnabled(),
               doc().state().find(id)->light->type == scene::Light::Type::Spot);
    }

    // An edit in the table: one undo step, the document's value.
    const scene::EntityId first = expected.front();
    auto* range = panel->editorFor(expected.back(), "range")->findChild<app::ScrubSpinBox*>();
    const float before = doc().state().find(expected.back())->light->range;
    const int steps = doc().undoStack()->index();
    range->setValue(double(before) + 7.0);
    emit range->editingFinished();
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    QCOMPARE(doc().state().find(expected.back())->light->range, before + 7.0f);
    doc().undoStack()->undo();
    QCOMPARE(doc().state().find(expected.back())->light->range, before);

    // Selecting a row selects the light in the editor (the outliner follows).
    panel->table()->selectRow(0);
    QCOMPARE(w_->selection().ids(), std::vector<scene::EntityId>{first});
    auto* outliner = w_->outliner()->view();
    auto* model = static_cast<app::OutlinerModel*>(outliner->model());
    QVERIFY(outliner->selectionModel()->isSelected(model->indexOf(first)));
    // And the other way round.
    w_->selection().select(expected.back());
    const auto rows = panel->table()->selectionModel()->selectedRows();
    QCOMPARE(rows.size(), 1);
    QCOMPARE(rows.front().row(), int(expected.size()) - 1);

    // Add a spot light: a new row, undoable.
    QTest::mouseClick(panel->addButton(scene::Light::Type::Spot), Qt::LeftButton);
    QCOMPARE(panel->lights().size(), expected.size() + 1);
    const scene::EntityId spot = w_->selection().primary();
    QVERIFY(doc().state().find(spot)->light);
    QCOMPARE(doc().state().find(spot)->light->type, scene::Light::Type::Spot);
    QVERIFY(std::find(panel->lights().begin(), panel->lights().end(), spot) != panel->lights().end());
    // Delete it (it is selected), then undo both ways.
    QTest::mouseClick(panel->deleteButton(), Qt::LeftButton);
    QVERIFY(!doc().state().find(spot));
    QCOMPARE(panel->lights(), expected);
    doc().undoStack()->undo();
    QVERIFY(doc().state().find(spot));
    QCOMPARE(panel->lights().size(), expected.size() + 1);
    doc().undoStack()->undo();
    QCOMPARE(panel->lights(), expected);
  }

  // Each row of the Lights dock keys its own light, whatever is selected;
  // an enum (the type) has no key button.
  void lightsDockKeyButtonsKeyTheirRow() {
    app::LightsPanel* panel = w_->lightsPanel();
    const std::vector<scene::EntityId> lights = panel->lights();
    QVERIFY(lights.size() >= 2);
    const scene::EntityId light = lights.back();
    w_->selection().select(lights.front());
    QVERIFY(!panel->keyButtonFor(light, "type"));
    app::KeyButton* button = panel->keyButtonFor(light, "intensity");
    QVERIFY(button);
    clock().setFrame(30);
    const double t = clock().time();
    const std::vector<double> before = times(light, "light.intensity");
    const std::vector<double> selectedBefore = times(lights.front(), "light.intensity");
    const int steps = doc().undoStack()->index();
    QTest::mouseClick(button, Qt::LeftButton);
    QCOMPARE(doc().undoStack()->index(), steps + 1);
    const std::vector<double> after = times(light, "light.intensity");
    QVERIFY(std::find(after.begin(), after.end(), t) != after.end());
    QCOMPARE(button->keyState(), app::Keying::KeyState::KeyHere);
    QCOMPARE(times(lights.front(), "light.intensity"), selectedBefore);  // not the selected light
    doc().undoStack()->undo();
    QCOMPARE(times(light, "light.intensity"), before);
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  scene::Document& doc() { return w_->document(); }
  app::TimelineClock& clock() { return *w_->timelineClock(); }
  std::vector<double> times(uint64_t target, const std::string& p) {
    return sequencer::keyTimes(doc().state().sequence, target, p);
  }

  std::unique_ptr<MainWindow> w_;
};

QTEST_MAIN(ObjectTracksTest)
#include "test_editor_object_tracks.moc"
