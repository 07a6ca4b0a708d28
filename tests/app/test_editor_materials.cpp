// The Materials panel as a user reaches it: from a mesh's properties
// ("Materials…"), its list, a field edited through the panel's editors as
// one undo step, a refused value's message, the preview sphere rendered
// on its worker with the material (and again when the material changes),
// New / Delete with the mesh's slot list, and a translucent material's OIT
// figures in the Scene Settings dock.
#include <QComboBox>
#include <QDockWidget>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSignalSpy>
#include <QtTest>

#include "app/field_editors.h"
#include "app/main_window.h"
#include "app/material_slots_widget.h"
#include "app/materials_panel.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "app/settings_panel.h"
#include "app/status_bar.h"
#include "app/viewport_widget.h"
#include "editor_fixture.h"
#include "scene/material_ops.h"
#include "scene/operations.h"

using namespace hs;

namespace {

QColor pixel(const QImage& img, int x, int y) { return img.pixelColor(x, y); }

}  // namespace

class EditorMaterialsTest : public QObject {
  Q_OBJECT
 public:
  static void initMain() { test::initEditorMain(); }

 private slots:
  void initTestCase() {
    app::initApplicationSettings();
    w_ = std::make_unique<app::MainWindow>();
    test::setQuietPrompts(*w_);
    w_->resize(1100, 760);
    w_->loadDemoScene();
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
  }

  void reachedFromTheMeshProperties() {
    const scene::SceneState& s = w_->document().state();
    const scene::EntityId bunny = s.findByName("Stanford Bunny");
    QVERIFY(bunny != scene::kNoEntity);
    w_->selection().select(bunny);
    QPushButton* button = nullptr;
    QTRY_VERIFY((button = w_->properties()->findChild<QPushButton*>("meshMaterials")) != nullptr);
    button->click();
    const scene::MeshAsset* a = s.findAsset(s.find(bunny)->mesh->mesh);
    QVERIFY(a && !a->materialSlots.empty());
    app::MaterialsPanel* panel = w_->materialsPanel();
    QCOMPARE(panel->selected(), a->materialSlots.front());
    QVERIFY(w_->findChild<QDockWidget*>("materialsDock")->isVisible());
    auto* list = panel->findChild<QListWidget*>("materialList");
    QCOMPARE(size_t(list->count()), s.materials.size());
    QCOMPARE(list->currentItem()->text().toStdString(), s.materials.at(panel->selected()).name);
  }

  void previewShowsTheMaterial() {
    app::MaterialsPanel* panel = w_->materialsPanel();
    QSignalSpy spy(panel, &app::MaterialsPanel::previewUpdated);
    std::string error;
    QVERIFY(scene::ops::setMaterialField(w_->document(), panel->selected(), *scene::findMaterialField("base_color"),
                                         scene::FieldValue(glm::dvec3(0.9, 0.05, 0.05)), error));
    QTRY_VERIFY_WITH_TIMEOUT(spy.count() >= 1, 20000);
    // Wait for the image of the red material (an earlier request may land first).
    // (Below the highlight, where the colour is least washed out by it.)
    auto hue = [&](int a, int b) {
      const QColor c = pixel(panel->previewImage(), 88, 96);
      const int ch[3] = {c.red(), c.green(), c.blue()};
      return ch[a] - ch[b];
    };
    QTRY_VERIFY_WITH_TIMEOUT(hue(0, 1) > 60, 20000);
    const QImage red = panel->previewImage();
    QCOMPARE(red.width(), 160);
    // A sphere on a backdrop: the corner is not the material.
    QVERIFY(pixel(red, 2, 2) != pixel(red, 80, 80));
    QVERIFY(scene::ops::setMaterialField(w_->document(), panel->selected(), *scene::findMaterialField("base_color"),
                                         scene::FieldValue(glm::dvec3(0.05, 0.2, 0.9)), error));
    QTRY_VERIFY_WITH_TIMEOUT(hue(2, 0) > 60, 20000);
  }

