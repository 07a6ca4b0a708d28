#include "app/lights_panel.h"

#include <algorithm>

#include <QHBoxLayout>
#include <QHeaderView>
#include <QItemSelectionModel>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/selection.h"
#include "app/timeline_keying.h"
#include "scene/sequence_edits.h"
#include "scene/operations.h"

namespace hs::app {
namespace {

const scene::ComponentInfo& lightComponent() {
  const scene::ComponentInfo* c = scene::findComponent("light");
  Q_ASSERT(c);
  return *c;
}

// The field declares "lx (sun) or lm"; a row knows which of the two it is.
std::string intensityUnitOf(scene::Light::Type type) { return type == scene::Light::Type::Sun ? "lx" : "lm"; }

// Fields a light of this type does not use stay visible but cannot be
// edited: a sun has no range and no cones, a point light no cones.
bool usedBy(const std::string& key, scene::Light::Type type) {
  if (key == "range") return type != scene::Light::Type::Sun;
  if (key == "inner_cone_deg" || key == "outer_cone_deg") return type == scene::Light::Type::Spot;
  return true;
}

}  // namespace

LightsPanel::LightsPanel(scene::Document& doc, Selection& selection, QWidget* parent)
    : QWidget(parent), doc_(doc), selection_(selection) {
  setObjectName("lightsPanel");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(8, 8, 8, 8);
  auto* buttons = new QHBoxLayout;
  const std::pair<scene::Light::Type, const char*> kinds[] = {
      {scene::Light::Type::Sun, "Sun"}, {scene::Light::Type::Point, "Point"}, {scene::Light::Type::Spot, "Spot"}};
  for (const auto& [type, name] : kinds) {
    auto* b = new QToolButton(this);
    b->setText(QString("+ %1").arg(name));
    b->setObjectName(QString("addLight%1").arg(name));
    b->setToolTip(QString("Add a %1 light at the view's pivot (undoable)").arg(QString(name).toLower()));
    const scene::Light::Type t = type;
    connect(b, &QToolButton::clicked, this, [this, t] { emit addRequested(t); });
    buttons->addWidget(b);
    add_[type] = b;
  }
  delete_ = new QToolButton(this);
  delete_->setText("Delete");
  delete_->setObjectName("deleteLights");
  delete_->setToolTip("Delete the selected lights (undoable)");
  connect(delete_, &QToolButton::clicked, this, [this] {
    std::vector<scene::EntityId> gone;
    for (scene::EntityId id : selection_.ids())
      if (std::find(lights_.begin(), lights_.end(), id) != lights_.end()) gone.push_back(id);
    if (!gone.empty()) scene::ops::remove(doc_, gone);
  });
  buttons->addWidget(delete_);
  buttons->addStretch(1);
  layout->addLayout(buttons);

  table_ = new QTableWidget(this);
  table_->setObjectName("lightsTable");
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::ExtendedSelection);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->verticalHeader()->hide();
  QStringList headers{"Name"};
  for (const scene::EntityField& f : lightComponent().fields)
    headers << QString::fromStdString(f.key == "intensity" ? f.label + " (lx / lm)" : f.label);
  table_->setColumnCount(int(headers.size()));
  table_->setHorizontalHeaderLabels(headers);
  layout->addWidget(table_, 1);

  connect(table_, &QTableWidget::itemSelectionChanged, this, &LightsPanel::tableToSelection);
  connect(&selection_, &Selection::changed, this, &LightsPanel::selectionToTable);
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet&) {
    if (structureKey() != structure_) rebuild();
    else refreshValues();
  });
  rebuild();
}

void LightsPanel::setStateSource(std::function<const scene::SceneState&()> source) {
  stateSource_ = std::move(source);
  refreshValues();
}

void LightsPanel::setEditedHook(std::function<void(scene::EntityId, const std::string&, const QString&)> hook) {
  edited_ = std::move(hook);
}

std::string LightsPanel::structureKey() const {
  std::string key;
  for (scene::EntityId id : doc_.state().depthFirstOrder()) {
    const scene::Entity* e = doc_.state().find(id);
    if (e && e->light) key += std::to_string(id) + ":" + std::to_string(int(e->light->type)) + ":" + e->name + ";";
  }
  return key;
}

void LightsPanel::enableKeying(Keying& keying, TimelineClock& clock) {
  keying_ = &keying;
  clock_ = &clock;
  rebuild();
}

KeyButton* LightsPanel::keyButtonFor(scene::EntityId id, const std::string& key) const {
  auto it = keyButtons_.find({id, key});
  return it == keyButtons_.end() ? nullptr : it->second;
}

FieldEditor* LightsPanel::editorFor(scene::EntityId id, const std::string& key) const {
  auto it = editors_.find({id, key});
  return it == editors_.end() ? nullptr : it->second;
}

QString LightsPanel::intensityUnit(scene::EntityId id) const {
  const scene::Entity* e = doc_.state().find(id);
  return e && e->light ? QString::fromStdString(intensityUnitOf(e->light->type)) : QString();
}

