#include "app/terrain_dialogs.h"

#include <QComboBox>
#include <QCheckBox>
#include <QDialogButtonBox>
#include <QPushButton>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QVBoxLayout>

#include "app/param_widgets.h"
#include "terrain/erosion_hydraulic.h"
#include "terrain/erosion_thermal.h"

namespace hs::app {
namespace {

// Two fields side by side with a word between them ("2048 × 2048").
QWidget* pairRow(QWidget* parent, QWidget* a, const QString& between, QWidget* b) {
  auto* row = new QWidget(parent);
  auto* h = new QHBoxLayout(row);
  h->setContentsMargins(0, 0, 0, 0);
  h->addWidget(a);
  h->addWidget(new QLabel(between, row));
  h->addWidget(b);
  return row;
}

QDialogButtonBox* okCancel(QDialog* d, const QString& okText) {
  auto* b = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, d);
  b->button(QDialogButtonBox::Ok)->setText(okText);
  QObject::connect(b, &QDialogButtonBox::accepted, d, &QDialog::accept);
  QObject::connect(b, &QDialogButtonBox::rejected, d, &QDialog::reject);
  return b;
}

}  // namespace

NewTerrainDialog::NewTerrainDialog(QWidget* parent, const QString& suggestedName) : QDialog(parent) {
  setWindowTitle("New Terrain");
  const OperationDecl& op = scene::ops::terrainNewOperation();
  auto* form = new QFormLayout;
  name_ = new QLineEdit(suggestedName, this);
  form->addRow(paramLabel(op.param("name")), name_);
  // A suggestion to start from: 2 km at 1 m spacing (the CLI has no default).
  const ParamDecl& size = op.param("size_m");
  sizeX_ = paramDoubleSpin(size, this, 0);
  sizeY_ = paramDoubleSpin(size, this, 1);
  for (QDoubleSpinBox* b : {sizeX_, sizeY_}) b->setValue(2048.0);
  form->addRow(paramLabel(size), pairRow(this, sizeX_, "×", sizeY_));
  const ParamDecl& samples = op.param("samples");
  samplesX_ = paramIntSpin(samples, this, 0);
  samplesY_ = paramIntSpin(samples, this, 1);
  for (QSpinBox* b : {samplesX_, samplesY_}) b->setValue(2049);
  form->addRow(paramLabel(samples), pairRow(this, samplesX_, "×", samplesY_));
  auto* spacing = new QLabel(this);
  auto updateSpacing = [this, spacing] {
    spacing->setText(QString("%1 × %2 m between samples")
                         .arg(sizeX_->value() / (samplesX_->value() - 1), 0, 'g', 4)
                         .arg(sizeY_->value() / (samplesY_->value() - 1), 0, 'g', 4));
  };
  for (QSpinBox* b : {samplesX_, samplesY_}) connect(b, &QSpinBox::valueChanged, this, updateSpacing);
  for (QDoubleSpinBox* b : {sizeX_, sizeY_}) connect(b, &QDoubleSpinBox::valueChanged, this, updateSpacing);
  updateSpacing();
  form->addRow("", spacing);
  const ParamDecl& height = op.param("height_m");
  minH_ = paramDoubleSpin(height, this, 0);
  maxH_ = paramDoubleSpin(height, this, 1);
  form->addRow(paramLabel(height), pairRow(this, minH_, "to", maxH_));
  start_ = new QComboBox(this);
  start_->addItem("Flat (at the lowest height)");
  start_->addItem("Fractal hills over the range");
  start_->setToolTip(QString::fromStdString(op.param("hills").help));
  form->addRow("Start from", start_);
  auto* v = new QVBoxLayout(this);
  v->addLayout(form);
  v->addWidget(okCancel(this, "Create"));
}

