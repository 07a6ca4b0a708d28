#include "app/terrain_layers_editor.h"

#include <algorithm>

#include <QColorDialog>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSettings>
#include <QToolButton>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/message_panel.h"
#include "app/prompts.h"
#include "scene/terrain_layer_ops.h"
#include "scene/terrain_ops.h"
#include "terrain/terrain_operations.h"

namespace hs::app {
namespace {

QDoubleSpinBox* spin(QWidget* parent, double min, double max, double step, int decimals, const QString& suffix,
                     const QString& tip) {
  return numberSpin(parent, min, max, step, decimals, suffix, tip);
}

QToolButton* smallButton(QWidget* parent, const QString& text, const char* name, const QString& tip) {
  return namedToolButton(parent, text, name, tip);
}

// A file button beside its clear button, as one form row.
QWidget* fileRow(QWidget* parent, QPushButton*& pick, QToolButton*& clear, const char* pickName, const char* clearName,
                 const QString& tip) {
  auto* row = new QWidget(parent);
  auto* h = new QHBoxLayout(row);
  h->setContentsMargins(0, 0, 0, 0);
  pick = new QPushButton("(none)", row);
  pick->setObjectName(pickName);
  pick->setToolTip(tip);
  // Long file names must not widen the narrow dock.
  pick->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  clear = smallButton(row, "✕", clearName, "No file: the layer's colour alone");
  h->addWidget(pick, 1);
  h->addWidget(clear);
  return row;
}

}  // namespace

TerrainLayersEditor::TerrainLayersEditor(scene::Document& doc, Prompts& prompts, MessagePanel& messages,
                                         std::function<const scene::TerrainAsset*()> terrain, QWidget* parent)
    : QGroupBox("Layers and materials", parent), doc_(doc), prompts_(prompts), messages_(messages),
      terrain_(std::move(terrain)) {
  setObjectName("terrainLayers");
  auto* form = new QFormLayout(this);

  auto* layerRow = new QWidget(this);
  auto* lh = new QHBoxLayout(layerRow);
  lh->setContentsMargins(0, 0, 0, 0);
  layer_ = new QComboBox(layerRow);
  layer_->setObjectName("terrainMaterialLayer");
  layer_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  layer_->setMinimumContentsLength(6);
  add_ = smallButton(layerRow, "+", "terrainLayerAdd", "Add a paint layer (at most 16); it starts with no weight");
  remove_ = smallButton(layerRow, "−", "terrainLayerRemove",
                        "Remove this layer: its weight goes to the other layers in proportion, its rules go too "
                        "(Undo brings it back)");
  lh->addWidget(layer_, 1);
  lh->addWidget(add_);
  lh->addWidget(remove_);
  form->addRow("Layer", layerRow);

  name_ = new QLineEdit(this);
  name_->setObjectName("terrainMaterialName");
  name_->setToolTip("The layer's name (menus, exported weight images)");
  albedo_ = new QPushButton(this);
  albedo_->setObjectName("terrainMaterialColour");
  albedo_->setToolTip("Albedo colour (linear; tints the texture)");
  // Ranges, steps and help as `terrain layer` declares them.
  const auto& params = terrain::terrainLayerOperation().params;
  const ParamDecl& rough = paramIn(params, "roughness");
  const ParamDecl& tiling = paramIn(params, "tiling_m");
  roughness_ = spin(this, rough.min, rough.max, rough.step, rough.decimals, "", QString::fromStdString(rough.help));
  roughness_->setObjectName("terrainMaterialRoughness");
  tiling_ = spin(this, tiling.min, tiling.max, tiling.step, tiling.decimals, " m", QString::fromStdString(tiling.help));
  tiling_->setObjectName("terrainMaterialTiling");
  form->addRow("Name", name_);
  form->addRow("Colour", albedo_);
  form->addRow("Roughness", roughness_);
  form->addRow("Tiling", tiling_);
  form->addRow("Albedo texture", fileRow(this, albedoTexture_, clearAlbedo_, "terrainAlbedoTexture",
                                         "terrainAlbedoTextureClear", "Albedo texture file (sRGB)"));
  form->addRow("Normal map", fileRow(this, normalTexture_, clearNormal_, "terrainNormalTexture",
                                     "terrainNormalTextureClear", "Tangent-space normal map file"));

  connect(layer_, &QComboBox::currentIndexChanged, this, [this] {
    if (!updating_) refreshMaterial();
  });
  connect(add_, &QToolButton::clicked, this, [this] { addLayer(); });
  connect(remove_, &QToolButton::clicked, this, [this] { removeLayer(currentLayer()); });
  connect(name_, &QLineEdit::editingFinished, this, [this] {
    const std::string name = name_->text().trimmed().toStdString();
    if (!name.empty()) editMaterial([&](terrain::Material& m) { m.name = name; });
    refreshMaterial();  // an empty name is refused: show the old one again
  });
  connect(roughness_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    editMaterial([v](terrain::Material& m) { m.roughness = float(v); }, scrubKey("roughness"));
  });
  connect(tiling_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    editMaterial([v](terrain::Material& m) { m.tilingMetres = float(v); }, scrubKey("tiling"));
  });
  for (QDoubleSpinBox* s : {roughness_, tiling_}) connect(s, &QDoubleSpinBox::editingFinished, this, [this] { ++scrub_; });
  connect(albedo_, &QPushButton::clicked, this, [this] {
    const scene::TerrainAsset* t = terrain_();
    const int l = currentLayer();
    if (!t || l < 0 || l >= int(t->materials.size())) return;
    const QColor c = QColorDialog::getColor(linearToDisplay(glm::dvec3(t->materials[size_t(l)].albedo)), this, "Layer colour");
    if (c.isValid()) editMaterial([&](terrain::Material& m) { m.albedo = glm::vec3(displayToLinear(c)); });
  });
  auto pick = [this](bool normal) {
    QSettings s;
    const QString path = prompts_.askOpenFile(this, normal ? "Normal Map" : "Albedo Texture",
                                              s.value("terrain/lastTextureDirectory", QDir::homePath()).toString(),
                                              "Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.tga);;All files (*)");
    if (path.isEmpty()) return;  // cancelled: keep the file it had
    s.setValue("terrain/lastTextureDirectory", QFileInfo(path).absolutePath());
    setTexture(normal, path);
  };
  connect(albedoTexture_, &QPushButton::clicked, this, [pick] { pick(false); });
  connect(normalTexture_, &QPushButton::clicked, this, [pick] { pick(true); });
  connect(clearAlbedo_, &QToolButton::clicked, this, [this] { setTexture(false, {}); });
  connect(clearNormal_, &QToolButton::clicked, this, [this] { setTexture(true, {}); });
}

