#include "app/terrain_rules_editor.h"

#include <algorithm>
#include <cmath>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QImage>
#include <QLabel>
#include <QListWidget>
#include <QPixmap>
#include <QPushButton>
#include <QToolButton>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "scene/terrain_asset.h"
#include "scene/terrain_ops.h"
#include "terrain/paint_rule_preview.h"

namespace hs::app {
namespace {

constexpr int kPreviewPixels = 96;

QDoubleSpinBox* spin(QWidget* parent, const char* name, double min, double max, double step, int decimals,
                     const QString& suffix, const QString& tip) {
  QDoubleSpinBox* s = numberSpin(parent, min, max, step, decimals, suffix, tip);
  s->setObjectName(name);
  // Three to a row in a narrow dock: let them shrink.
  s->setMinimumWidth(0);
  s->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  return s;
}

QToolButton* toolButton(QWidget* parent, const QString& text, const char* name, const QString& tip) {
  return namedToolButton(parent, text, name, tip);
}

// min, max and blend side by side under their captions.
QWidget* bandRow(QWidget* parent, QDoubleSpinBox* lo, QDoubleSpinBox* hi, QDoubleSpinBox* blend) {
  auto* row = new QWidget(parent);
  auto* g = new QGridLayout(row);
  g->setContentsMargins(0, 0, 0, 0);
  g->setHorizontalSpacing(4);
  g->setVerticalSpacing(0);
  const char* captions[] = {"from", "to", "blend"};
  QDoubleSpinBox* boxes[] = {lo, hi, blend};
  for (int i = 0; i < 3; ++i) {
    auto* c = new QLabel(captions[i], row);
    c->setStyleSheet("QLabel { color: #8f9095; font-size: 8pt; }");
    g->addWidget(c, 0, i);
    g->addWidget(boxes[i], 1, i);
  }
  return row;
}

QString num(double v) { return QString::number(v, 'f', std::abs(v) >= 100.0 ? 0 : 1); }

}  // namespace

TerrainRulesEditor::TerrainRulesEditor(scene::Document& doc, std::function<const scene::TerrainAsset*()> terrain,
                                       std::function<void()> apply, QWidget* parent)
    : QGroupBox("Paint rules", parent), doc_(doc), terrain_(std::move(terrain)), apply_(std::move(apply)) {
  setObjectName("terrainRulesEditor");
  build();
}

void TerrainRulesEditor::build() {
  auto* layout = new QVBoxLayout(this);
  auto* hint = new QLabel("Applied in order: a later rule paints over an earlier one.", this);
  hint->setWordWrap(true);
  hint->setStyleSheet("QLabel { color: #8f9095; }");
  layout->addWidget(hint);
  list_ = new QListWidget(this);
  list_->setObjectName("terrainRules");
  list_->setToolTip("The terrain's paint rules; the check box turns a rule on or off");
  list_->setMaximumHeight(120);
  layout->addWidget(list_);

  auto* buttons = new QHBoxLayout;
  add_ = toolButton(this, "+", "terrainRuleAdd", "Add a rule (steep ground, for the chosen layer)");
  remove_ = toolButton(this, "−", "terrainRuleRemove", "Remove the chosen rule");
  up_ = toolButton(this, "▲", "terrainRuleUp", "Apply the chosen rule earlier (rules after it paint over it)");
  down_ = toolButton(this, "▼", "terrainRuleDown", "Apply the chosen rule later (it paints over those before it)");
  defaults_ = new QPushButton("Defaults", this);
  defaults_->setObjectName("terrainRuleDefaults");
  defaults_->setToolTip("Replace the rules with the default ones for this terrain's heights");
  for (QWidget* w : std::initializer_list<QWidget*>{add_, remove_, up_, down_}) buttons->addWidget(w);
  buttons->addStretch(1);
  buttons->addWidget(defaults_);
  layout->addLayout(buttons);

  form_ = new QWidget(this);
  auto* f = new QFormLayout(form_);
  f->setContentsMargins(0, 0, 0, 0);
  layer_ = new QComboBox(form_);
  layer_->setObjectName("terrainRuleLayer");
  layer_->setToolTip("The layer this rule paints");
  layer_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  layer_->setMinimumContentsLength(6);
  strength_ = spin(form_, "terrainRuleStrength", 0.0, 100.0, 5.0, 0, " %",
                   "How far toward the layer where the rule fully applies");
  strength_->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Fixed);
  useAltitude_ = new QCheckBox("By altitude", form_);
  useAltitude_->setObjectName("terrainRuleUseAltitude");
  useAltitude_->setToolTip("Only between two heights (metres as the terrain stores them; a DEM: above sea level)");
  altMin_ = spin(form_, "terrainRuleAltitudeMin", -12000.0, 100000.0, 10.0, 1, "", "Lowest height, m");
  altMax_ = spin(form_, "terrainRuleAltitudeMax", -12000.0, 100000.0, 10.0, 1, "", "Highest height, m");
  altBlend_ = spin(form_, "terrainRuleAltitudeBlend", 0.0, 100000.0, 5.0, 1, "",
                   "Metres over which the rule fades out beyond the band");
  useSlope_ = new QCheckBox("By slope", form_);
  useSlope_->setObjectName("terrainRuleUseSlope");
  useSlope_->setToolTip("Only between two slopes, degrees from horizontal");
  slopeMin_ = spin(form_, "terrainRuleSlopeMin", 0.0, 90.0, 1.0, 1, "°", "Gentlest slope");
  slopeMax_ = spin(form_, "terrainRuleSlopeMax", 0.0, 90.0, 1.0, 1, "°", "Steepest slope");
  slopeBlend_ = spin(form_, "terrainRuleSlopeBlend", 0.0, 90.0, 1.0, 1, "°",
                     "Degrees over which the rule fades out beyond the band");
  range_ = new QLabel(form_);
  range_->setStyleSheet("QLabel { color: #8f9095; }");
  f->addRow("Layer", layer_);
  f->addRow("Strength", strength_);
  f->addRow(useAltitude_);
  f->addRow(bandRow(form_, altMin_, altMax_, altBlend_));
  f->addRow(range_);
  f->addRow(useSlope_);
  f->addRow(bandRow(form_, slopeMin_, slopeMax_, slopeBlend_));
  preview_ = new QLabel(form_);
  preview_->setObjectName("terrainRulePreview");
  preview_->setFixedSize(kPreviewPixels, kPreviewPixels);
  preview_->setToolTip("Where the rule paints (north up; brighter: stronger)");
  coverageText_ = new QLabel(form_);
  coverageText_->setObjectName("terrainRuleCoverage");
  coverageText_->setWordWrap(true);
  auto* previewRow = new QHBoxLayout;
  previewRow->addWidget(preview_);
  previewRow->addWidget(coverageText_, 1);
  f->addRow(previewRow);
  layout->addWidget(form_);

