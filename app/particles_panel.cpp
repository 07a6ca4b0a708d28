#include "app/particles_panel.h"

#include <QDialog>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QMenu>
#include <QPushButton>
#include <QScrollArea>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "app/camera_controller.h"
#include "app/life_curve_editor.h"
#include "app/main_window.h"
#include "app/message_panel.h"
#include "app/param_form.h"
#include "app/selection.h"
#include "app/time_keys_editor.h"
#include "app/timeline_clock.h"
#include "app/viewport_widget.h"
#include "particles/emitter.h"
#include "particles/particle_operations.h"
#include "scene/operations.h"
#include "scene/particle_ops.h"
#include "scene/particle_world.h"
#include "scene/sequence_edits.h"
#include "sequencer/frame_range.h"

namespace hs::app {
namespace {

std::vector<ParamDecl> editorParams(const std::vector<ParamDecl>& params) {
  std::vector<ParamDecl> out;
  for (const ParamDecl& p : params)
    if (p.editor) out.push_back(p);
  return out;
}

QString countText(const scene::EmitterCount& c) {
  if (!c.error.empty()) return "error";
  return (c.estimated ? "~" : "") + QLocale().toString(qulonglong(c.live));
}

}  // namespace

ParticlesAddDialog::ParticlesAddDialog(QWidget* parent, const glm::dvec3& pivot) : QDialog(parent) {
  setWindowTitle("Add Particles");
  setObjectName("addParticlesDialog");
  form_ = new ParamForm(editorParams(particles::particlesAddOperation().params), this, {},
                        {"name", "at", "area", "rate"});
  form_->setValue("at", Json::array({pivot.x, pivot.y, pivot.z}));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons->button(QDialogButtonBox::Ok)->setText("Add");
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  auto* v = new QVBoxLayout(this);
  auto* help = new QLabel("Snow, fog and dust cover an area (default 100 m around the position); a torch or "
                          "campfire stands at the position (default: the view's pivot).",
                          this);
  help->setWordWrap(true);
  v->addWidget(help);
  v->addWidget(form_);
  v->addWidget(buttons);
}

Json ParticlesAddDialog::values() const { return form_->values(); }

ParticlesPanel::ParticlesPanel(MainWindow& window) : QWidget(&window), window_(window), doc_(window.document()) {
  setObjectName("particlesPanel");
  buildUi();
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet&) { refresh(); });
  connect(doc_.undoStack(), &QUndoStack::indexChanged, this, [this] { refresh(); });
  connect(&window_.selection(), &Selection::changed, this, [this] {
    const scene::EntityId id = window_.selection().primary();
    const scene::Entity* e = doc_.state().find(id);
    if (e && e->particles && id != current_) setCurrentEmitter(id);
  });
  refresh();
}