int TerrainLayersEditor::currentLayer() const { return layer_->currentIndex(); }

void TerrainLayersEditor::setCurrentLayer(int layer) {
  if (layer >= 0 && layer < layer_->count()) layer_->setCurrentIndex(layer);
}

QString TerrainLayersEditor::scrubKey(const char* field) const {
  return QString("terrainLayer-%1-%2-%3").arg(currentLayer()).arg(field).arg(scrub_);
}

void TerrainLayersEditor::refresh() {
  const scene::TerrainAsset* t = terrain_();
  QStringList names;
  if (t)
    for (const auto& m : t->materials) names << QString::fromStdString(m.name);
  QStringList shown;
  for (int i = 0; i < layer_->count(); ++i) shown << layer_->itemText(i);
  if (names != shown) {
    updating_ = true;
    const int keep = layer_->currentIndex();
    layer_->clear();
    layer_->addItems(names);
    if (!names.isEmpty()) layer_->setCurrentIndex(std::clamp(keep, 0, int(names.size()) - 1));
    updating_ = false;
  }
  const bool busy = t && t->data && t->data->jobRunning;
  add_->setEnabled(t && !busy && names.size() < terrain::kMaxPaintLayers);
  remove_->setEnabled(t && !busy && names.size() > 1);
  refreshMaterial();
}