  applyButton_ = new QPushButton("Apply Paint Rules", this);
  applyButton_->setObjectName("terrainPaintRules");
  applyButton_->setToolTip("Paint the whole terrain by these rules (one undo step; on a worker, with Cancel)");
  layout->addWidget(applyButton_);

  connect(list_, &QListWidget::currentRowChanged, this, [this] {
    if (updating_) return;
    ++scrub_;
    refreshForm();
  });
  connect(list_, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
    if (updating_) return;
    const int row = list_->row(item);
    const bool on = item->checkState() == Qt::Checked;
    if (row < 0 || row >= int(shownRules_.size()) || shownRules_[size_t(row)].enabled == on) return;
    terrain::PaintRule r = shownRules_[size_t(row)];
    r.enabled = on;
    setRule(row, r);
  });
  connect(add_, &QToolButton::clicked, this, [this] { addRule(); });
  connect(remove_, &QToolButton::clicked, this, [this] { removeRule(currentRule()); });
  connect(up_, &QToolButton::clicked, this, [this] { moveRule(currentRule(), -1); });
  connect(down_, &QToolButton::clicked, this, [this] { moveRule(currentRule(), +1); });
  connect(defaults_, &QPushButton::clicked, this, [this] { resetToDefaults(); });
  connect(applyButton_, &QPushButton::clicked, this, [this] {
    if (apply_) apply_();
  });
  connect(layer_, &QComboBox::currentIndexChanged, this, [this](int l) {
    if (l >= 0) editRule([l](terrain::PaintRule& r) { r.layer = l; });
  });
  connect(useAltitude_, &QCheckBox::toggled, this, [this](bool on) {
    editRule([on](terrain::PaintRule& r) { r.useAltitude = on; });
  });
  connect(useSlope_, &QCheckBox::toggled, this, [this](bool on) {
    editRule([on](terrain::PaintRule& r) { r.useSlope = on; });
  });
  connect(strength_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    editRule([v](terrain::PaintRule& r) { r.strength = float(v / 100.0); }, scrubKey("strength"));
  });
  // A band's ends keep their order: moving one past the other moves both.
  auto band = [this](QDoubleSpinBox* box, const char* key, double terrain::PaintRule::*field,
                     double terrain::PaintRule::*lo, double terrain::PaintRule::*hi) {
    connect(box, &QDoubleSpinBox::valueChanged, this, [this, key, field, lo, hi](double v) {
      editRule([field, lo, hi, v](terrain::PaintRule& r) {
        r.*field = v;
        if (lo && hi && r.*lo > r.*hi) (field == lo ? r.*hi : r.*lo) = v;
      }, scrubKey(key));
    });
    connect(box, &QDoubleSpinBox::editingFinished, this, [this] { ++scrub_; });
  };
  using R = terrain::PaintRule;
  band(altMin_, "altMin", &R::altitudeMin, &R::altitudeMin, &R::altitudeMax);
  band(altMax_, "altMax", &R::altitudeMax, &R::altitudeMin, &R::altitudeMax);
  band(altBlend_, "altBlend", &R::altitudeBlend, nullptr, nullptr);
  band(slopeMin_, "slopeMin", &R::slopeMin, &R::slopeMin, &R::slopeMax);
  band(slopeMax_, "slopeMax", &R::slopeMax, &R::slopeMin, &R::slopeMax);
  band(slopeBlend_, "slopeBlend", &R::slopeBlend, nullptr, nullptr);
  connect(strength_, &QDoubleSpinBox::editingFinished, this, [this] { ++scrub_; });
}