void ParticlesPanel::buildUi() {
  auto* v = new QVBoxLayout(this);
  info_ = new QLabel(this);
  info_->setObjectName("particlesInfo");
  info_->setWordWrap(true);
  v->addWidget(info_);

  list_ = new QTreeWidget(this);
  list_->setObjectName("particleEmitters");
  list_->setHeaderLabels({"Emitter", "Look", "Live"});
  list_->setRootIsDecorated(false);
  list_->setSelectionMode(QAbstractItemView::SingleSelection);
  list_->setToolTip("The scene's particle emitters with their live particles at the playhead (by lifetimes: a "
                    "collision's kills are not counted).");
  list_->header()->setStretchLastSection(false);
  list_->header()->setSectionResizeMode(0, QHeaderView::Stretch);
  list_->header()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  list_->header()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
  list_->setMinimumHeight(100);
  connect(list_, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item) {
    if (updating_ || !item) return;
    const scene::EntityId id = item->data(0, Qt::UserRole).toULongLong();
    setCurrentEmitter(id);
    window_.selection().select(id);
  });
  v->addWidget(list_);

  auto* buttons = new QHBoxLayout;
  auto* add = new QPushButton("Add Preset…", this);
  add->setObjectName("particlesAdd");
  add->setToolTip(QString::fromStdString(particles::particlesAddOperation().summary));
  connect(add, &QPushButton::clicked, this, &ParticlesPanel::requestAddPreset);
  remove_ = new QPushButton("Remove", this);
  remove_->setObjectName("particlesRemove");
  remove_->setToolTip("Remove the emitter's entity (one undo step)");
  connect(remove_, &QPushButton::clicked, this, [this] {
    if (current_ != scene::kNoEntity) scene::ops::remove(doc_, {current_});
  });
  buttons->addWidget(add);
  buttons->addWidget(remove_);
  buttons->addStretch(1);
  v->addLayout(buttons);

  error_ = new QLabel(this);
  error_->setObjectName("particlesError");
  error_->setWordWrap(true);
  error_->setStyleSheet("QLabel { color: #ff8a75; }");
  error_->hide();
  v->addWidget(error_);

  // The emitter's fields scroll: it has forty.
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  fields_ = new QWidget(scroll);
  auto* fv = new QVBoxLayout(fields_);
  form_ = new ParamForm(editorParams(particles::emitterParamDecls()), fields_);
  form_->setObjectName("particlesForm");
  connect(form_, &ParamForm::edited, this, &ParticlesPanel::formEdited);
  fv->addWidget(form_);
  auto* listsForm = new QFormLayout;
  const std::pair<const char*, const char*> listHelp[] = {
      {"rate_keys", "[[t, rate], ...]: particles per second over scene time (linear between keys)"},
      {"bursts", "[[t, count], ...]: particles born at once"},
      {"wind_keys", "[[t, x, y, z], ...]: wind over scene time, m/s"},
      {"size_over_life", "[[x, multiplier], ...], x = age / lifetime"},
      {"colour_over_life", "[[x, r, g, b, a], ...], linear RGB (above 1 for fire), opacity"},
  };
  for (const auto& [key, help] : listHelp) {
    auto* e = new QLineEdit(fields_);
    e->setObjectName(QString("particles_") + key);
    e->setToolTip(help);
    e->setPlaceholderText("[]");
    connect(e, &QLineEdit::editingFinished, this, [this, k = std::string(key), e] { listEdited(k, e); });
    listsForm->addRow(key, e);
    lists_.emplace_back(key, e);
    // The over-life curves are drawn and dragged too (the line stays for exact values).
    const std::string k(key);
    if (k == "size_over_life" || k == "colour_over_life") {
      auto* curve = new LifeCurveEditor(
          k == "size_over_life" ? LifeCurveEditor::Kind::Size : LifeCurveEditor::Kind::Colour, fields_);
      curve->setObjectName(QString("particles_") + key + "_curve");
      connect(curve, &LifeCurveEditor::edited, this, [this, k](const Json& rows) {
        if (!updating_ && current_ != scene::kNoEntity) setValue(current_, k, rows, false);
      });
      listsForm->addRow("", curve);
      curves_.emplace_back(k, curve);
    }
    // The lists over scene time too, against the playback range and the playhead.
    if (k == "rate_keys" || k == "bursts" || k == "wind_keys") {
      auto* keys = new TimeKeysEditor(k == "rate_keys"   ? TimeKeysEditor::Kind::Rate
                                      : k == "wind_keys" ? TimeKeysEditor::Kind::Wind
                                                         : TimeKeysEditor::Kind::Bursts,
                                      fields_);
      keys->setObjectName(QString("particles_") + key + "_curve");
      connect(keys, &TimeKeysEditor::edited, this, [this, k](const Json& rows) {
        if (!updating_ && current_ != scene::kNoEntity) setValue(current_, k, rows, false);
      });
      listsForm->addRow("", keys);
      timeKeys_.emplace_back(k, keys);
    }
  }
  fv->addLayout(listsForm);

  // Keys on the timeline for the spawn values (scene/emitter_tracks.h): the
  // field's value in the form, keyed at the playhead; particles born after
  // take the keyed values.
  auto* keyRow = new QHBoxLayout;
  keyField_ = new QComboBox(fields_);
  keyField_->setObjectName("particlesKeyField");
  // The rate and the wind first (keys of the emitter's own lists), then the
  // spawn values (timeline tracks).
  for (const char* k : {"rate_per_s", "wind_m_per_s"})
    keyField_->addItem(QString::fromStdString(paramIn(particles::emitterParamDecls(), k).label),
                       QString::fromStdString(std::string(scene::kEmitterTrackPrefix) + k));
  for (const std::string& k : particles::spawnKeys())
    keyField_->addItem(QString::fromStdString(paramIn(particles::emitterParamDecls(), k).label),
                       QString::fromStdString(std::string(scene::kEmitterTrackPrefix) + k));
  keyField_->setToolTip("A value to key at the playhead: the rate and the wind as keys of the emitter's lists "
                        "(rate_keys, wind_keys); a spawn value on the timeline, each particle taking its value "
                        "at its birth");
  auto* key = new QPushButton("Key at Playhead", fields_);
  key->setObjectName("particlesKey");
  key->setToolTip("Key the chosen field's value (a MIN,MAX pair: its centre) at the playhead: one undo step");
  connect(key, &QPushButton::clicked, this, [this] { keyAtPlayhead(keyField_->currentData().toString().toStdString()); });
  keyRow->addWidget(new QLabel("Timeline:", fields_));
  keyRow->addWidget(keyField_, 1);
  keyRow->addWidget(key);
  fv->addLayout(keyRow);
  fv->addStretch(1);
  scroll->setWidget(fields_);
  v->addWidget(scroll, 1);
}

