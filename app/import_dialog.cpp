#include "app/import_dialog.h"

#include <cmath>
#include <limits>

#include <QButtonGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSettings>
#include <QSpinBox>
#include <QStackedWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/error_curve.h"
#include "app/import_preview.h"
#include "app/param_widgets.h"

namespace hs::app {
namespace {

// The choices of up axis and reader by name (their declarations), and back.
const char* upName(mesh::UpAxis a) { return a == mesh::UpAxis::Y ? "y" : a == mesh::UpAxis::Z ? "z" : "auto"; }
const char* readerName(mesh::Reader r) {
  return r == mesh::Reader::Obj ? "obj" : r == mesh::Reader::Assimp ? "assimp" : "auto";
}

QTableWidgetItem* cell(const QString& text, bool bold) {
  auto* item = new QTableWidgetItem(text);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  if (bold) {
    QFont f = item->font();
    f.setBold(true);
    item->setFont(f);
  }
  return item;
}

}  // namespace

ImportDialog::ImportDialog(const QStringList& files, const mesh::ImportOptions& defaults, QWidget* parent)
    : QDialog(parent), files_(files), preview_(new ImportPreview(this)) {
  setObjectName("importDialog");
  setWindowTitle(files.size() > 1 ? QString("Import %1 Tiles").arg(files.size()) : QString("Import Mesh"));
  auto* layout = new QVBoxLayout(this);

  QStringList names;
  for (const QString& f : files) names << QFileInfo(f).fileName();
  auto* what = new QLabel(files.size() > 1 ? QString("<b>%1 tiles of one scan</b> (one asset, borders welded):<br>%2")
                                                 .arg(files.size())
                                                 .arg(names.join(", ").toHtmlEscaped())
                                           : QString("<b>%1</b>").arg(names.value(0).toHtmlEscaped()),
                          this);
  what->setWordWrap(true);
  what->setToolTip(files.join('\n'));
  layout->addWidget(what);

  // Reading.
  auto* readBox = new QGroupBox("Reading", this);
  auto* readForm = new QFormLayout(readBox);
  const std::vector<ParamDecl>& reading = mesh::importOptionDecls();
  const ParamDecl& up = paramIn(reading, "up");
  up_ = paramCombo(up, readBox,
                   {"Automatic (FBX and glTF say; OBJ/PLY are Y up)", "Y up", "Z up (scans at UTM coordinates)"});
  up_->setObjectName("upAxis");
  up_->setCurrentIndex(std::max(0, up_->findData(QString(upName(defaults.up)))));
  readForm->addRow(paramLabel(up), up_);
  const ParamDecl& reader = paramIn(reading, "reader");
  reader_ = paramCombo(reader, readBox,
                       {"Automatic (own reader for OBJ, Assimp for the rest)",
                        "Own OBJ reader (parallel, double precision)", "Assimp"});
  reader_->setObjectName("reader");
  reader_->setCurrentIndex(std::max(0, reader_->findData(QString(readerName(defaults.reader)))));
  readForm->addRow(paramLabel(reader), reader_);
  auto* originRow = new QWidget(readBox);
  auto* originLayout = new QVBoxLayout(originRow);
  originLayout->setContentsMargins(0, 0, 0, 0);
  originAuto_ = new QRadioButton("From an offset file beside the mesh (Pix4D, OpenDroneMap, offset.xyz)", originRow);
  originAuto_->setObjectName("originAuto");
  originFile_ = new QRadioButton("The file's own coordinates", originRow);
  originFile_->setObjectName("originFile");
  originManual_ = new QRadioButton("Set by hand (added to the file's coordinates):", originRow);
  originManual_->setObjectName("originManual");
  auto* group = new QButtonGroup(this);
  for (QRadioButton* b : {originAuto_, originFile_, originManual_}) {
    group->addButton(b);
    originLayout->addWidget(b);
  }
  auto* xyz = new QHBoxLayout;
  const char* axis[] = {"originX", "originY", "originZ"};
  for (int i = 0; i < 3; ++i) {
    origin_[i] = paramDoubleSpin(paramIn(reading, "origin_offset_m"), originRow, i);
    origin_[i]->setObjectName(axis[i]);
    origin_[i]->setValue(defaults.geoOffset[i]);
    xyz->addWidget(origin_[i]);
  }
  originLayout->addLayout(xyz);
  using Mode = mesh::ImportOptions::GeoOffsetMode;
  (defaults.geoOffsetMode == Mode::Manual ? originManual_
   : defaults.geoOffsetMode == Mode::None ? originFile_
                                          : originAuto_)
      ->setChecked(true);
  readForm->addRow(paramLabel(paramIn(reading, "origin")), originRow);
  layout->addWidget(readBox);

  // Processing.
  QSettings settings;
  auto* procBox = new QGroupBox("Processing", this);
  auto* procForm = new QFormLayout(procBox);
  clean_ = new QCheckBox("Weld duplicates, remove degenerate faces, split non-manifold spots", procBox);
  clean_->setObjectName("clean");
  clean_->setChecked(settings.value("import/clean", true).toBool());
  procForm->addRow("Clean", clean_);
  auto* decimateRow = new QWidget(procBox);
  auto* decimateLayout = new QHBoxLayout(decimateRow);
  decimateLayout->setContentsMargins(0, 0, 0, 0);
  decimate_ = new QCheckBox("to", decimateRow);
  decimate_->setObjectName("decimate");
  targetKind_ = new QComboBox(decimateRow);
  targetKind_->setObjectName("targetKind");
  targetKind_->addItem("a share of the triangles", int(Target::Ratio));
  targetKind_->addItem("a triangle count", int(Target::Triangles));
  targetKind_->addItem("a maximum error", int(Target::MaxError));
  auto* values = new QStackedWidget(decimateRow);
  const std::vector<ParamDecl>& processing = mesh::processOptionDecls();
  ratio_ = paramDoubleSpin(paramIn(processing, "target_ratio_pct"), values);
  ratio_->setObjectName("targetRatio");
  triangles_ = paramIntSpin(paramIn(processing, "target_triangles"), values);
  triangles_->setObjectName("targetTriangles");
  triangles_->setGroupSeparatorShown(true);
  triangles_->setSuffix(" triangles");
  maxError_ = paramDoubleSpin(paramIn(processing, "max_error_m"), values);
  maxError_->setObjectName("maxError");
  maxError_->setToolTip("Hausdorff distance from the cleaned original, in metres (" +
                        QString::fromStdString(rangeText(paramIn(processing, "max_error_m"))) + ")");
  for (QWidget* w : std::initializer_list<QWidget*>{ratio_, triangles_, maxError_}) values->addWidget(w);
  decimateLayout->addWidget(decimate_);
  decimateLayout->addWidget(targetKind_);
  decimateLayout->addWidget(values, 1);
  connect(targetKind_, &QComboBox::currentIndexChanged, values, &QStackedWidget::setCurrentIndex);
  procForm->addRow("Decimate", decimateRow);
  // The flag is declared as an opt-out (--no-refine); the dialog asks it
  // the positive way round, with the declaration's words as its tooltip.
  const ParamDecl& noRefine = paramIn(processing, "no_refine");
  refine_ = new QCheckBox("Move vertices to lower the largest error (minimax)", procBox);
  refine_->setObjectName("refine");
  refine_->setToolTip(QString::fromStdString("Unchecked: " + noRefine.help));
  refine_->setChecked(settings.value("import/refine", true).toBool());
  procForm->addRow("Refine", refine_);
  const ParamDecl& certify = paramIn(processing, "certify");
  certify_ = new QCheckBox("Bound the error from above (a certified maximum)", procBox);
  certify_->setObjectName("certify");
  certify_->setToolTip(QString::fromStdString(certify.help));
  certify_->setChecked(settings.value("import/certify", false).toBool());
  procForm->addRow(paramLabel(certify), certify_);
  const ParamDecl& lods = paramIn(processing, "lods");
  lods_ = paramIntSpin(lods, procBox);
  lods_->setObjectName("lodLevels");
  lods_->setSpecialValueText("none");
  lods_->setSuffix(" coarser levels (a quarter each)");
  lods_->setToolTip("Each instance draws the coarsest level whose error stays under the scene's pixel bound (" +
                    QString::fromStdString(rangeText(lods)) + ")");
  procForm->addRow(paramLabel(lods), lods_);
  const ParamDecl& clusters = scene::meshImportOperation().param("clusters");
  clusters_ = paramCombo(clusters, procBox,
                         {QString("Automatic (meshes of %1M triangles and more)")
                              .arg(scene::kClusterAutoTriangles / 1000000),
                          "Build one (pages stream from the scene file)", "None"});
  clusters_->setObjectName("clusters");
  procForm->addRow(paramLabel(clusters), clusters_);
  const ParamDecl& crs = scene::meshImportOperation().param("crs");
  tilesetCrs_ = new QLineEdit(QString::fromStdString(crs.defaultValue.get<std::string>()), procBox);
  tilesetCrs_->setObjectName("crs");
  tagParamWidget(tilesetCrs_, crs);
  procForm->addRow(paramLabel(crs), tilesetCrs_);
  layout->addWidget(procBox);

  // Preview.
  auto* prevBox = new QGroupBox("Preview: triangles against error", this);
  auto* prev = new QVBoxLayout(prevBox);
  auto* prevButtons = new QHBoxLayout;
  previewButton_ = new QPushButton("Preview", prevBox);
  previewButton_->setObjectName("previewButton");
  previewButton_->setToolTip(QString("Decimates at 50%, 25%, 10%, 5%, 2%, 1% and the chosen target, and measures each "
                                     "(%1 samples per face; the import's report uses 10)")
                                 .arg(ImportPreview::kSamplesPerFace));
  cancelPreviewButton_ = new QPushButton("Cancel", prevBox);
  cancelPreviewButton_->setObjectName("cancelPreviewButton");
  previewProgress_ = new QProgressBar(prevBox);
  previewProgress_->setRange(0, 1000);
  previewProgress_->setTextVisible(false);
  prevButtons->addWidget(previewButton_);
  prevButtons->addWidget(cancelPreviewButton_);
  prevButtons->addWidget(previewProgress_, 1);
  prev->addLayout(prevButtons);
  previewStatus_ = new QLabel(prevBox);
  previewStatus_->setObjectName("previewStatus");
  previewStatus_->setWordWrap(true);
  prev->addWidget(previewStatus_);
  table_ = new QTableWidget(0, 6, prevBox);
  table_->setObjectName("previewTable");
  table_->setHorizontalHeaderLabels({"Target", "Triangles", "Hausdorff", "of diagonal", "Mean", "Time"});
  table_->verticalHeader()->hide();
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->setMinimumHeight(150);
  curve_ = new ErrorCurve(prevBox);
  auto* results = new QHBoxLayout;
  results->addWidget(table_, 3);
  results->addWidget(curve_, 2);
  prev->addLayout(results);
  layout->addWidget(prevBox, 1);

  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  importButton_ = buttons->button(QDialogButtonBox::Ok);
  importButton_->setText("Import");
  importButton_->setObjectName("importButton");
  layout->addWidget(buttons);

  // The choices of the last import.
  ratio_->setValue(settings.value("import/ratio", 10.0).toDouble());
  triangles_->setValue(settings.value("import/triangles", 500000).toInt());
  maxError_->setValue(settings.value("import/maxError", 0.02).toDouble());
  lods_->setValue(settings.value("import/lods", 0).toInt());
  setDecimation(settings.value("import/decimate", false).toBool(), Target(settings.value("import/target", 0).toInt()),
                0.0);

  connect(previewButton_, &QPushButton::clicked, this, &ImportDialog::runPreview);
  connect(cancelPreviewButton_, &QPushButton::clicked, this, &ImportDialog::cancelPreview);
  connect(preview_, &ImportPreview::progress, this, [this](double f, const QString& stage) {
    previewProgress_->setValue(int(std::lround(f * 1000.0)));
    if (!stage.isEmpty()) previewStatus_->setText(stage + "…");
  });
  connect(preview_, &ImportPreview::finished, this, &ImportDialog::onPreviewFinished);
  connect(buttons, &QDialogButtonBox::accepted, this, [this] {
    cancelPreview();
    remember();
    accept();
  });
  connect(buttons, &QDialogButtonBox::rejected, this, [this] {
    cancelPreview();
    reject();
  });
  for (QCheckBox* c : {clean_, decimate_}) connect(c, &QCheckBox::toggled, this, &ImportDialog::updateEnabled);
  connect(originManual_, &QRadioButton::toggled, this, &ImportDialog::updateEnabled);
  updateEnabled();
  resize(720, 720);
}

ImportDialog::~ImportDialog() = default;

void ImportDialog::setDecimation(bool on, Target target, double value) {
  decimate_->setChecked(on);
  targetKind_->setCurrentIndex(std::clamp(int(target), 0, 2));
  if (value > 0) {
    if (target == Target::Ratio) ratio_->setValue(value);
    else if (target == Target::Triangles) triangles_->setValue(int(std::min(value, 2e9)));
    else maxError_->setValue(value);
  }
  updateEnabled();
}

void ImportDialog::setLodLevels(int levels) { lods_->setValue(levels); }

scene::MeshImportRequest ImportDialog::request() const {
  scene::MeshImportRequest r;
  for (const QString& f : files_) r.files.push_back(f.toStdString());
  const QString up = up_->currentData().toString(), reader = reader_->currentData().toString();
  r.import.up = up == "y" ? mesh::UpAxis::Y : up == "z" ? mesh::UpAxis::Z : mesh::UpAxis::Auto;
  r.import.reader = reader == "obj" ? mesh::Reader::Obj : reader == "assimp" ? mesh::Reader::Assimp : mesh::Reader::Auto;
  using Mode = mesh::ImportOptions::GeoOffsetMode;
  r.import.geoOffsetMode = originAuto_->isChecked() ? Mode::Auto : originManual_->isChecked() ? Mode::Manual : Mode::None;
  if (originManual_->isChecked()) r.import.geoOffset = {origin_[0]->value(), origin_[1]->value(), origin_[2]->value()};

  mesh::ProcessOptions& p = r.processing;
  p.clean = clean_->isChecked();
  p.decimate = decimate_->isChecked();
  switch (Target(targetKind_->currentData().toInt())) {
    case Target::Ratio:
      p.decimation.targetRatio = ratio_->value() / 100.0;
      break;
    case Target::Triangles:
      p.decimation.targetTriangles = size_t(triangles_->value());
      break;
    case Target::MaxError:
      // As far as the error allows (mesh_process.h measures and tightens).
      p.decimation.targetRatio = 0.0;
      p.decimation.maxError = maxError_->value();
      break;
  }
  p.refine = refine_->isChecked();
  p.error.certify = certify_->isChecked();
  p.lodLevels = lods_->value();
  r.process = p.clean || p.decimate || p.lodLevels > 0;
  const QString clusters = clusters_->currentData().toString();
  r.clusters = scene::clustersMode(clusters.toStdString());
  r.tilesetCrs = tilesetCrs_->text().trimmed().toStdString();
  return r;
}

void ImportDialog::runPreview() {
  table_->setRowCount(0);
  curve_->setPoints({}, 0);
  previewProgress_->setValue(0);
  previewStatus_->setText("Reading…");
  preview_->start(request());
  updateEnabled();
}

void ImportDialog::cancelPreview() {
  if (!preview_->isRunning()) return;
  preview_->cancel();
  previewStatus_->setText("Cancelling…");
}

void ImportDialog::onPreviewFinished() {
  updateEnabled();
  if (preview_->cancelled()) {
    previewStatus_->setText("Preview cancelled.");
    previewProgress_->setValue(0);
    return;
  }
  if (!preview_->error().isEmpty()) {
    previewStatus_->setText("<span style='color:#ff6b6b'>" + preview_->error().toHtmlEscaped() + "</span>");
    return;
  }
  previewProgress_->setValue(1000);
  previewStatus_->setText(QString("%L1 triangles after cleaning. Hausdorff: the largest distance between the surfaces, "
                                  "symmetric (%2 samples per face).")
                              .arg(preview_->trianglesIn())
                              .arg(ImportPreview::kSamplesPerFace));
  const auto& pts = preview_->points();
  table_->setRowCount(int(pts.size()));
  for (int i = 0; i < int(pts.size()); ++i) {
    const PreviewPoint& p = pts[size_t(i)];
    table_->setItem(i, 0, cell(p.target + (p.chosen ? " (chosen)" : ""), p.chosen));
    table_->setItem(i, 1, cell(QString("%L1").arg(p.triangles), p.chosen));
    table_->setItem(i, 2, cell(QString("%1 m").arg(p.hausdorff, 0, 'g', 3), p.chosen));
    table_->setItem(i, 3, cell(QString("%1%").arg(p.hausdorffRel * 100.0, 0, 'g', 3), p.chosen));
    table_->setItem(i, 4, cell(QString("%1 m").arg(p.mean, 0, 'g', 3), p.chosen));
    table_->setItem(i, 5, cell(QString("%1 s").arg(p.seconds, 0, 'f', 2), p.chosen));
  }
  curve_->setPoints(pts, preview_->trianglesIn());
}

void ImportDialog::updateEnabled() {
  const bool on = decimate_->isChecked();
  targetKind_->setEnabled(on);
  ratio_->setEnabled(on);
  triangles_->setEnabled(on);
  maxError_->setEnabled(on);
  for (QDoubleSpinBox* b : origin_) b->setEnabled(originManual_->isChecked());
  const bool running = preview_->isRunning();
  previewButton_->setEnabled(!running);
  cancelPreviewButton_->setEnabled(running);
}

void ImportDialog::remember() const {
  QSettings s;
  s.setValue("import/clean", clean_->isChecked());
  s.setValue("import/decimate", decimate_->isChecked());
  s.setValue("import/refine", refine_->isChecked());
  s.setValue("import/certify", certify_->isChecked());
  s.setValue("import/target", targetKind_->currentIndex());
  s.setValue("import/ratio", ratio_->value());
  s.setValue("import/triangles", triangles_->value());
  s.setValue("import/maxError", maxError_->value());
  s.setValue("import/lods", lods_->value());
}

}  // namespace hs::app
