#include "app/materials_panel.h"

#include <QComboBox>
#include <QFormLayout>
#include <QImage>
#include <QLabel>
#include <QListWidget>
#include <QPixmap>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/material_preview.h"
#include "scene/material_ops.h"

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
      const scene::Material* m = doc_.state().findMaterial(current_);
      if (!m) return;
      if (component >= 0) {
        glm::dvec3 now = std::get<glm::dvec3>(field->get(*m));
        now[component] = std::get<glm::dvec3>(value)[component];
        v = now;
      }
      apply(*field, v, key);
    });
    form->addRow(label, ed);
    rows_.emplace_back(field, ed);
    byKey_[f.key] = ed;
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

void MaterialsPanel::select(scene::MaterialId id) {
  if (!doc_.state().findMaterial(id)) return;
  current_ = id;
  rebuildList();
}

void MaterialsPanel::apply(const scene::MaterialField& field, const scene::FieldValue& value, const QString& mergeKey) {
  std::string error;
  if (!scene::ops::setMaterialField(doc_, current_, field, value, error, mergeKey) && !error.empty()) {
    error_->setText(QString::fromStdString(error));
    error_->show();
    emit problem(QString::fromStdString(error));
    refreshValues();  // back to the document's value
    return;
  }
  error_->hide();
}

void MaterialsPanel::rebuildList() {
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
  const scene::Material* m = doc_.state().findMaterial(current_);
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
  requestPreview();
}

void MaterialsPanel::requestPreview() {
  if (const scene::Material* m = doc_.state().findMaterial(current_)) renderer_->request(doc_.state(), *m);
}

}  // namespace hs::app