void ParticlesPanel::followClock(TimelineClock* clock) {
  // The live counts follow the playhead (scrubbing, playing, edits).
  connect(clock, &TimelineClock::stateChanged, this, &ParticlesPanel::refreshCounts);
  connect(clock, &TimelineClock::stateChanged, this, &ParticlesPanel::refreshTimeKeys);
  refreshCounts();
  refreshTimeKeys();
}

void ParticlesPanel::refreshTimeKeys() {
  // The span: the playback range, widened to the keys and the playhead.
  const sequencer::Sequence& seq = doc_.state().sequence;
  const double now = playheadSeconds();
  double t0 = std::min(sequencer::frameTime(seq.startFrame, seq.rate), now);
  double t1 = std::max(sequencer::frameTime(seq.endFrame, seq.rate), now);
  for (auto& [key, editor] : timeKeys_)
    for (const Json& row : editor->keys()) {
      t0 = std::min(t0, row[0].get<double>());
      t1 = std::max(t1, row[0].get<double>());
    }
  if (!(t1 - t0 >= 1.0)) t1 = t0 + 1.0;
  const double margin = 0.02 * (t1 - t0);
  for (auto& [key, editor] : timeKeys_) {
    editor->setSpan(t0 - margin, t1 + margin);
    editor->setPlayhead(now);
  }
}

void ParticlesPanel::populateMenu(QMenu* menu) {
  menu->addAction("&Add Particles…", this, &ParticlesPanel::requestAddPreset);
}

double ParticlesPanel::playheadSeconds() const {
  const TimelineClock* clock = window_.timelineClock();
  return clock ? clock->time() : 0.0;
}

void ParticlesPanel::setCurrentEmitter(scene::EntityId id) {
  current_ = id;
  refresh();
}

