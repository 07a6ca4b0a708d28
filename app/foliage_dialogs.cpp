#include "app/foliage_dialogs.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPixmap>
#include <QPushButton>
#include <QScrollArea>
#include <QTimer>
#include <QVBoxLayout>

#include "app/param_form.h"
#include "app/plant_preview.h"
#include "app/preview_renderer.h"
#include "foliage/foliage_operations.h"

namespace hs::app {
namespace {

constexpr int kPreviewPixels = 220;  // the Generate Plant dialog's live preview

QDialogButtonBox* okCancel(QDialog* d, const QString& okText) {
  auto* b = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, d);
  b->button(QDialogButtonBox::Ok)->setText(okText);
  QObject::connect(b, &QDialogButtonBox::accepted, d, &QDialog::accept);
  QObject::connect(b, &QDialogButtonBox::rejected, d, &QDialog::reject);
  return b;
}

std::vector<ParamDecl> editorParams(const OperationDecl& op) {
  std::vector<ParamDecl> out;
  for (const ParamDecl& p : op.params)
    if (p.editor) out.push_back(p);
  return out;
}

// The scatter options that override a type's rule (declared without a
// default: the type's own applies unless one is given).
const std::vector<std::string>& overrideKeys() {
  static const std::vector<std::string> keys = {"density_per_ha", "layer", "slope_deg", "altitude_m", "surface"};
  return keys;
}

QStringList withNone(const QStringList& names) { return QStringList{QString()} + names; }

}  // namespace

// --- FoliageTypeDialog ----------------------------------------------------------

FoliageTypeDialog::FoliageTypeDialog(QWidget* parent, const QStringList& meshes, const QStringList& layers,
                                     const foliage::FoliageType* initial, const QString& suggestedName)
    : QDialog(parent) {
  setWindowTitle(initial ? "Edit Foliage Type" : "New Foliage Type");
  setObjectName("foliageTypeDialog");
  const OperationDecl& op = foliage::foliageTypeAddOperation();
  auto* top = new QFormLayout;
  name_ = new QLineEdit(initial ? QString::fromStdString(initial->name) : suggestedName, this);
  name_->setObjectName("foliageTypeName");
  name_->setToolTip(QString::fromStdString(op.positionals.front().help));
  top->addRow("Name", name_);
  // The form scrolls: a type has twenty fields.
  auto* scroll = new QScrollArea(this);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  form_ = new ParamForm(editorParams(op), scroll, {{"mesh", meshes}, {"layer", withNone(layers)}});
  scroll->setWidget(form_);
  if (initial) {
    const Json j = foliage::toJson(*initial);
    for (auto it = j.begin(); it != j.end(); ++it) form_->setValue(it.key(), it.value());
  }
  error_ = new QLabel(this);
  error_->setObjectName("foliageTypeError");
  error_->setWordWrap(true);
  error_->setStyleSheet("QLabel { color: #ff8a75; }");
  error_->hide();
  auto* v = new QVBoxLayout(this);
  v->addLayout(top);
  v->addWidget(scroll, 1);
  v->addWidget(error_);
  v->addWidget(okCancel(this, initial ? "Apply" : "Add Type"));
  resize(460, 620);
}

bool FoliageTypeDialog::type(foliage::FoliageType& out, std::string& error) const {
  const std::string name = name_->text().trimmed().toStdString();
  if (name.empty()) {
    error = "foliage type: name: a type needs a name";
    return false;
  }
  return foliage::typeFromValues(name, form_->values(), out, error);
}

void FoliageTypeDialog::accept() {
  foliage::FoliageType t;
  std::string error;
  if (!type(t, error)) {
    // Stays open: the user fixes the field the message names.
    error_->setText(QString::fromStdString(error));
    error_->show();
    return;
  }
  QDialog::accept();
}

// --- PlantDialog ------------------------------------------------------------------

