// The Camera section's post settings: the scene settings this camera
// overrides (scene/camera_post.h), one row each with a button that gives
// the field back to the scene, and a list of the others to override. Rows
// are entity fields ("camera.post.bloom.intensity"), so they are edited,
// undone and keyed on the timeline like the camera's own fields.
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>

#include "app/field_editors.h"
#include "app/property_panel.h"
#include "app/selection.h"
#include "scene/camera_post.h"
#include "scene/operations.h"

namespace hs::app {

void PropertyPanel::buildCameraPost(QFormLayout* form, QWidget* body, const scene::ComponentInfo& camera,
                                    const scene::Entity& e) {
  auto* title = new QLabel("Post settings (this camera's, over the scene's)", body);
  title->setStyleSheet("QLabel { color: #c9cacd; font-weight: bold; padding-top: 4px; }");
  form->addRow(title);
  for (const auto& [key, value] : e.camera->post) {
    const scene::EntityField* field = scene::findCameraPostField(key);
    if (!field) continue;
    const std::string path = "camera." + field->key;
    FieldEditor* ed = createFieldEditor(specOf(*field, path), body);
    const scene::ComponentInfo* comp = &camera;
    ed->setOnEdited([this, field, comp](const scene::FieldValue& v, int component, const QString& mergeKey) {
      apply(*field, *comp, v, component, mergeKey);
    });
    auto* row = new QWidget(body);
    auto* h = new QHBoxLayout(row);
    h->setContentsMargins(0, 0, 0, 0);
    h->setSpacing(2);
    h->addWidget(decorator_ ? decorator_(path, ed, row) : static_cast<QWidget*>(ed), 1);
    auto* reset = new QToolButton(row);
    reset->setObjectName("resetPost_" + QString::fromStdString(key));
    reset->setText("↺");
    reset->setAutoRaise(true);
    reset->setToolTip("Use the scene's value again (hybridscape-cli set CAMERA " + QString::fromStdString(path) +
                      " inherit)");
    connect(reset, &QToolButton::clicked, this, [this, key = key] {
      // Every selected camera that overrides it (one undo step each), as
      // an edit here applies to the whole selection.
      for (scene::EntityId target : selection_.ids()) scene::ops::clearCameraPost(doc_, target, key);
    });
    h->addWidget(reset);
    auto* label = new QLabel(QString::fromStdString(field->label), body);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    form->addRow(label, row);
    rows_.push_back({comp, field, ed});
    byPath_[path] = ed;
  }
  // The settings not yet overridden: choosing one copies the scene's value
  // to the camera, to be changed from there.
  auto* add = new QComboBox(body);
  add->setObjectName("overridePost");
  add->addItem("Override a post setting…");
  for (const scene::EntityField& f : scene::cameraPostFields()) {
    const std::string key = f.key.substr(5);
    if (!e.camera->post.count(key)) add->addItem(QString::fromStdString(f.label), QString::fromStdString(key));
  }
  add->setToolTip("The settings of the Post dock (and exposure, tone map, anti-aliasing) this camera shows "
                  "differently from the scene");
  const scene::ComponentInfo* comp = &camera;
  connect(add, qOverload<int>(&QComboBox::activated), this, [this, add, comp](int index) {
    if (index <= 0) return;
    const std::string key = add->itemData(index).toString().toStdString();
    const scene::EntityField* field = scene::findCameraPostField(key);
    const scene::SettingsField* setting = scene::cameraPostSetting(key);
    if (field && setting) apply(*field, *comp, setting->get(doc_.state().settings), -1, {});
  });
  form->addRow(add);
}

}  // namespace hs::app