QToolButton* LightsPanel::addButton(scene::Light::Type type) const {
  auto it = add_.find(type);
  return it == add_.end() ? nullptr : it->second;
}

void LightsPanel::rebuild() {
  syncing_ = true;
  editors_.clear();
  keyButtons_.clear();
  lights_.clear();
  table_->clearContents();
  const scene::SceneState& s = doc_.state();
  for (scene::EntityId id : s.depthFirstOrder())
    if (const scene::Entity* e = s.find(id); e && e->light) lights_.push_back(id);
  table_->setRowCount(int(lights_.size()));
  const scene::ComponentInfo& light = lightComponent();
  for (int row = 0; row < int(lights_.size()); ++row) {
    const scene::EntityId id = lights_[size_t(row)];
    const scene::Entity& e = *s.find(id);
    auto* name = new QTableWidgetItem(QString::fromStdString(e.name));
    name->setData(Qt::UserRole, QVariant::fromValue<qulonglong>(id));
    table_->setItem(row, 0, name);
    for (int col = 0; col < int(light.fields.size()); ++col) {
      const scene::EntityField* field = &light.fields[size_t(col)];
      FieldSpec spec = specOf(*field, "light." + field->key);
      if (field->key == "intensity") spec.unit = intensityUnitOf(e.light->type);
      FieldEditor* ed = createFieldEditor(spec, table_);
      ed->setObjectName(QString("light_%1_%2").arg(id).arg(QString::fromStdString(field->key)));
      ed->setEnabled(usedBy(field->key, e.light->type));
      ed->setOnEdited([this, id, field](const scene::FieldValue& v, int component, const QString& key) {
        apply(id, *field, v, component, key);
      });
      QWidget* cell = ed;
      std::string error;
      if (keying_ && scene::animationTarget("light." + field->key, error)) {
        cell = editorRow(table_, ed);
        auto* key = new KeyButton(
            *keying_, [id] { return std::vector<uint64_t>{id}; }, *clock_, "light." + field->key, cell);
        key->setObjectName(QString("key_%1_light.%2").arg(id).arg(QString::fromStdString(field->key)));
        cell->layout()->addWidget(key);
        keyButtons_[{id, field->key}] = key;
      }
      table_->setCellWidget(row, col + 1, cell);
      editors_[{id, field->key}] = ed;
    }
  }
  structure_ = structureKey();
  syncing_ = false;
  table_->resizeColumnsToContents();
  refreshValues();
  selectionToTable();
}

void LightsPanel::refreshValues() {
  const scene::SceneState& s = shown();
  for (const auto& [where, editor] : editors_) {
    const scene::Entity* e = s.find(where.first);
    const scene::EntityField* f = scene::findEntityField("light." + where.second);
    if (e && e->light && f) editor->setValue(f->get(*e));
  }
}

void LightsPanel::apply(scene::EntityId id, const scene::EntityField& field, const scene::FieldValue& v, int component,
                        const QString& mergeKey) {
  const scene::Entity* e = shown().find(id);
  if (!e || !e->light) return;
  scene::FieldValue value = v;
  if (component >= 0) {
    glm::dvec3 current = std::get<glm::dvec3>(field.get(*e));
    current[component] = std::get<glm::dvec3>(v)[component];
    value = current;
  }
  // The field's range and rule, as the Properties dock checks them: a value
  // that breaks them is not applied and the message says why.
  if (const std::string problem = scene::fieldValueProblem(field, value, e); !problem.empty()) {
    emit this->problem(QString::fromStdString(e->name + ": " + field.label + " " +
                                              scene::formatFieldValue(field.type, value, field.enumNames, 6) + " " +
                                              problem + "; not applied"));
    refreshValues();
    return;
  }
  // With a hook every edit has a merge key, so keys it sets join the step.
  const QString key = mergeKey.isEmpty() && edited_ ? QString("lights-%1").arg(++editCounter_) : mergeKey;
  scene::ops::FieldChange change;
  if (scene::ops::setField(doc_, id, field, value, key, &change) && edited_) edited_(id, "light." + field.key, key);
  if (!change.message.empty()) emit problem(QString::fromStdString(change.message));
}

void LightsPanel::selectionToTable() {
  if (syncing_) return;
  syncing_ = true;
  table_->clearSelection();
  for (int row = 0; row < int(lights_.size()); ++row)
    if (selection_.contains(lights_[size_t(row)]))
      table_->selectionModel()->select(table_->model()->index(row, 0),
                                       QItemSelectionModel::Select | QItemSelectionModel::Rows);
  syncing_ = false;
}

void LightsPanel::tableToSelection() {
  if (syncing_) return;
  std::vector<scene::EntityId> ids;
  for (const QModelIndex& index : table_->selectionModel()->selectedRows())
    if (index.row() >= 0 && size_t(index.row()) < lights_.size()) ids.push_back(lights_[size_t(index.row())]);
  syncing_ = true;
  selection_.set(ids);
  syncing_ = false;
}

}  // namespace hs::app
