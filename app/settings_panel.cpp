#include "app/settings_panel.h"

#include <QFormLayout>
#include <QLabel>
#include <QScrollArea>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "scene/operations.h"

namespace hs::app {

SettingsPanel::SettingsPanel(scene::Document& doc, QWidget* parent) : QWidget(parent), doc_(doc) {
  setObjectName("settingsPanel");
  auto* content = new QWidget;
  auto* form = new QFormLayout(content);
  form->setContentsMargins(8, 8, 8, 8);
  form->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form->setVerticalSpacing(4);
  for (const auto& f : scene::settingsFields()) {
    FieldEditor* ed = createFieldEditor(specOf(f, "settings." + f.key), content);
    const scene::SettingsField* field = &f;
    ed->setOnEdited([this, field](const scene::FieldValue& value, int component, const QString& key) {
      scene::FieldValue v = value;
      if (component >= 0) {
        glm::dvec3 current = std::get<glm::dvec3>(field->get(doc_.state().settings));
        current[component] = std::get<glm::dvec3>(value)[component];
        v = current;
      }
      scene::ops::setSettingsField(doc_, *field, v, key);
    });
    auto* label = new QLabel(QString::fromStdString(f.label), content);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    form->addRow(label, ed);
    rows_.emplace_back(field, ed);
    byKey_[f.key] = ed;
  }
  putInScrollArea(this, content);
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.settings || c.reset) refresh();
  });
  refresh();
}

FieldEditor* SettingsPanel::editorFor(const std::string& key) const {
  auto it = byKey_.find(key);
  return it == byKey_.end() ? nullptr : it->second;
}

void SettingsPanel::refresh() {
  for (const auto& [field, editor] : rows_) editor->setValue(field->get(doc_.state().settings));
}

}  // namespace hs::app