int TerrainRulesEditor::currentRule() const { return list_->currentRow(); }

void TerrainRulesEditor::setCurrentRule(int index) {
  if (index >= 0 && index < list_->count()) list_->setCurrentRow(index);
}

QString TerrainRulesEditor::scrubKey(const char* field) const {
  return QString("terrainRule-%1-%2-%3").arg(currentRule()).arg(field).arg(scrub_);
}

QString TerrainRulesEditor::describe(const terrain::PaintRule& r, const std::vector<terrain::Material>& materials) const {
  QString s = r.layer >= 0 && r.layer < int(materials.size()) ? QString::fromStdString(materials[size_t(r.layer)].name)
                                                              : QString("layer %1").arg(r.layer);
  QStringList where;
  if (r.useSlope) where << QString("slope %1–%2°").arg(num(r.slopeMin), num(r.slopeMax));
  if (r.useAltitude) where << QString("%1–%2 m").arg(num(r.altitudeMin), num(r.altitudeMax));
  if (where.isEmpty()) where << "everywhere";
  return s + ": " + where.join(", ") + QString(", %1%").arg(std::lround(double(r.strength) * 100.0));
}

void TerrainRulesEditor::refresh() {
  const scene::TerrainAsset* t = terrain_();
  const std::vector<terrain::PaintRule> rules = t ? t->paintRules : std::vector<terrain::PaintRule>{};
  std::vector<std::string> layers;
  if (t)
    for (const auto& m : t->materials) layers.push_back(m.name);
  if (rules != shownRules_ || layers != shownLayers_ || list_->count() != int(rules.size())) {
    updating_ = true;
    const int keep = list_->currentRow();
    list_->clear();
    for (const auto& r : rules) {
      auto* item = new QListWidgetItem(describe(r, t->materials), list_);
      item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
      item->setCheckState(r.enabled ? Qt::Checked : Qt::Unchecked);
    }
    if (layers != shownLayers_) {
      layer_->clear();
      for (const auto& n : layers) layer_->addItem(QString::fromStdString(n));
    }
    shownRules_ = rules;
    shownLayers_ = layers;
    if (!rules.empty()) list_->setCurrentRow(std::clamp(keep < 0 ? 0 : keep, 0, int(rules.size()) - 1));
    updating_ = false;
  }
  const bool ready = t && !(t->data && t->data->jobRunning);
  add_->setEnabled(ready);
  defaults_->setEnabled(ready);
  applyButton_->setEnabled(ready && !rules.empty());
  refreshForm();
}

