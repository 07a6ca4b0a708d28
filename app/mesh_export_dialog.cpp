#include "app/mesh_export_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include "app/param_widgets.h"

namespace hs::app {

MeshExportDialog::MeshExportDialog(const scene::SceneState& state, scene::EntityId preferred,
                                   const QString& suggestedPath, QWidget* parent)
    : QDialog(parent), state_(state) {
  setWindowTitle("Export Mesh");
  const OperationDecl& op = scene::meshExportOperation();
  auto* form = new QFormLayout(this);

  target_ = new QComboBox(this);
  target_->setObjectName("exportTarget");
  target_->setToolTip("An entity's mesh is written where the entity places it; an asset as it was imported");
  // Item data: the name the operation resolves (entities first, as it does).
  for (const auto& [id, e] : state.entities)
    if (e.mesh) {
      target_->addItem(QString::fromStdString(e.name) + "  (entity)", QString::fromStdString(e.name));
      if (id == preferred) target_->setCurrentIndex(target_->count() - 1);
    }
  for (const auto& [id, a] : state.assets)
    if (state.findByName(a.name) == scene::kNoEntity)
      target_->addItem(QString::fromStdString(a.name) + "  (asset)", QString::fromStdString(a.name));
  form->addRow("Mesh", target_);

  auto* pathRow = new QHBoxLayout;
  path_ = new QLineEdit(suggestedPath, this);
  path_->setObjectName("exportPath");
  auto* browse = new QPushButton("Browse…", this);
  connect(browse, &QPushButton::clicked, this, &MeshExportDialog::browse);
  pathRow->addWidget(path_);
  pathRow->addWidget(browse);
  form->addRow("File", pathRow);

  lod_ = paramIntSpin(op.param("lod"), this);
  lod_->setObjectName("lod");
  form->addRow(paramLabel(op.param("lod")), lod_);
  format_ = paramCombo(op.param("format"), this,
                       {"From the extension", "OBJ (+ MTL, textures)", "PLY (binary)", "GLB", "3D Tiles (tileset.json)"});
  format_->setObjectName("format");
  form->addRow(paramLabel(op.param("format")), format_);
  up_ = paramCombo(op.param("up"), this, {"Auto (Z with world coordinates)", "Y up", "Z up"});
  up_->setObjectName("up");
  form->addRow(paramLabel(op.param("up")), up_);
  crs_ = new QLineEdit(QString::fromStdString(op.param("crs").defaultValue.get<std::string>()), this);
  crs_->setObjectName("crs");
  tagParamWidget(crs_, op.param("crs"));
  form->addRow(paramLabel(op.param("crs")), crs_);
  dracoBits_ = paramIntSpin(op.param("draco_bits"), this);
  dracoBits_->setObjectName("draco_bits");
  dracoBits_->setSpecialValueText("Off (exact)");
  form->addRow(paramLabel(op.param("draco_bits")), dracoBits_);
  world_ = new QCheckBox(paramLabel(op.param("world")), this);
  world_->setObjectName("world");
  world_->setToolTip(QString::fromStdString(paramHelp(op.param("world"))));
  form->addRow(QString(), world_);

  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons->button(QDialogButtonBox::Ok)->setText("Export");
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  form->addRow(buttons);
  connect(target_, &QComboBox::currentIndexChanged, this, &MeshExportDialog::updateLodRange);
  updateLodRange();
}

void MeshExportDialog::updateLodRange() {
  // The declaration's range is the widest any asset can have; this asset's
  // levels are shown in the tooltip, and the operation refuses a level it
  // does not have with a message naming the levels it has.
  const std::string name = target_->currentData().toString().toStdString();
  const scene::MeshAsset* asset = nullptr;
  if (const scene::EntityId id = state_.findByName(name); id != scene::kNoEntity && state_.find(id)->mesh)
    asset = state_.findAsset(state_.find(id)->mesh->mesh);
  for (const auto& [aid, a] : state_.assets)
    if (!asset && a.name == name) asset = &a;
  const size_t levels = asset ? asset->lods.size() : 0;
  lod_->setToolTip(QString::fromStdString(paramHelp(scene::meshExportOperation().param("lod"))) +
                   QString("\nThis mesh has levels 0 to %1.").arg(levels));
}

void MeshExportDialog::browse() {
  const QString p = QFileDialog::getSaveFileName(this, "Export Mesh", path_->text(),
                                                 "Meshes (*.obj *.ply *.glb *.json);;OBJ (*.obj);;PLY (*.ply);;GLB (*.glb);;"
                                                 "3D Tiles (tileset.json)");
  if (!p.isEmpty()) path_->setText(p);
}

scene::MeshExportRequest MeshExportDialog::request() const {
  scene::MeshExportRequest r = scene::MeshExportRequest::fromParams(
      Json{{"lod", lod_->value()},
           {"world", world_->isChecked()},
           {"format", format_->currentData().toString().toStdString()},
           {"up", up_->currentData().toString().toStdString()},
           {"crs", crs_->text().trimmed().toStdString()},
           {"draco_bits", dracoBits_->value()}});
  r.target = target_->currentData().toString().toStdString();
  r.out = path_->text().toStdString();
  return r;
}

}  // namespace hs::app