PlantDialog::PlantDialog(QWidget* parent, const QString& suggestedName) : QDialog(parent) {
  setWindowTitle("Generate Plant");
  setObjectName("plantDialog");
  const OperationDecl& op = foliage::foliagePlantOperation();
  auto* top = new QFormLayout;
  name_ = new QLineEdit(suggestedName, this);
  name_->setObjectName("plantName");
  name_->setToolTip(QString::fromStdString(op.positionals.front().help));
  top->addRow("Asset name", name_);
  form_ = new ParamForm(editorParams(op), this);
  connect(qobject_cast<QComboBox*>(form_->field("kind")), &QComboBox::currentIndexChanged, this,
          [this] { showKindDefaults(); });
  showKindDefaults();
  auto* note = new QLabel("Makes a mesh asset with its levels of detail (no entity): a foliage type draws it.", this);
  note->setWordWrap(true);
  preview_ = new QLabel(this);
  preview_->setObjectName("plantPreview");
  preview_->setFixedSize(kPreviewPixels, kPreviewPixels);
  preview_->setAlignment(Qt::AlignCenter);
  preview_->setWordWrap(true);
  preview_->setToolTip("The plant these fields grow, at full detail");
  renderer_ = new PreviewRenderer(this);
  connect(renderer_, &PreviewRenderer::ready, this, [this](int, const QImage& image) {
    preview_->setPixmap(QPixmap::fromImage(image));
    ++previewsShown_;
  });
  connect(renderer_, &PreviewRenderer::problem, this, [this](const QString& m) { preview_->setText(m); });
  // A moment after the last edit: typing a number renders once.
  previewDelay_ = new QTimer(this);
  previewDelay_->setSingleShot(true);
  previewDelay_->setInterval(150);
  connect(previewDelay_, &QTimer::timeout, this, [this] { requestPreview(); });
  connect(form_, &ParamForm::edited, previewDelay_, qOverload<>(&QTimer::start));
  auto* v = new QVBoxLayout;
  v->addLayout(top);
  v->addWidget(form_);
  v->addWidget(note);
  auto* h = new QHBoxLayout;
  h->addLayout(v, 1);
  h->addWidget(preview_, 0, Qt::AlignTop);
  auto* outer = new QVBoxLayout(this);
  outer->addLayout(h);
  outer->addWidget(okCancel(this, "Generate"));
  requestPreview();
}

void PlantDialog::requestPreview() {
  std::string error;
  std::optional<scene::SceneState> s = plantPreviewScene(params(), error);
  if (!s) {
    preview_->setText(QString::fromStdString(error));
    return;
  }
  renderer_->request(0, std::move(*s), kPreviewCamera, kPreviewPixels);
}

void PlantDialog::showKindDefaults() {
  const foliage::PlantParams d = foliage::plantFromValues(Json{{"kind", form_->values().value("kind", "broadleaf")}});
  form_->setValue("height_m", d.height);
  form_->setValue("levels", d.levels);
  form_->setValue("branches", d.branches);
  form_->setValue("leaf_size_m", d.leafSize);
  form_->setValue("leaves_per_branch", d.leavesPerBranch);
  form_->setValue("sides", d.sides);
  if (previewDelay_) previewDelay_->start();
}

QString PlantDialog::name() const { return name_->text().trimmed(); }

foliage::PlantParams PlantDialog::params() const { return foliage::plantFromValues(form_->values()); }

// --- FoliageScatterDialog -----------------------------------------------------------