void TerrainRulesEditor::refreshForm() {
  const scene::TerrainAsset* t = terrain_();
  const int i = currentRule();
  const bool have = t && i >= 0 && i < int(t->paintRules.size());
  const bool ready = t && !(t->data && t->data->jobRunning);
  form_->setEnabled(have && ready);
  remove_->setEnabled(have && ready);
  up_->setEnabled(have && ready && i > 0);
  down_->setEnabled(have && ready && i + 1 < int(t->paintRules.size()));
  if (t && t->data) {
    const terrain::Heightfield& hf = t->data->heights();
    const terrain::HeightRange hr = hf.range();
    range_->setText(QString("terrain heights %1 … %2 m").arg(num(hf.origin().z + double(hr.min)),
                                                             num(hf.origin().z + double(hr.max))));
  }
  if (!have) {
    preview_->clear();
    coverageText_->setText(t ? "No rule chosen." : QString());
    coverage_ = 0.0;
    return;
  }
  const terrain::PaintRule& r = t->paintRules[size_t(i)];
  updating_ = true;
  layer_->setCurrentIndex(r.layer);
  strength_->setValue(double(r.strength) * 100.0);
  useAltitude_->setChecked(r.useAltitude);
  useSlope_->setChecked(r.useSlope);
  altMin_->setValue(r.altitudeMin);
  altMax_->setValue(r.altitudeMax);
  altBlend_->setValue(r.altitudeBlend);
  slopeMin_->setValue(r.slopeMin);
  slopeMax_->setValue(r.slopeMax);
  slopeBlend_->setValue(r.slopeBlend);
  for (QWidget* w : std::initializer_list<QWidget*>{altMin_, altMax_, altBlend_}) w->setEnabled(r.useAltitude);
  for (QWidget* w : std::initializer_list<QWidget*>{slopeMin_, slopeMax_, slopeBlend_}) w->setEnabled(r.useSlope);
  updating_ = false;
  refreshPreview();
}

void TerrainRulesEditor::refreshPreview() {
  const scene::TerrainAsset* t = terrain_();
  const int i = currentRule();
  if (!t || !t->data || i < 0 || i >= int(t->paintRules.size())) return;
  const terrain::PaintRule& r = t->paintRules[size_t(i)];
  // Exact at the samples it reads, and cheap (kPreviewPixels^2 samples), so
  // it follows every edit of the rule and every brush stroke.
  const terrain::RulePreview p = terrain::previewRule(t->data->heights(), r, kPreviewPixels);
  coverage_ = p.coverage;
  if (p.width <= 0) return;
  QColor top = r.layer >= 0 && r.layer < int(t->materials.size())
                   ? linearToDisplay(glm::dvec3(t->materials[size_t(r.layer)].albedo))
                   : QColor(Qt::white);
  // Dark layers (forest floor) would vanish on the dark ground.
  if (top.lightness() < 110) top = top.lighter(250);
  const QColor ground(34, 35, 38);
  QImage img(p.width, p.height, QImage::Format_RGB32);
  for (int y = 0; y < p.height; ++y) {
    QRgb* line = reinterpret_cast<QRgb*>(img.scanLine(p.height - 1 - y));  // row 0 is south: north up
    for (int x = 0; x < p.width; ++x) {
      const float w = p.weights[size_t(y) * size_t(p.width) + size_t(x)];
      auto mix = [w](int a, int b) { return int(std::lround(a + (b - a) * double(w))); };
      line[x] = qRgb(mix(ground.red(), top.red()), mix(ground.green(), top.green()), mix(ground.blue(), top.blue()));
    }
  }
  preview_->setPixmap(QPixmap::fromImage(img.scaled(kPreviewPixels, kPreviewPixels, Qt::KeepAspectRatio)));
  coverageText_->setText(r.enabled ? QString("Reaches %1% of the terrain, fully %2%.")
                                         .arg(std::lround(p.coverage * 100.0))
                                         .arg(std::lround(p.full * 100.0))
                                   : QString("Off: Apply Paint Rules skips it."));
}