  void editIsOneUndoStep() {
    app::MaterialsPanel* panel = w_->materialsPanel();
    auto* spin = panel->findChild<app::ScrubSpinBox*>("material.roughness");
    QVERIFY(spin);
    const scene::MaterialId id = panel->selected();
    const float before = w_->document().state().materials.at(id).roughness;
    const int steps = w_->document().undoStack()->count();
    spin->setValue(0.12);
    spin->setValue(0.1);
    emit spin->editingFinished();
    QCOMPARE(w_->document().undoStack()->count(), steps + 1);
    QCOMPARE(w_->document().state().materials.at(id).roughness, 0.1f);
    w_->document().undoStack()->undo();
    QCOMPARE(w_->document().state().materials.at(id).roughness, before);
    QTRY_COMPARE(spin->value(), double(before));
    // The lighting model from its list of choices.
    auto* model = panel->findChild<QComboBox*>("material.model");
    QVERIFY(model);
    model->setCurrentIndex(int(scene::LightingModel::Lambert));
    emit model->activated(int(scene::LightingModel::Lambert));  // what a user's pick sends
    QCOMPARE(w_->document().state().materials.at(id).model, scene::LightingModel::Lambert);
  }

  void refusedValueIsNamed() {
    app::MaterialsPanel* panel = w_->materialsPanel();
    auto* name = panel->findChild<QLineEdit*>("material.name");
    QVERIFY(name);
    const std::string before = w_->document().state().materials.at(panel->selected()).name;
    QSignalSpy problems(panel, &app::MaterialsPanel::problem);
    name->setText("   ");
    emit name->editingFinished();
    QCOMPARE(w_->document().state().materials.at(panel->selected()).name, before);
    QCOMPARE(problems.count(), 1);
    const QString message = problems.front().front().toString();
    QVERIFY2(message == QString::fromStdString("material '" + before + "': name: a material needs a name"),
             qPrintable(message));
    QVERIFY(panel->findChild<QLabel*>("materialError")->isVisible());
  }

  // New copies the material shown; the mesh's slot list puts it on the
  // bunny (one undo step); Delete refuses it while the slot uses it and
  // removes the bunny's own one once it is free.
  void newAssignDelete() {
    const scene::SceneState& s = w_->document().state();
    const scene::EntityId bunny = s.findByName("Stanford Bunny");
    w_->selection().select(bunny);
    const scene::AssetId asset = s.find(bunny)->mesh->mesh;
    const scene::MaterialId own = s.findAsset(asset)->materialSlots.front();
    app::MaterialsPanel* panel = w_->materialsPanel();
    panel->select(own);
    const size_t before = s.materials.size();
    panel->findChild<QPushButton*>("newMaterial")->click();
    QCOMPARE(s.materials.size(), before + 1);
    const scene::MaterialId made = panel->selected();
    QVERIFY(made != own);
    QCOMPARE(s.materials.at(made).roughness, s.materials.at(own).roughness);
    QCOMPARE(s.materials.at(made).asset, scene::kNoAsset);

    app::MaterialSlotsWidget* slotList = nullptr;
    QTRY_VERIFY((slotList = w_->properties()->materialSlots()) != nullptr);
    QTRY_VERIFY(slotList->chooser(0) != nullptr);
    QComboBox* slot0 = slotList->chooser(0);
    QCOMPARE(slot0->currentText().toStdString(), s.materials.at(own).name);
    const int index = slot0->findData(QVariant::fromValue<qulonglong>(made));
    QVERIFY(index >= 0);
    const int steps = w_->document().undoStack()->count();
    slot0->setCurrentIndex(index);
    emit slot0->activated(index);
    QCOMPARE(s.findAsset(asset)->materialSlots.front(), made);
    QCOMPARE(w_->document().undoStack()->count(), steps + 1);

    QSignalSpy problems(panel, &app::MaterialsPanel::problem);
    panel->select(made);
    panel->findChild<QPushButton*>("deleteMaterial")->click();
    QVERIFY(s.findMaterial(made));
    QCOMPARE(problems.count(), 1);
    QVERIFY2(problems.front().front().toString().contains("is used by mesh asset"),
             qPrintable(problems.front().front().toString()));
    panel->select(own);
    panel->findChild<QPushButton*>("deleteMaterial")->click();
    QVERIFY(!s.findMaterial(own));
    // Undo brings the bunny's material and its slot back.
    w_->document().undoStack()->undo();
    w_->document().undoStack()->undo();
    QVERIFY(s.findMaterial(own));
    QCOMPARE(s.findAsset(asset)->materialSlots.front(), own);
    QTRY_COMPARE(w_->properties()->materialSlots()->chooser(0)->currentText().toStdString(), s.materials.at(own).name);
  }