scene::ops::NewTerrain NewTerrainDialog::spec() const {
  scene::ops::NewTerrain s;
  s.name = name_->text().trimmed().toStdString();
  if (s.name.empty()) s.name = "Terrain";
  s.samplesX = samplesX_->value();
  s.samplesY = samplesY_->value();
  s.sizeMetres = glm::dvec2(sizeX_->value(), sizeY_->value());
  s.heightRange = {float(std::min(minH_->value(), maxH_->value())), float(std::max(minH_->value(), maxH_->value()))};
  s.start = start_->currentIndex() == 1 ? scene::ops::NewTerrain::Start::Hills : scene::ops::NewTerrain::Start::Flat;
  return s;
}

DemImportDialog::DemImportDialog(QWidget* parent, const QString& file, bool haveSelectedTerrain) : QDialog(parent) {
  setWindowTitle("Import DEM");
  const std::vector<ParamDecl>& decls = terrain::demImportParamDecls();
  auto* form = new QFormLayout;
  form->addRow("File", new QLabel(QFileInfo(file).fileName(), this));
  target_ = new QComboBox(this);
  target_->addItem("A new terrain at its true ground size");
  if (haveSelectedTerrain) target_->addItem("The selected terrain (resampled onto its grid)");
  form->addRow("Into", target_);
  const ParamDecl& window = paramIn(decls, "window");
  window_ = new QComboBox(this);
  window_->addItems({"The whole file", "Pixels (columns, rows)", "The file's CRS units", "Longitude / latitude"});
  window_->setToolTip(QString::fromStdString(window.help));
  form->addRow(paramLabel(window), window_);
  const ParamDecl& windowBox = paramIn(decls, "window_box");
  auto* box = new QHBoxLayout;
  for (int i = 0; i < 4; ++i) {
    box_[i] = paramDoubleSpin(windowBox, this, i);
    box_[i]->setEnabled(false);
    box->addWidget(box_[i]);
  }
  connect(window_, &QComboBox::currentIndexChanged, this, [this](int i) {
    for (auto* b : box_) b->setEnabled(i != 0);
  });
  form->addRow(paramLabel(windowBox), box);
  // Resampling is optional: without it the DEM keeps its own resolution.
  const ParamDecl& samples = paramIn(decls, "samples");
  resample_ = new QCheckBox("Resample to", this);
  resample_->setToolTip(QString::fromStdString(paramHelp(samples)));
  samplesX_ = paramIntSpin(samples, this, 0);
  samplesY_ = paramIntSpin(samples, this, 1);
  for (QSpinBox* b : {samplesX_, samplesY_}) {
    b->setValue(1025);
    b->setEnabled(false);
    connect(resample_, &QCheckBox::toggled, b, &QWidget::setEnabled);
  }
  auto* res = new QHBoxLayout;
  res->addWidget(resample_);
  res->addWidget(pairRow(this, samplesX_, "×", samplesY_), 1);
  form->addRow(paramLabel(samples), res);
  const ParamDecl& crs = paramIn(decls, "crs");
  crs_ = new QComboBox(this);
  crs_->addItems({"Automatic (reproject degrees, Web Mercator, feet to metres)", "Keep the file's CRS",
                  "Local transverse Mercator", "UTM zone of the centre", "Custom (EPSG:n, WKT, PROJ)"});
  crs_->setToolTip(QString::fromStdString(crs.help));
  customCrs_ = new QLineEdit(this);
  customCrs_->setPlaceholderText("EPSG:32634");
  customCrs_->setEnabled(false);
  connect(crs_, &QComboBox::currentIndexChanged, this, [this](int i) { customCrs_->setEnabled(i == 4); });
  form->addRow(paramLabel(crs), crs_);
  form->addRow("", customCrs_);
  const ParamDecl& resampling = paramIn(decls, "resampling");
  resampling_ = paramCombo(resampling, this, {"Nearest", "Bilinear", "Cubic (Catmull-Rom)"});
  form->addRow(paramLabel(resampling), resampling_);
  const ParamDecl& fill = paramIn(decls, "fill");
  fill_ = paramCombo(fill, this, {"Diffusion (smoothest surface over the gap)", "Inverse distance, then diffusion"});
  form->addRow(paramLabel(fill), fill_);
  auto* v = new QVBoxLayout(this);
  v->addLayout(form);
  v->addWidget(okCancel(this, "Import"));
}