bool TerrainRulesEditor::push(std::vector<terrain::PaintRule> rules, const QString& mergeKey) {
  const scene::TerrainAsset* t = terrain_();
  if (!t) return false;
  return scene::ops::setTerrainPaintRules(doc_, t->id, std::move(rules), mergeKey);
}

void TerrainRulesEditor::editRule(const std::function<void(terrain::PaintRule&)>& change, const QString& mergeKey) {
  if (updating_) return;
  const scene::TerrainAsset* t = terrain_();
  const int i = currentRule();
  if (!t || i < 0 || i >= int(t->paintRules.size())) return;
  terrain::PaintRule r = t->paintRules[size_t(i)];
  change(r);
  setRule(i, r, mergeKey);
}

bool TerrainRulesEditor::setRule(int index, const terrain::PaintRule& rule, const QString& mergeKey) {
  const scene::TerrainAsset* t = terrain_();
  if (!t || index < 0 || index >= int(t->paintRules.size())) return false;
  std::vector<terrain::PaintRule> rules = t->paintRules;
  rules[size_t(index)] = rule;
  const bool done = push(std::move(rules), mergeKey);
  refresh();
  return done;
}

int TerrainRulesEditor::addRule() {
  const scene::TerrainAsset* t = terrain_();
  if (!t || t->materials.empty()) return -1;
  terrain::PaintRule r;
  r.layer = std::clamp(layer_->currentIndex(), 0, int(t->materials.size()) - 1);
  r.useSlope = true;
  r.slopeMin = 30.0;
  r.slopeMax = 90.0;
  r.slopeBlend = 5.0;
  std::vector<terrain::PaintRule> rules = t->paintRules;
  rules.push_back(r);
  const int index = int(rules.size()) - 1;
  if (!push(std::move(rules))) return -1;
  refresh();
  setCurrentRule(index);
  return index;
}

bool TerrainRulesEditor::removeRule(int index) {
  const scene::TerrainAsset* t = terrain_();
  if (!t || index < 0 || index >= int(t->paintRules.size())) return false;
  std::vector<terrain::PaintRule> rules = t->paintRules;
  rules.erase(rules.begin() + index);
  if (!push(std::move(rules))) return false;
  refresh();
  setCurrentRule(std::min(index, list_->count() - 1));
  return true;
}

bool TerrainRulesEditor::moveRule(int index, int by) {
  const scene::TerrainAsset* t = terrain_();
  const int to = index + by;
  if (!t || index < 0 || index >= int(t->paintRules.size()) || to < 0 || to >= int(t->paintRules.size())) return false;
  std::vector<terrain::PaintRule> rules = t->paintRules;
  std::swap(rules[size_t(index)], rules[size_t(to)]);
  if (!push(std::move(rules))) return false;
  refresh();
  setCurrentRule(to);
  return true;
}

bool TerrainRulesEditor::resetToDefaults() {
  const scene::TerrainAsset* t = terrain_();
  if (!t || !t->data) return false;
  std::vector<terrain::PaintRule> rules = scene::defaultPaintRules(t->data->heights());
  // The defaults name the eight default layers; a terrain with fewer keeps those it has.
  std::erase_if(rules, [&](const terrain::PaintRule& r) { return r.layer >= int(t->materials.size()); });
  const bool done = push(std::move(rules));
  refresh();
  return done;
}

}  // namespace hs::app