void ParticlesPanel::refresh() {
  updating_ = true;
  const scene::SceneState& s = doc_.state();
  const scene::Entity* cur = s.find(current_);
  if (!cur || !cur->particles) current_ = scene::kNoEntity;
  list_->clear();
  size_t emitters = 0;
  for (scene::EntityId id : s.depthFirstOrder()) {
    const scene::Entity* e = s.find(id);
    if (!e || !e->particles) continue;
    ++emitters;
    if (current_ == scene::kNoEntity) current_ = id;
    const particles::EmitterDesc& d = e->particles->desc;
    auto* item = new QTreeWidgetItem(
        list_, {QString::fromStdString(e->name),
                QString("%1, %2").arg(particles::spriteName(d.sprite), particles::blendName(d.blend)), QString()});
    item->setData(0, Qt::UserRole, qulonglong(id));
    if (!s.effectivelyVisible(id)) item->setForeground(0, palette().color(QPalette::Disabled, QPalette::Text));
    if (id == current_) list_->setCurrentItem(item);
  }
  info_->setText(emitters ? QString("%1 emitter(s). Fields apply at once; Ctrl+Z undoes.").arg(emitters)
                          : QString("No particle emitters. Add Preset… adds snow, fog, a torch, a campfire or dust."));
  remove_->setEnabled(current_ != scene::kNoEntity);
  fields_->setEnabled(current_ != scene::kNoEntity);
  updating_ = false;
  refreshForm();
  refreshCounts();
}

void ParticlesPanel::refreshCounts() {
  if (list_->topLevelItemCount() == 0) return;  // no emitter: nothing to count
  // At the playhead, on the document's emitters (what the viewport shows).
  const std::vector<scene::EmitterCount> counts = scene::liveParticleCounts(doc_.state(), playheadSeconds());
  for (int i = 0; i < list_->topLevelItemCount(); ++i) {
    QTreeWidgetItem* item = list_->topLevelItem(i);
    const scene::EntityId id = item->data(0, Qt::UserRole).toULongLong();
    item->setText(2, "hidden");
    for (const scene::EmitterCount& c : counts)
      if (c.entity == id) {
        item->setText(2, countText(c));
        item->setToolTip(2, QString::fromStdString(c.error));
      }
  }
}

void ParticlesPanel::refreshForm() {
  const scene::Entity* e = doc_.state().find(current_);
  if (!e || !e->particles) return;
  updating_ = true;
  const Json j = particles::emitterToJson(e->particles->desc);
  for (const ParamDecl& p : particles::emitterParamDecls())
    if (p.editor && j.contains(p.key)) form_->setValue(p.key, j[p.key]);
  // What the fields show now (rounded to their decimals): an edit is a
  // field that differs from this, never one the rounding made differ.
  shown_ = form_->values();
  for (auto& [key, edit] : lists_)
    if (j.contains(key)) edit->setText(QString::fromStdString(j[key].dump()));
  for (auto& [key, curve] : curves_)
    if (j.contains(key)) curve->setKeys(j[key]);
  for (auto& [key, editor] : timeKeys_) {
    std::vector<double> constant;
    const Json c = key == "rate_keys" ? j["rate_per_s"] : key == "wind_keys" ? j["wind_m_per_s"] : Json();
    if (c.is_number()) constant.push_back(c.get<double>());
    if (c.is_array())
      for (const Json& v : c) constant.push_back(v.get<double>());
    if (j.contains(key)) editor->setKeys(j[key], constant);
  }
  updating_ = false;
  refreshTimeKeys();
}

void ParticlesPanel::formEdited() {
  if (updating_ || current_ == scene::kNoEntity) return;
  const scene::Entity* e = doc_.state().find(current_);
  if (!e || !e->particles) return;
  const Json values = form_->values();
  for (auto it = values.begin(); it != values.end(); ++it)
    if (!shown_.contains(it.key()) || shown_[it.key()] != it.value()) {
      shown_[it.key()] = it.value();
      setValue(current_, it.key(), it.value());
    }
}