void TerrainLayersEditor::refreshMaterial() {
  const scene::TerrainAsset* t = terrain_();
  const int l = currentLayer();
  if (!t || l < 0 || l >= int(t->materials.size())) return;
  const terrain::Material& m = t->materials[size_t(l)];
  updating_ = true;
  if (!name_->hasFocus()) name_->setText(QString::fromStdString(m.name));
  const QColor c = linearToDisplay(glm::dvec3(m.albedo));
  albedo_->setText(c.name());
  albedo_->setStyleSheet(QString("QPushButton { background: %1; color: %2; }")
                             .arg(c.name(), c.lightness() > 128 ? "black" : "white"));
  roughness_->setValue(double(m.roughness));
  tiling_->setValue(double(m.tilingMetres));
  auto showFile = [](QPushButton* b, QToolButton* clear, const std::string& path) {
    const QString p = QString::fromStdString(path);
    b->setText(p.isEmpty() ? "(none)" : QFileInfo(p).fileName());
    b->setToolTip(p.isEmpty() ? "No file: click to choose one" : p);
    clear->setEnabled(!p.isEmpty());
  };
  showFile(albedoTexture_, clearAlbedo_, m.albedoTexture);
  showFile(normalTexture_, clearNormal_, m.normalTexture);
  updating_ = false;
}

void TerrainLayersEditor::editMaterial(const std::function<void(terrain::Material&)>& change, const QString& mergeKey) {
  if (updating_) return;
  const scene::TerrainAsset* t = terrain_();
  const int l = currentLayer();
  if (!t || l < 0 || l >= int(t->materials.size())) return;
  terrain::Material m = t->materials[size_t(l)];
  change(m);
  scene::ops::setTerrainMaterial(doc_, t->id, l, m, mergeKey);
}

bool TerrainLayersEditor::setTexture(bool normal, const QString& path) {
  const scene::TerrainAsset* t = terrain_();
  const int l = currentLayer();
  if (!t || l < 0 || l >= int(t->materials.size())) return false;
  terrain::Material m = t->materials[size_t(l)];
  (normal ? m.normalTexture : m.albedoTexture) = path.toStdString();
  // The renderer reads the file when it next draws; a file it cannot read
  // reaches Messages from there (TerrainPanel), naming the file and layer.
  return scene::ops::setTerrainMaterial(doc_, t->id, l, m);
}

int TerrainLayersEditor::addLayer() {
  const scene::TerrainAsset* t = terrain_();
  if (!t) return -1;
  std::string error;
  terrain::Material m;
  m.name = "Layer " + std::to_string(t->materials.size() + 1);
  const scene::TerrainId id = t->id;
  const std::string terrainName = t->name;
  const int added = scene::ops::addTerrainLayer(doc_, id, m, error);
  if (added < 0) {
    messages_.error("Add paint layer: " + QString::fromStdString(error));
    return -1;
  }
  refresh();
  setCurrentLayer(added);
  messages_.info(QString("Added paint layer '%1' to '%2'").arg(QString::fromStdString(m.name),
                                                               QString::fromStdString(terrainName)));
  emit layerAdded(added);
  return added;
}

bool TerrainLayersEditor::removeLayer(int layer) {
  const scene::TerrainAsset* t = terrain_();
  if (!t || layer < 0 || layer >= int(t->materials.size())) return false;
  const QString name = QString::fromStdString(t->materials[size_t(layer)].name);
  const QString terrainName = QString::fromStdString(t->name);
  std::string error;
  if (!scene::ops::removeTerrainLayer(doc_, t->id, layer, error)) {
    messages_.error("Remove paint layer: " + QString::fromStdString(error));
    return false;
  }
  refresh();
  messages_.info(QString("Removed paint layer '%1' from '%2': its weight went to the other layers (Undo brings it back)")
                     .arg(name, terrainName));
  emit layerRemoved(layer);
  return true;
}

}  // namespace hs::app