  // A translucent material in view: the Scene Settings dock's Transparency
  // block shows the frame's OIT figures (mode, memory, fragments per pixel,
  // overflow) as the renderer reported them; another mode shows in the
  // next frame, and with every material opaque it says no OIT buffers.
  void translucencyFiguresInSceneSettings() {
    const scene::SceneState& s = w_->document().state();
    const scene::EntityId bunny = s.findByName("Stanford Bunny");
    const scene::MaterialId m = s.findAsset(s.find(bunny)->mesh->mesh)->materialSlots.front();
    std::string error;
    QVERIFY2(scene::ops::setMaterialField(w_->document(), m, *scene::findMaterialField("opacity"),
                                          scene::FieldValue(0.4), error),
             error.c_str());
    auto* label = w_->sceneSettings()->findChild<QLabel*>("oitStats");
    QVERIFY(label);
    app::ViewportWidget* vp = w_->viewport();
    // Fragments are counted with the pass timings, every few frames.
    QTRY_VERIFY_WITH_TIMEOUT(vp->lastStats().oit.active && vp->lastStats().oit.counted, 30000);
    const render::OitStats o = vp->lastStats().oit;
    QCOMPARE(o.mode, std::string("abuffer"));
    QVERIFY(o.bytes > 0 && o.maxPerPixel >= 2);
    QVERIFY2(label->text().startsWith("abuffer: " + app::formatBytes(o.bytes)), qPrintable(label->text()));
    QVERIFY2(label->text().contains(QString("fragments per pixel: max %1, mean %2")
                                        .arg(o.maxPerPixel)
                                        .arg(o.meanPerPixel, 0, 'f', 2)),
             qPrintable(label->text()));
    QVERIFY2(label->text().contains("no overflow"), qPrintable(label->text()));
    const scene::SettingsField* mode = scene::findSettingsField("transparency");
    const auto kbuffer = scene::parseFieldValue(*mode, "kbuffer", error);
    QVERIFY(kbuffer && scene::ops::setSettingsField(w_->document(), *mode, *kbuffer, QString()));
    QTRY_VERIFY_WITH_TIMEOUT(label->text().startsWith("kbuffer: "), 30000);
    QVERIFY(label->text().contains(QString("%1 layers per pixel").arg(s.settings.kbufferK)));
    // Every material opaque (the bunny's and the demo's glass and pond) and
    // no particles.
    std::vector<scene::MaterialId> translucent;
    for (const auto& [mid, mat] : s.materials)
      if (mat.opacity < 1.0f) translucent.push_back(mid);
    QVERIFY(translucent.size() >= 2);
    for (scene::MaterialId t : translucent)
      QVERIFY(scene::ops::setMaterialField(w_->document(), t, *scene::findMaterialField("opacity"),
                                           scene::FieldValue(1.0), error));
    // The particles (snow, fog, smoke) are translucent too: hidden.
    std::vector<scene::EntityId> emitters;
    for (const auto& [eid, e] : w_->document().state().entities)
      if (e.particles) emitters.push_back(eid);
    QVERIFY(!emitters.empty());
    for (scene::EntityId eid : emitters)
      QVERIFY(scene::ops::setField(w_->document(), eid, *scene::findEntityField("entity.visible"), scene::FieldValue(false)));
    QTRY_VERIFY_WITH_TIMEOUT(label->text().startsWith("No translucent surface in view"), 30000);
  }

  void cleanupTestCase() { w_.reset(); }

 private:
  std::unique_ptr<app::MainWindow> w_;
};

QTEST_MAIN(EditorMaterialsTest)
#include "test_editor_materials.moc"