void ParticlesPanel::listEdited(const std::string& key, QLineEdit* edit) {
  if (updating_ || current_ == scene::kNoEntity) return;
  std::string error;
  const scene::Entity* owner = doc_.state().find(current_);
  const std::optional<Json> v =
      scene::ops::parseEmitterValue(owner ? owner->name : std::string(), key, edit->text().toStdString(), error);
  if (!v) {
    showProblem(error);
    return;
  }
  const scene::Entity* e = doc_.state().find(current_);
  if (e && e->particles && particles::emitterToJson(e->particles->desc)[key] == *v) return;
  setValue(current_, key, *v);
}

bool ParticlesPanel::keyAtPlayhead(const std::string& property) {
  const scene::Entity* e = doc_.state().find(current_);
  std::string error;
  // The rate and the wind: a key of the emitter's own list, the form's value.
  const std::string_view prefix = scene::kEmitterTrackPrefix;
  const std::string field = property.rfind(prefix, 0) == 0 ? property.substr(prefix.size()) : std::string();
  if (!scene::ops::keyedListOf(field).empty()) {
    const Json value = e && e->particles ? particles::emitterToJson(e->particles->desc)[field] : Json();
    if (!e || !scene::ops::keyEmitterField(doc_, current_, field, playheadSeconds(), value, error)) {
      showProblem(e ? error : "no emitter to key");
      return false;
    }
    error_->hide();
    return true;
  }
  const std::optional<scene::AnimTarget> target = scene::animationTarget(property, error);
  if (!e || !target) {
    if (target) error = "no emitter to key";
    showProblem(error);
    return false;
  }
  const std::optional<sequencer::PropertyValue> value = scene::currentKeyValue(*e, *target);
  if (!value) return false;
  if (!scene::ops::setKeys(doc_, {{current_, *target, *value}}, playheadSeconds(), std::nullopt,
                           QString("Key %1").arg(QString::fromStdString(property)), {}, &error)) {
    if (!error.empty()) showProblem(error);
    return false;
  }
  error_->hide();
  return true;
}

void ParticlesPanel::showProblem(const std::string& error) {
  window_.messages()->warning(QString::fromStdString(error));
  error_->setText(QString::fromStdString(error));
  error_->show();
}

bool ParticlesPanel::setValue(scene::EntityId id, const std::string& key, const Json& value, bool merge) {
  std::string error;
  const QString mergeKey =
      merge ? QString("particles/%1/%2").arg(qulonglong(id)).arg(QString::fromStdString(key)) : QString();
  if (!scene::ops::setEmitterValue(doc_, id, key, value, error, mergeKey)) {
    // The form keeps what was typed, marked; the document keeps its value.
    showProblem(error);
    return false;
  }
  error_->hide();
  return true;
}

scene::EntityId ParticlesPanel::addPreset(const Json& values) {
  Json v = values;
  const bool atGiven = v.contains("at") || !v.contains("area");
  if (!v.contains("at") && !v.contains("area")) {
    const glm::dvec3 p = window_.viewport()->camera().pivot();
    v["at"] = Json::array({p.x, p.y, p.z});
  }
  const std::string preset = v.value("preset", std::string("snow"));
  std::string error;
  const scene::EntityId id = scene::ops::addParticles(doc_, preset, particles::presetFromValues(v), atGiven, error);
  if (id == scene::kNoEntity) {
    window_.messages()->error("Add particles: " + QString::fromStdString(error));
    return id;
  }
  const scene::Entity& top = *doc_.state().find(id);
  window_.messages()->info(QString("Added %1 (%2)").arg(QString::fromStdString(top.name), QString::fromStdString(preset)));
  const scene::EntityId first = top.particles ? id : top.children.front();
  window_.selection().select(id);
  setCurrentEmitter(first);
  return id;
}

void ParticlesPanel::requestAddPreset() {
  ParticlesAddDialog d(this, window_.viewport()->camera().pivot());
  if (d.exec() != QDialog::Accepted) return;
  addPreset(d.values());
}

}  // namespace hs::app