FoliageScatterDialog::FoliageScatterDialog(QWidget* parent, const std::vector<foliage::FoliageType>& types,
                                           int selected, const QStringList& layers)
    : QDialog(parent), types_(types) {
  setWindowTitle("Scatter Foliage");
  setObjectName("foliageScatterDialog");
  const OperationDecl& op = foliage::foliageScatterOperation();
  auto* top = new QFormLayout;
  which_ = new QComboBox(this);
  which_->setObjectName("foliageScatterTypes");
  for (const foliage::FoliageType& t : types) which_->addItem(QString::fromStdString(t.name));
  which_->addItem("All types, competing for room (in list order)");
  which_->setToolTip("One type by its rules (overridden below where checked), or every type in the list's order: "
                     "the first keep room around them from the later ones");
  which_->setCurrentIndex(selected >= 0 && selected < int(types.size()) ? selected : int(types.size()));
  top->addRow("Types", which_);
  // Every option of `foliage scatter` (the seed and the region too, which
  // the CLI offers though no other dialog shows them).
  std::vector<std::string> optional = overrideKeys();
  optional.push_back("region");
  form_ = new ParamForm(op.params, this, {{"layer", withNone(layers)}}, optional);
  connect(which_, &QComboBox::currentIndexChanged, this, [this] { showTypeRules(); });
  showTypeRules();
  auto* note = new QLabel("One undo step. Millions of instances take a second or two.", this);
  note->setWordWrap(true);
  auto* v = new QVBoxLayout(this);
  v->addLayout(top);
  v->addWidget(form_);
  v->addWidget(note);
  v->addWidget(okCancel(this, "Scatter"));
}

void FoliageScatterDialog::showTypeRules() {
  const int i = which_->currentIndex();
  const bool one = i >= 0 && i < int(types_.size());
  // Competing types each keep their own rules (scene::ops::scatterFoliage
  // overrides one type only).
  for (const std::string& key : overrideKeys()) form_->setRowEnabled(key, one);
  if (!one) return;
  const Json j = foliage::toJson(types_[size_t(i)]);
  for (const std::string& key : overrideKeys())
    if (j.contains(key)) form_->setValue(key, j[key]);
}

foliage::TypeSet FoliageScatterDialog::types() const {
  const int i = which_->currentIndex();
  if (i >= 0 && i < int(types_.size())) return {uint16_t(i)};
  foliage::TypeSet all;
  for (size_t t = 0; t < types_.size(); ++t) all.push_back(uint16_t(t));
  return all;
}

Json FoliageScatterDialog::values() const { return form_->values(); }

// --- FoliageFillDialog -----------------------------------------------------------

FoliageFillDialog::FoliageFillDialog(QWidget* parent, const std::vector<foliage::FoliageType>& types, int selected,
                                     const QStringList& layers)
    : QDialog(parent) {
  setWindowTitle("Fill Paint Layer");
  setObjectName("foliageFillDialog");
  const OperationDecl& op = foliage::foliageFillOperation();
  auto* top = new QFormLayout;
  which_ = new QComboBox(this);
  which_->setObjectName("foliageFillType");
  for (const foliage::FoliageType& t : types) which_->addItem(QString::fromStdString(t.name));
  which_->setCurrentIndex(selected >= 0 && selected < int(types.size()) ? selected : 0);
  top->addRow("Type", which_);
  form_ = new ParamForm(op.params, this, {{"layer", layers}}, {"region"});
  auto* note = new QLabel(QString::fromStdString(op.description), this);
  note->setWordWrap(true);
  auto* v = new QVBoxLayout(this);
  v->addLayout(top);
  v->addWidget(form_);
  v->addWidget(note);
  v->addWidget(okCancel(this, "Fill"));
}

foliage::TypeSet FoliageFillDialog::types() const {
  const int i = which_->currentIndex();
  return i >= 0 ? foliage::TypeSet{uint16_t(i)} : foliage::TypeSet{};
}

Json FoliageFillDialog::values() const { return form_->values(); }

FoliageMoveDialog::FoliageMoveDialog(QWidget* parent, size_t selected) : QDialog(parent) {
  setWindowTitle("Move Selected Instances");
  setObjectName("foliageMoveDialog");
  const OperationDecl& op = foliage::foliageMoveOperation();
  form_ = new ParamForm(op.params, this, {}, {"region"});
  auto* note = new QLabel(QString("%1 selected instance(s). ").arg(selected) +
                              QString::fromStdString(op.description).replace("every instance of a type (or those in "
                                                                             "a region)",
                                                                             "the selected instances"),
                          this);
  note->setWordWrap(true);
  auto* v = new QVBoxLayout(this);
  v->addWidget(form_);
  v->addWidget(note);
  v->addWidget(okCancel(this, "Move"));
}

Json FoliageMoveDialog::values() const { return form_->values(); }

}  // namespace hs::app
