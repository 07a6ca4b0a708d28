#include "app/materials_panel.h"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QLayout>
#include <QListWidget>
#include <QPixmap>
#include <QPushButton>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/material_preview.h"
#include "app/timeline_clock.h"
#include "app/timeline_keying.h"
#include "scene/material_ops.h"
#include "scene/object_tracks.h"

namespace hs::app {

MaterialsPanel::MaterialsPanel(scene::Document& doc, QWidget* parent)
    : QWidget(parent), doc_(doc), lastImage_(new QImage) {
  setObjectName("materialsPanel");
  auto* content = new QWidget;
  auto* layout = new QVBoxLayout(content);
  layout->setContentsMargins(8, 8, 8, 8);
  list_ = new QListWidget(content);
  list_->setObjectName("materialList");
  list_->setMaximumHeight(140);
  layout->addWidget(list_);
  // New copies the material shown (a start for a variant); Delete refuses a
  // material a mesh slot still uses, naming the slot (material_ops.h).
  auto* buttons = new QHBoxLayout;
  auto* add = new QPushButton("New", content);
  add->setObjectName("newMaterial");
  add->setToolTip("Add a material of the scene's own, a copy of the one shown");
  connect(add, &QPushButton::clicked, this, [this] { addMaterial(); });
  auto* remove = new QPushButton("Delete", content);
  remove->setObjectName("deleteMaterial");
  remove->setToolTip("Delete the material shown (only when no mesh slot uses it)");
  connect(remove, &QPushButton::clicked, this, [this] { deleteMaterial(); });
  buttons->addWidget(add);
  buttons->addWidget(remove);
  buttons->addStretch(1);
  layout->addLayout(buttons);
  preview_ = new QLabel(content);
  preview_->setObjectName("materialPreview");
  preview_->setAlignment(Qt::AlignCenter);
  preview_->setMinimumSize(160, 160);
  layout->addWidget(preview_);
  error_ = new QLabel(content);
  error_->setObjectName("materialError");
  error_->setWordWrap(true);
  error_->setStyleSheet("QLabel { color: #e0745c; }");
  error_->hide();
  layout->addWidget(error_);

  form_ = new QWidget(content);
  auto* form = new QFormLayout(form_);
  form->setContentsMargins(0, 0, 0, 0);
  form->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form->setVerticalSpacing(4);
  for (const auto& f : scene::materialFields()) {
    const scene::MaterialField* field = &f;
    auto* label = new QLabel(QString::fromStdString(f.label), form_);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    if (f.type == scene::FieldType::AssetRef) {
      // A texture: one of the scene's, or none.
      auto* combo = new QComboBox(form_);
      combo->setObjectName(QString::fromStdString("material." + f.key));
      connect(combo, &QComboBox::currentIndexChanged, this, [this, field, combo](int index) {
        if (updating_ || index < 0) return;
        apply(*field, scene::FieldValue(combo->itemData(index).toLongLong()), {});
      });
      form->addRow(label, combo);
      textures_[f.key] = combo;
      continue;
    }
    FieldEditor* ed = createFieldEditor(specOf(f, "material." + f.key), form_);
    ed->setOnEdited([this, field](const scene::FieldValue& value, int component, const QString& key) {
      scene::FieldValue v = value;
      const scene::Material* m = shown().findMaterial(current_);
      if (!m) return;
      if (component >= 0) {
        glm::dvec3 now = std::get<glm::dvec3>(field->get(*m));
        now[component] = std::get<glm::dvec3>(value)[component];
        v = now;
      }
      apply(*field, v, key);
    });
    QWidget* row = editorRow(form_, ed);
    form->addRow(label, row);
    rows_.emplace_back(field, ed);
    byKey_[f.key] = ed;
    rowOf_[f.key] = row;
  }
  layout->addWidget(form_);
  layout->addStretch(1);
  putInScrollArea(this, content);

  renderer_ = new MaterialPreview(160, this);
  connect(renderer_, &MaterialPreview::ready, this, [this](const QImage& img) {
    *lastImage_ = img;
    preview_->setPixmap(QPixmap::fromImage(img));
    emit previewUpdated();
  });
  connect(renderer_, &MaterialPreview::problem, this, &MaterialsPanel::problem);
  connect(list_, &QListWidget::currentRowChanged, this, [this](int row) {
    if (updating_ || row < 0) return;
    current_ = scene::MaterialId(list_->item(row)->data(Qt::UserRole).toULongLong());
    refreshValues();
  });
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.materials || c.reset) rebuildList();
  });
  rebuildList();
}

MaterialsPanel::~MaterialsPanel() { delete lastImage_; }

const QImage& MaterialsPanel::previewImage() const { return *lastImage_; }

FieldEditor* MaterialsPanel::editorFor(const std::string& key) const {
  auto it = byKey_.find(key);
  return it == byKey_.end() ? nullptr : it->second;
}

QComboBox* MaterialsPanel::textureChooser(const std::string& key) const {
  auto it = textures_.find(key);
  return it == textures_.end() ? nullptr : it->second;
}

