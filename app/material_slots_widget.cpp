#include "app/material_slots_widget.h"

#include <QComboBox>
#include <QFormLayout>
#include <QLabel>

#include "scene/material_ops.h"

namespace hs::app {

MaterialSlotsWidget::MaterialSlotsWidget(scene::Document& doc, QWidget* parent) : QWidget(parent), doc_(doc) {
  setObjectName("materialSlots");
  form_ = new QFormLayout(this);
  form_->setContentsMargins(0, 0, 0, 0);
  form_->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form_->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form_->setVerticalSpacing(4);
}

QComboBox* MaterialSlotsWidget::chooser(size_t slot) const {
  return slot < choosers_.size() ? choosers_[slot] : nullptr;
}

void MaterialSlotsWidget::showAsset(const scene::SceneState& state, scene::AssetId asset) {
  const scene::MeshAsset* a = state.findAsset(asset);
  // Rebuilding while the user has a list open would close it: only when
  // something it shows changed.
  std::string key = std::to_string(asset) + "|";
  if (a)
    for (scene::MaterialId m : a->materialSlots) key += std::to_string(m) + ",";
  for (const auto& [id, m] : state.materials) key += std::to_string(id) + ":" + m.name + "|";
  if (key == shownKey_) return;
  shownKey_ = key;
  asset_ = asset;
  while (form_->rowCount() > 0) form_->removeRow(0);
  choosers_.clear();
  if (!a) return;
  for (size_t slot = 0; slot < a->materialSlots.size(); ++slot) {
    auto* combo = new QComboBox(this);
    combo->setObjectName(QString("materialSlot%1").arg(slot));
    for (const auto& [id, m] : state.materials)
      combo->addItem(QString::fromStdString(m.name), QVariant::fromValue<qulonglong>(id));
    combo->setCurrentIndex(combo->findData(QVariant::fromValue<qulonglong>(a->materialSlots[slot])));
    combo->setToolTip("The material this slot of the mesh draws with (every entity showing the mesh follows)");
    connect(combo, &QComboBox::activated, this, [this, slot, combo](int index) {
      if (index < 0) return;
      std::string error;
      const auto material = scene::MaterialId(combo->itemData(index).toULongLong());
      if (!scene::ops::assignMaterial(doc_, asset_, slot, material, error) && !error.empty())
        emit problem(QString::fromStdString(error));
    });
    auto* label = new QLabel(QString("Slot %1").arg(slot), this);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    form_->addRow(label, combo);
    choosers_.push_back(combo);
  }
}

}  // namespace hs::app