DemImportRequest DemImportDialog::request() const {
  DemImportRequest r;
  r.intoSelected = target_->currentIndex() == 1;
  terrain::DemImportOptions& o = r.options;
  using U = terrain::DemWindow::Units;
  const U units[4] = {U::Full, U::Pixels, U::SourceCrs, U::LonLat};
  o.window.units = units[window_->currentIndex()];
  o.window.minX = box_[0]->value();
  o.window.minY = box_[1]->value();
  o.window.maxX = box_[2]->value();
  o.window.maxY = box_[3]->value();
  if (resample_->isChecked()) {
    o.samplesX = samplesX_->value();
    o.samplesY = samplesY_->value();
  }
  using C = terrain::DemCrsMode;
  const C modes[5] = {C::Auto, C::KeepSource, C::LocalTransverseMercator, C::Utm, C::Custom};
  o.crs = modes[crs_->currentIndex()];
  o.customCrs = customCrs_->text().trimmed().toStdString();
  const QString resampling = resampling_->currentData().toString();
  o.resampling = resampling == "nearest" ? terrain::Resampling::Nearest
                 : resampling == "cubic" ? terrain::Resampling::Cubic
                                         : terrain::Resampling::Bilinear;
  o.fill = fill_->currentData().toString() == "idw" ? terrain::NodataFill::InverseDistance
                                                    : terrain::NodataFill::Diffusion;
  return r;
}

ErosionDialog::ErosionDialog(QWidget* parent, bool hydraulic, const QStringList& layers)
    : QDialog(parent), hydraulic_(hydraulic) {
  setWindowTitle(hydraulic ? "Hydraulic Erosion" : "Thermal Erosion");
  auto* form = new QFormLayout;
  for (const ParamDecl& p : hydraulic ? terrain::hydraulicParamDecls() : terrain::thermalParamDecls()) {
    if (!p.editor) continue;
    QAbstractSpinBox* field = p.integer ? static_cast<QAbstractSpinBox*>(paramIntSpin(p, this))
                                        : static_cast<QAbstractSpinBox*>(paramDoubleSpin(p, this));
    fields_[p.key] = field;
    form->addRow(paramLabel(p), field);
  }
  mask_ = new QComboBox(this);
  mask_->addItem("Everywhere");
  for (const QString& l : layers) mask_->addItem("Where painted: " + l);
  form->addRow("Where", mask_);
  auto* note = new QLabel("Runs on a worker with progress and Cancel; one undo step. The time step is limited so the "
                          "solver cannot blow up, and the report gives its mass error.",
                          this);
  note->setWordWrap(true);
  auto* v = new QVBoxLayout(this);
  v->addLayout(form);
  v->addWidget(note);
  v->addWidget(okCancel(this, "Erode"));
}

double ErosionDialog::value(const char* key) const {
  QAbstractSpinBox* f = fields_.at(key);
  if (auto* i = qobject_cast<QSpinBox*>(f)) return i->value();
  return static_cast<QDoubleSpinBox*>(f)->value();
}

terrain::ThermalParams ErosionDialog::thermal() const {
  terrain::ThermalParams p;
  if (hydraulic_) return p;
  p.iterations = int(value("iterations"));
  p.talusDegrees = value("talus_deg");
  p.strength = float(value("strength"));
  return p;
}

terrain::HydraulicParams ErosionDialog::hydraulic() const {
  terrain::HydraulicParams p;
  if (!hydraulic_) return p;
  p.iterations = int(value("iterations"));
  p.rain = value("rain_m_per_s");
  p.evaporation = value("evaporation_per_s");
  p.sedimentCapacity = value("sediment_capacity");
  p.erosionRate = value("erosion_rate_per_s");
  p.depositionRate = value("deposition_rate_per_s");
  p.timeStep = value("time_step_s");
  return p;
}

scene::TerrainJobMask ErosionDialog::mask() const {
  scene::TerrainJobMask m;
  m.paintLayer = mask_->currentIndex() - 1;
  return m;
}

}  // namespace hs::app
