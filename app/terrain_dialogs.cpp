#include "app/terrain_dialogs.h"

#include <QComboBox>
#include <QPushButton>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>
#include <QVBoxLayout>

namespace hs::app {
namespace {

QDoubleSpinBox* number(QWidget* parent, double min, double max, double value, int decimals, const QString& suffix = {}) {
  auto* s = new QDoubleSpinBox(parent);
  s->setRange(min, max);
  s->setDecimals(decimals);
  s->setValue(value);
  s->setSuffix(suffix);
  s->setKeyboardTracking(false);
  return s;
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
  auto* form = new QFormLayout;
  name_ = new QLineEdit(suggestedName, this);
  form->addRow("Name", name_);
  sizeX_ = number(this, 1.0, 1e6, 2048.0, 2, " m");
  sizeY_ = number(this, 1.0, 1e6, 2048.0, 2, " m");
  auto* size = new QHBoxLayout;
  size->addWidget(sizeX_);
  size->addWidget(new QLabel("×", this));
  size->addWidget(sizeY_);
  form->addRow("Size (east × north)", size);
  resolution_ = new QComboBox(this);
  for (int n : {129, 257, 513, 1025, 2049, 4097, 8193}) resolution_->addItem(QString("%1 × %1 samples").arg(n), n);
  resolution_->setCurrentIndex(4);
  form->addRow("Resolution", resolution_);
  auto* spacing = new QLabel(this);
  auto updateSpacing = [this, spacing] {
    const int n = resolution_->currentData().toInt();
    spacing->setText(QString("%1 × %2 m between samples")
                         .arg(sizeX_->value() / (n - 1), 0, 'g', 4)
                         .arg(sizeY_->value() / (n - 1), 0, 'g', 4));
  };
  connect(resolution_, &QComboBox::currentIndexChanged, this, updateSpacing);
  connect(sizeX_, &QDoubleSpinBox::valueChanged, this, updateSpacing);
  connect(sizeY_, &QDoubleSpinBox::valueChanged, this, updateSpacing);
  updateSpacing();
  form->addRow("", spacing);
  minH_ = number(this, -11000.0, 9000.0, 0.0, 2, " m");
  maxH_ = number(this, -11000.0, 9000.0, 200.0, 2, " m");
  auto* range = new QHBoxLayout;
  range->addWidget(minH_);
  range->addWidget(new QLabel("to", this));
  range->addWidget(maxH_);
  form->addRow("Height range", range);
  start_ = new QComboBox(this);
  start_->addItem("Flat (at the lowest height)");
  start_->addItem("Fractal hills over the range");
  form->addRow("Start from", start_);
  auto* v = new QVBoxLayout(this);
  v->addLayout(form);
  v->addWidget(okCancel(this, "Create"));
}

scene::ops::NewTerrain NewTerrainDialog::spec() const {
  scene::ops::NewTerrain s;
  s.name = name_->text().trimmed().toStdString();
  if (s.name.empty()) s.name = "Terrain";
  s.samplesX = s.samplesY = resolution_->currentData().toInt();
  s.sizeMetres = glm::dvec2(sizeX_->value(), sizeY_->value());
  s.heightRange = {float(std::min(minH_->value(), maxH_->value())), float(std::max(minH_->value(), maxH_->value()))};
  s.start = start_->currentIndex() == 1 ? scene::ops::NewTerrain::Start::Hills : scene::ops::NewTerrain::Start::Flat;
  return s;
}

DemImportDialog::DemImportDialog(QWidget* parent, const QString& file, bool haveSelectedTerrain) : QDialog(parent) {
  setWindowTitle("Import DEM");
  auto* form = new QFormLayout;
  form->addRow("File", new QLabel(QFileInfo(file).fileName(), this));
  target_ = new QComboBox(this);
  target_->addItem("A new terrain at its true ground size");
  if (haveSelectedTerrain) target_->addItem("The selected terrain (resampled onto its grid)");
  form->addRow("Into", target_);
  window_ = new QComboBox(this);
  window_->addItems({"The whole file", "Pixels (columns, rows)", "The file's CRS units", "Longitude / latitude"});
  form->addRow("Part", window_);
  auto* box = new QHBoxLayout;
  const char* tips[4] = {"min x / column / longitude", "min y / row / latitude", "max x", "max y"};
  for (int i = 0; i < 4; ++i) {
    box_[i] = number(this, -1e9, 1e9, 0.0, 6);
    box_[i]->setToolTip(tips[i]);
    box_[i]->setEnabled(false);
    box->addWidget(box_[i]);
  }
  connect(window_, &QComboBox::currentIndexChanged, this, [this](int i) {
    for (auto* b : box_) b->setEnabled(i != 0);
  });
  form->addRow("Window (min x, min y, max x, max y)", box);
  resolution_ = new QSpinBox(this);
  resolution_->setRange(0, 8193);
  resolution_->setSpecialValueText("The DEM's own");
  resolution_->setSuffix(" samples per side");
  form->addRow("Resolution", resolution_);
  crs_ = new QComboBox(this);
  crs_->addItems({"Automatic (reproject degrees, Web Mercator, feet to metres)", "Keep the file's CRS",
                  "Local transverse Mercator", "UTM zone of the centre", "Custom (EPSG:n, WKT, PROJ)"});
  customCrs_ = new QLineEdit(this);
  customCrs_->setPlaceholderText("EPSG:32634");
  customCrs_->setEnabled(false);
  connect(crs_, &QComboBox::currentIndexChanged, this, [this](int i) { customCrs_->setEnabled(i == 4); });
  form->addRow("Coordinates", crs_);
  form->addRow("", customCrs_);
  resampling_ = new QComboBox(this);
  resampling_->addItems({"Nearest", "Bilinear", "Cubic (Catmull-Rom)"});
  resampling_->setCurrentIndex(1);
  form->addRow("Resampling", resampling_);
  fill_ = new QComboBox(this);
  fill_->addItems({"Diffusion (smoothest surface over the gap)", "Inverse distance, then diffusion"});
  form->addRow("Fill nodata", fill_);
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
  o.samplesX = o.samplesY = resolution_->value() >= 2 ? resolution_->value() : 0;
  using C = terrain::DemCrsMode;
  const C modes[5] = {C::Auto, C::KeepSource, C::LocalTransverseMercator, C::Utm, C::Custom};
  o.crs = modes[crs_->currentIndex()];
  o.customCrs = customCrs_->text().trimmed().toStdString();
  o.resampling = terrain::Resampling(resampling_->currentIndex());
  o.fill = fill_->currentIndex() == 1 ? terrain::NodataFill::InverseDistance : terrain::NodataFill::Diffusion;
  return r;
}

ErosionDialog::ErosionDialog(QWidget* parent, bool hydraulic, const QStringList& layers)
    : QDialog(parent), hydraulic_(hydraulic) {
  setWindowTitle(hydraulic ? "Hydraulic Erosion" : "Thermal Erosion");
  auto* form = new QFormLayout;
  const terrain::ThermalParams t;
  const terrain::HydraulicParams h;
  iterations_ = new QSpinBox(this);
  iterations_->setRange(1, 1000000);
  iterations_->setValue(hydraulic ? h.iterations : t.iterations);
  form->addRow("Iterations", iterations_);
  talus_ = number(this, 0.0, 90.0, t.talusDegrees, 1, "°");
  strength_ = number(this, 0.0, 1.0, double(t.strength), 3);
  rain_ = number(this, 0.0, 1e3, h.rain, 4, " m/s");
  evaporation_ = number(this, 0.0, 1e3, h.evaporation, 3, " /s");
  capacity_ = number(this, 0.0, 1e3, h.sedimentCapacity, 3);
  erosion_ = number(this, 0.0, 1e3, h.erosionRate, 3, " /s");
  deposition_ = number(this, 0.0, 1e3, h.depositionRate, 3, " /s");
  dt_ = number(this, 1e-4, 10.0, h.timeStep, 4, " s");
  if (hydraulic) {
    form->addRow("Rain", rain_);
    form->addRow("Evaporation", evaporation_);
    form->addRow("Sediment capacity", capacity_);
    form->addRow("Erosion rate", erosion_);
    form->addRow("Deposition rate", deposition_);
    form->addRow("Time step (upper bound)", dt_);
  } else {
    form->addRow("Talus angle", talus_);
    form->addRow("Strength", strength_);
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

terrain::ThermalParams ErosionDialog::thermal() const {
  terrain::ThermalParams p;
  p.iterations = iterations_->value();
  p.talusDegrees = talus_->value();
  p.strength = float(strength_->value());
  return p;
}

terrain::HydraulicParams ErosionDialog::hydraulic() const {
  terrain::HydraulicParams p;
  p.iterations = iterations_->value();
  p.rain = rain_->value();
  p.evaporation = evaporation_->value();
  p.sedimentCapacity = capacity_->value();
  p.erosionRate = erosion_->value();
  p.depositionRate = deposition_->value();
  p.timeStep = dt_->value();
  return p;
}

scene::TerrainJobMask ErosionDialog::mask() const {
  scene::TerrainJobMask m;
  m.paintLayer = mask_->currentIndex() - 1;
  return m;
}

}  // namespace hs::app
