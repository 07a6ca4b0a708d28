#include "app/property_panel.h"

#include <atomic>

#include <QFormLayout>
#include <QFrame>
#include <QLabel>
#include <QMenu>
#include <QPushButton>
#include <QScrollArea>
#include <QToolButton>
#include <QVBoxLayout>

#include "app/error_report_dialog.h"
#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/material_slots_widget.h"
#include "app/selection.h"
#include "app/terrain_component_picker.h"
#include "particles/emitter.h"
#include "scene/operations.h"

namespace hs::app {
namespace {

std::atomic<int> editCounter{0};

QString formatCount(size_t n) { return QString("%L1").arg(n); }

// "\nLODs: 17,363 (0.12 mm), 4,340 (0.6 mm), ..." for an asset with levels.
QString lodText(const scene::MeshAsset& a) {
  if (a.lods.empty()) return {};
  QStringList levels;
  for (const scene::MeshLod& l : a.lods)
    levels << QString("%1 (%2 mm)").arg(formatCount(l.data ? l.data->triangleCount() : 0)).arg(l.hausdorff * 1000.0, 0, 'g', 3);
  return "\nLODs: " + levels.join(", ");
}

}  // namespace

PropertyPanel::PropertyPanel(scene::Document& doc, Selection& selection, QWidget* parent)
    : QWidget(parent), doc_(doc), selection_(selection) {
  setObjectName("propertyPanel");
  content_ = new QWidget;
  contentLayout_ = new QVBoxLayout(content_);
  contentLayout_->setContentsMargins(6, 6, 6, 6);
  contentLayout_->setSpacing(6);
  putInScrollArea(this, content_);

  connect(&doc_, &scene::Document::changed, this, &PropertyPanel::onDocumentChanged);
  connect(&selection_, &Selection::changed, this, [this] {
    rebuild();
    refresh();
  });
  rebuild();
  refresh();
}

FieldEditor* PropertyPanel::editorFor(const std::string& path) const {
  auto it = byPath_.find(path);
  return it == byPath_.end() ? nullptr : it->second;
}

std::string PropertyPanel::structureKey() const {
  const scene::Entity* e = doc_.state().find(selection_.primary());
  if (!e) return "none";
  std::string key = std::to_string(e->id) + ":" + std::to_string(selection_.size());
  for (const auto& c : scene::entityComponents()) key += c.has(*e) ? "1" : "0";
  if (e->camera)  // its post overrides are rows of their own
    for (const auto& [post, value] : e->camera->post) key += "|" + post;
  return key;
}

void PropertyPanel::onDocumentChanged(const scene::ChangeSet&) {
  if (structureKey() != structure_) rebuild();
  refresh();
}

QWidget* PropertyPanel::buildSection(const scene::ComponentInfo& c, const scene::Entity& e) {
  auto* section = new QFrame(content_);
  section->setObjectName("section_" + QString::fromStdString(c.key));
  section->setStyleSheet("QFrame#section_" + QString::fromStdString(c.key) +
                         " { background: #38393c; border-radius: 4px; }");
  auto* v = new QVBoxLayout(section);
  v->setContentsMargins(6, 4, 6, 6);
  v->setSpacing(4);

  auto* head = new QHBoxLayout;
  auto* toggle = new QToolButton(section);
  toggle->setText(QString::fromStdString(c.label));
  toggle->setCheckable(true);
  toggle->setChecked(!collapsed_.count(c.key));
  toggle->setArrowType(toggle->isChecked() ? Qt::DownArrow : Qt::RightArrow);
  toggle->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  toggle->setAutoRaise(true);
  toggle->setStyleSheet("QToolButton { font-weight: bold; border: none; }");
  head->addWidget(toggle);
  head->addStretch();
  if (c.optional) {
    auto* remove = new QToolButton(section);
    remove->setObjectName("remove_" + QString::fromStdString(c.key));
    remove->setText("✕");
    remove->setAutoRaise(true);
    remove->setToolTip(QString("Remove the %1 component").arg(QString::fromStdString(c.label)));
    const scene::EntityId id = e.id;
    const scene::ComponentInfo* comp = &c;
    connect(remove, &QToolButton::clicked, this, [this, id, comp] { scene::ops::removeComponent(doc_, id, *comp); });
    head->addWidget(remove);
  }
  v->addLayout(head);

  auto* body = new QWidget(section);
  auto* form = new QFormLayout(body);
  form->setContentsMargins(4, 0, 0, 0);
  form->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form->setHorizontalSpacing(8);
  form->setVerticalSpacing(4);
  for (const auto& f : c.fields) {
    const std::string path = c.key + "." + f.key;
    FieldEditor* ed = createFieldEditor(specOf(f, path), body);
    const scene::EntityField* field = &f;
    const scene::ComponentInfo* comp = &c;
    ed->setOnEdited([this, field, comp](const scene::FieldValue& value, int component, const QString& key) {
      apply(*field, *comp, value, component, key);
    });
    auto* label = new QLabel(QString::fromStdString(f.label), body);
    label->setStyleSheet("QLabel { color: #a9aaae; }");
    form->addRow(label, decorator_ ? decorator_(path, ed, body) : static_cast<QWidget*>(ed));
    rows_.push_back({comp, field, ed});
    byPath_[path] = ed;
  }
  if (c.key == "camera") buildCameraPost(form, body, c, e);
  // Which terrain it shows is a reference, not a field: its own row.
  if (c.key == "terrain") form->insertRow(0, "Terrain", new TerrainPicker(doc_, e.id, newTerrain_, body));
  // An emitter's forty fields and its lists are the Particles panel's
  // (fields.cpp says why they are not fields here): a summary and a way there.
  if (c.key == "particles") {
    const particles::EmitterDesc& d = e.particles->desc;
    auto* summary = new QLabel(QString("%1 from a %2, %3 per s, %4..%5 s")
                                   .arg(particles::spriteName(d.sprite), particles::shapeName(d.shape))
                                   .arg(d.rate)
                                   .arg(d.lifetimeMin)
                                   .arg(d.lifetimeMax),
                               body);
    summary->setWordWrap(true);
    summary->setStyleSheet("QLabel { color: #8f9095; }");
    form->addRow(summary);
    auto* edit = new QPushButton("Particles…", body);
    edit->setObjectName("editParticles");
    edit->setToolTip("Edit this emitter's fields in the Particles panel");
    const scene::EntityId id = e.id;
    connect(edit, &QPushButton::clicked, this, [this, id] {
      if (particlesHook_) particlesHook_(id);
    });
    form->addRow(edit);
  }
  if (c.key == "mesh") {
    meshInfo_ = new QLabel(body);
    meshInfo_->setWordWrap(true);
    meshInfo_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    meshInfo_->setStyleSheet("QLabel { color: #8f9095; }");
    form->addRow(meshInfo_);
    // The asset's processing report (error_report_dialog.h), when it has one.
    meshReport_ = new QPushButton("Mesh Report…", body);
    meshReport_->setObjectName("meshReport");
    meshReport_->setToolTip("Decimation error, cleaning counts, LOD errors and run times of this mesh's import");
    connect(meshReport_, &QPushButton::clicked, this, [this] {
      const scene::Entity* ent = doc_.state().find(selection_.primary());
      const scene::MeshAsset* a = ent && ent->mesh ? doc_.state().findAsset(ent->mesh->mesh) : nullptr;
      if (a) showErrorReport(this, QString::fromStdString(a->name), a->processReport);
    });
    form->addRow(meshReport_);
    auto* materials = new QPushButton("Materials…", body);
    materials->setObjectName("meshMaterials");
    materials->setToolTip("Edit this mesh's materials (colour, maps, lighting model) in the Materials panel");
    connect(materials, &QPushButton::clicked, this, [this] {
      const scene::Entity* ent = doc_.state().find(selection_.primary());
      if (ent && ent->mesh && materialsHook_) materialsHook_(ent->mesh->mesh);
    });
    form->addRow(materials);
    slots_ = new MaterialSlotsWidget(doc_, body);
    connect(slots_, &MaterialSlotsWidget::problem, this, &PropertyPanel::problem);
    form->addRow(slots_);
  }
  v->addWidget(body);
  body->setVisible(toggle->isChecked());
  const std::string key = c.key;
  connect(toggle, &QToolButton::toggled, this, [this, toggle, body, key](bool open) {
    body->setVisible(open);
    toggle->setArrowType(open ? Qt::DownArrow : Qt::RightArrow);
    if (open) collapsed_.erase(key);
    else collapsed_.insert(key);
  });
  return section;
}

void PropertyPanel::rebuild() {
  structure_ = structureKey();
  rows_.clear();
  byPath_.clear();
  header_ = nullptr;
  meshInfo_ = nullptr;
  meshReport_ = nullptr;
  slots_ = nullptr;
  addButton_ = nullptr;
  while (QLayoutItem* item = contentLayout_->takeAt(0)) {
    if (QWidget* w = item->widget()) w->deleteLater();
    delete item;
  }

  const scene::Entity* e = doc_.state().find(selection_.primary());
  if (!e) {
    auto* empty = new QLabel("Nothing selected.\n\nClick an entity in the viewport or the Outliner.", content_);
    empty->setAlignment(Qt::AlignCenter);
    empty->setWordWrap(true);
    empty->setStyleSheet("QLabel { color: #8f9095; padding: 24px; }");
    contentLayout_->addWidget(empty);
    contentLayout_->addStretch();
    return;
  }

  header_ = new QLabel(content_);
  header_->setObjectName("propertyHeader");
  header_->setWordWrap(true);
  contentLayout_->addWidget(header_);

  for (const auto& c : scene::entityComponents())
    if (c.has(*e)) contentLayout_->addWidget(buildSection(c, *e));

  addButton_ = new QToolButton(content_);
  addButton_->setObjectName("addComponent");
  addButton_->setText("Add Component");
  addButton_->setPopupMode(QToolButton::InstantPopup);
  addButton_->setToolButtonStyle(Qt::ToolButtonTextOnly);
  addButton_->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
  auto* menu = new QMenu(addButton_);
  const scene::EntityId id = e->id;
  for (const auto& c : scene::entityComponents()) {
    if (!c.optional || c.has(*e)) continue;
    if (c.key == "terrain") {  // without a terrain to show it would draw nothing: choose one
      fillTerrainComponentMenu(menu->addMenu(QString::fromStdString(c.label)), doc_, id, newTerrain_);
      continue;
    }
    const scene::ComponentInfo* comp = &c;
    menu->addAction(QString::fromStdString(c.label), this, [this, id, comp] { scene::ops::addComponent(doc_, id, *comp); });
  }
  addButton_->setMenu(menu);
  addButton_->setEnabled(!menu->isEmpty());
  contentLayout_->addWidget(addButton_);
  contentLayout_->addStretch();
}

void PropertyPanel::refresh() {
  const scene::SceneState& s = shown();
  const scene::Entity* e = s.find(selection_.primary());
  if (!e) return;
  if (header_) {
    QString text = "<b style='font-size:11pt'>" + QString::fromStdString(e->name).toHtmlEscaped() + "</b>";
    if (selection_.size() > 1)
      text += QString("<br><span style='color:#8f9095'>and %1 more selected: edits apply to all that have the field</span>")
                  .arg(selection_.size() - 1);
    header_->setText(text);
  }
  for (const Row& r : rows_) {
    if (!r.component->has(*e)) continue;
    r.editor->setAssets(s);
    r.editor->setValue(r.field->get(*e));
  }
  if (meshInfo_ && e->mesh) {
    const scene::MeshAsset* a = s.findAsset(e->mesh->mesh);
    if (a && a->data)
      meshInfo_->setText(QString("%1 triangles, %2 vertices, %3 material(s)\nSource: %4")
                             .arg(formatCount(a->data->triangleCount()), formatCount(a->data->vertexCount()))
                             .arg(a->data->materials.size())
                             .arg(QString::fromStdString(a->sourcePath)) +
                         lodText(*a));
    else
      meshInfo_->setText("No mesh asset assigned.");
    if (meshReport_) meshReport_->setEnabled(a && !a->processReport.is_null());
    if (slots_) slots_->showAsset(s, e->mesh->mesh);
  }
}

void PropertyPanel::setStateSource(std::function<const scene::SceneState&()> source) {
  stateSource_ = std::move(source);
  refresh();
}

void PropertyPanel::setRowDecorator(std::function<QWidget*(const std::string&, QWidget*, QWidget*)> decorator) {
  decorator_ = std::move(decorator);
  rebuild();
  refresh();
}

void PropertyPanel::setNewTerrainHook(std::function<void(scene::EntityId)> hook) {
  newTerrain_ = std::move(hook);
  rebuild();
  refresh();
}

void PropertyPanel::setEditedHook(
    std::function<void(const std::vector<scene::EntityId>&, const std::string&, const QString&)> hook) {
  edited_ = std::move(hook);
}

void PropertyPanel::apply(const scene::EntityField& field, const scene::ComponentInfo& component,
                          const scene::FieldValue& v, int vectorComponent, const QString& mergeKey) {
  const scene::SceneState& s = shown();
  std::vector<scene::EntityId> targets;
  // A name is one entity's; everything else applies to the whole selection.
  if (field.type == scene::FieldType::String) targets = {selection_.primary()};
  else targets = selection_.ids();
  // Several entities in one edit share a key, so they fold into one undo step.
  // (With the timeline's hook every edit has a key: its keys join the step.)
  const QString key = !mergeKey.isEmpty() || (targets.size() < 2 && !edited_) ? mergeKey
                                                                              : QString("prop-%1").arg(++editCounter);
  // Values first: an edit refreshes the shown state, which `s` refers to.
  std::vector<std::pair<scene::EntityId, scene::FieldValue>> edits;
  bool refused = false;
  for (scene::EntityId id : targets) {
    const scene::Entity* e = s.find(id);
    if (!e || !component.has(*e)) continue;
    scene::FieldValue value = v;
    if (vectorComponent >= 0) {
      glm::dvec3 current = std::get<glm::dvec3>(field.get(*e));
      current[vectorComponent] = std::get<glm::dvec3>(v)[vectorComponent];
      value = current;
    }
    // The field's range and rule (fields.h), as the CLI and the loader apply
    // them: an empty name, a zero scale or a far clip inside the near one
    // is not applied (the widget shows the entity's value again).
    // The rule goes to Messages, so the user learns why.
    if (const std::string problem = scene::fieldValueProblem(field, value, e); !problem.empty()) {
      emit this->problem(QString::fromStdString(e->name + ": " + field.label + " " +
                                                scene::formatFieldValue(field.type, value, field.enumNames, 6) + " " +
                                                problem + "; not applied"));
      refused = true;
      continue;
    }
    edits.emplace_back(id, std::move(value));
  }
  for (const auto& [id, value] : edits) {
    // What the setter clamped (ops::setField reports it) goes to Messages too.
    scene::ops::FieldChange change;
    scene::ops::setField(doc_, id, field, value, key, &change);
    if (!change.message.empty()) emit problem(QString::fromStdString(change.message));
  }
  if (refused) refresh();
  if (edited_ && !edits.empty()) {
    std::vector<scene::EntityId> ids;
    for (const auto& edit : edits) ids.push_back(edit.first);
    edited_(ids, component.key + "." + field.key, key);
  }
}

}  // namespace hs::app