void MaterialsPanel::enableKeying(Keying& keying, TimelineClock& clock) {
  keying_ = &keying;
  clock_ = &clock;
  for (const auto& [key, row] : rowOf_) {
    const std::string path = std::string(scene::kMaterialTrackPrefix) + key;
    std::string error;
    if (!scene::animationTarget(path, error)) continue;  // enums, names: not animatable
    auto* button = new KeyButton(
        keying, [this] { return std::vector<uint64_t>{scene::materialTarget(current_)}; }, clock, path, row);
    row->layout()->addWidget(button);
    keyButtons_[key] = button;
  }
  connect(&clock, &TimelineClock::stateChanged, this, [this] {
    if (!updating_) refreshValues();
  });
  refreshValues();
}

KeyButton* MaterialsPanel::keyButtonFor(const std::string& key) const {
  auto it = keyButtons_.find(key);
  return it == keyButtons_.end() ? nullptr : it->second;
}

const scene::SceneState& MaterialsPanel::shown() const { return clock_ ? clock_->state() : doc_.state(); }

void MaterialsPanel::select(scene::MaterialId id) {
  if (!doc_.state().findMaterial(id)) return;
  current_ = id;
  rebuildList();
}

void MaterialsPanel::apply(const scene::MaterialField& field, const scene::FieldValue& value, const QString& mergeKey) {
  std::string error;
  // With keying on every edit has a merge key, so a key it sets joins its step.
  const QString key = mergeKey.isEmpty() && keying_ ? QString("material-%1").arg(++editCounter_) : mergeKey;
  if (!scene::ops::setMaterialField(doc_, current_, field, value, error, key) && !error.empty()) {
    showError(error);
    refreshValues();  // back to the document's value
    return;
  }
  error_->hide();
  // An animated field keeps the edit as a key at this frame (else its track
  // would put the old value back at once); with Auto Key, any field.
  if (keying_) keying_->afterEdit({scene::materialTarget(current_)}, {std::string(scene::kMaterialTrackPrefix) + field.key}, key);
}

void MaterialsPanel::showError(const std::string& error) {
  error_->setText(QString::fromStdString(error));
  error_->show();
  emit problem(QString::fromStdString(error));
}

void MaterialsPanel::addMaterial() {
  const scene::SceneState& s = doc_.state();
  QString name;
  for (int n = 1; name.isEmpty() || s.findMaterialByName(name.toStdString()) != scene::kNoMaterial; ++n)
    name = QString("Material %1").arg(n);
  std::string error;
  const scene::MaterialId id = scene::ops::addMaterial(doc_, name.toStdString(), current_, error);
  if (id == scene::kNoMaterial) return showError(error);
  error_->hide();
  select(id);
}

void MaterialsPanel::deleteMaterial() {
  std::string error;
  if (current_ == scene::kNoMaterial) return;
  if (!scene::ops::removeMaterial(doc_, current_, error)) return showError(error);
  error_->hide();
}

void MaterialsPanel::rebuildList() {
  previewed_.reset();  // a document change (a texture, say) may change the look: render again
  updating_ = true;
  const scene::SceneState& s = doc_.state();
  if (!s.findMaterial(current_)) current_ = s.materials.empty() ? scene::kNoMaterial : s.materials.begin()->first;
  list_->clear();
  for (const auto& [id, m] : s.materials) {
    auto* item = new QListWidgetItem(QString::fromStdString(m.name), list_);
    item->setData(Qt::UserRole, QVariant::fromValue<qulonglong>(id));
    if (id == current_) list_->setCurrentItem(item);
  }
  for (auto& [key, combo] : textures_) {
    combo->clear();
    combo->addItem("(none)", QVariant::fromValue<qlonglong>(0));
    for (const auto& [id, t] : s.textures) combo->addItem(QString::fromStdString(t.name), QVariant::fromValue<qlonglong>(qlonglong(id)));
  }
  updating_ = false;
  refreshValues();
}

void MaterialsPanel::refreshValues() {
  const scene::Material* m = shown().findMaterial(current_);
  form_->setEnabled(m != nullptr);
  if (!m) {
    preview_->clear();
    return;
  }
  updating_ = true;
  for (const auto& [field, editor] : rows_) editor->setValue(field->get(*m));
  for (auto& [key, combo] : textures_) {
    const scene::MaterialField* f = scene::findMaterialField(key);
    const qlonglong id = qlonglong(std::get<int64_t>(f->get(*m)));
    combo->setCurrentIndex(std::max(0, combo->findData(QVariant::fromValue<qlonglong>(id))));
  }
  updating_ = false;
  for (const auto& [key, button] : keyButtons_) button->refresh();  // the material shown may have changed
  requestPreview();
}

void MaterialsPanel::requestPreview() {
  // Playback changes the shown state every frame; the sphere is rendered
  // again only when the material itself looks different.
  const scene::SceneState& s = shown();
  const scene::Material* m = s.findMaterial(current_);
  if (!m || (previewed_ && *previewed_ == *m)) return;
  previewed_ = *m;
  renderer_->request(s, *m);
}

}  // namespace hs::app
