#include "app/camera_path_panel.h"

#include <cmath>
#include <optional>
#include <tuple>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QScrollArea>
#include <QVBoxLayout>

#include "app/field_editors.h"
#include "app/form_widgets.h"
#include "app/param_widgets.h"
#include "app/path_editor.h"

namespace hs::app {

namespace {

enum AimChoice { kAlong = 0, kAtPoint = 1, kAtEntity = 2 };

QPushButton* button(QWidget* parent, const QString& text, const QString& name, const QString& tip) {
  auto* b = new QPushButton(text, parent);
  b->setObjectName(name);
  b->setToolTip(tip);
  return b;
}

FieldEditor* fieldEditor(QWidget* parent, const std::string& path, scene::FieldType type, double min, double max,
                    double step, const std::string& unit) {
  FieldSpec spec;
  spec.path = path;
  spec.type = type;
  spec.min = min;
  spec.max = max;
  spec.step = step;
  spec.unit = unit;
  return createFieldEditor(spec, parent);
}

QString pointText(size_t i, const glm::dvec3& p) {
  return QString("%1   %2, %3, %4").arg(i + 1).arg(p.x, 0, 'f', 2).arg(p.y, 0, 'f', 2).arg(p.z, 0, 'f', 2);
}

}  // namespace

CameraPathPanel::CameraPathPanel(PathEditor& pathEditor, std::function<glm::dvec3()> viewEye, QWidget* parent)
    : QWidget(parent), editor_(pathEditor), viewEye_(std::move(viewEye)) {
  setObjectName("cameraPathPanel");
  auto* content = new QWidget;
  auto* v = new QVBoxLayout(content);
  v->setContentsMargins(6, 6, 6, 6);
  putInScrollArea(this, content, true);

  header_ = new QLabel(content);
  header_->setObjectName("pathHeader");
  header_->setWordWrap(true);
  v->addWidget(header_);

  // --- no path yet
  createBox_ = new QWidget(content);
  auto* c = new QVBoxLayout(createBox_);
  c->setContentsMargins(0, 0, 0, 0);
  auto* create = button(createBox_, "Follow Path", "pathCreate",
                        "A path from the camera's position at the playhead to a point ahead of it, covered at "
                        "constant speed over the playback range; add and drag points to shape it");
  fromKeys_ = button(createBox_, "From Location Keys", "pathFromKeys",
                     "A path through the camera's location keys, covered at constant speed over their times (the "
                     "keys become the path's points)");
  c->addWidget(create);
  c->addWidget(fromKeys_);
  v->addWidget(createBox_);
  connect(create, &QPushButton::clicked, this, [this] { editor_.createAhead(); });
  connect(fromKeys_, &QPushButton::clicked, this, [this] { editor_.createFromKeys(); });

  // --- a path
  editBox_ = new QWidget(content);
  auto* form = new QFormLayout(editBox_);
  form->setContentsMargins(0, 0, 0, 0);
  points_ = new QListWidget(editBox_);
  points_->setObjectName("pathPoints");
  points_->setMaximumHeight(140);
  points_->setToolTip("The path's points (drawn as orange diamonds; drag them in the viewport)");
  form->addRow(points_);
  auto* row = new QHBoxLayout;
  auto* addAtView = button(editBox_, "Add at View", "pathAddAtView",
                           "A point where the viewport looks from, after the selected point (else at the end)");
  auto* insert = button(editBox_, "Insert After", "pathInsert",
                        "A point on the curve after the selected point (beyond the end after the last one)");
  delete_ = button(editBox_, "Delete", "pathDelete", "Delete the selected point (Delete in the viewport)");
  row->addWidget(addAtView);
  row->addWidget(insert);
  row->addWidget(delete_);
  form->addRow(row);
  point_ = fieldEditor(editBox_, "path.point", scene::FieldType::Vec3, -1e300, 1e300, 0.1, "m");
  form->addRow("Point", point_);

  aim_ = new QComboBox(editBox_);
  aim_->setObjectName("pathAim");
  aim_->addItems({"Along the path", "At a point", "At an entity"});
  form->addRow("Look", aim_);
  targetPoint_ = fieldEditor(editBox_, "path.target", scene::FieldType::Vec3, -1e300, 1e300, 0.1, "m");
  form->addRow("Target", targetPoint_);
  targetEntity_ = new QComboBox(editBox_);
  targetEntity_->setObjectName("pathTargetEntity");
  targetEntity_->setToolTip("The entity to look at (followed as it moves)");
  form->addRow("Entity", targetEntity_);

  bank_ = new QCheckBox("Bank into turns", editBox_);
  bank_->setObjectName("pathBank");
  bank_->setToolTip("Roll into turns like an aircraft in a coordinated turn (from the path's curvature and speed)");
  form->addRow(bank_);
  // Banking's limit and strength as `path --bank/--bank-scale` declare them.
  const std::vector<ParamDecl>& follow = sequencer::pathFollowParamDecls();
  for (auto [field, key, path] : {std::tuple{&bankMax_, "bank_deg", "path.bank_max_deg"},
                                  std::tuple{&bankScale_, "bank_scale", "path.bank_scale"}}) {
    const ParamDecl& p = paramIn(follow, key);
    *field = createFieldEditor(paramFieldSpec(p, path), editBox_);
    tagParamWidget((*field)->findChild<QDoubleSpinBox*>(), p);
    (*field)->setToolTip(QString::fromStdString(paramHelp(p)));
    form->addRow(paramLabel(p), *field);
  }

  auto* timing = new QHBoxLayout;
  auto* constant = button(editBox_, "Constant Speed", "pathConstantSpeed",
                          "Cover the path at constant speed over the playback range (replaces the progress keys)");
  auto* eased = button(editBox_, "Ease In/Out", "pathEase",
                       "Cover the path over the playback range, starting and stopping softly");
  timing->addWidget(constant);
  timing->addWidget(eased);
  form->addRow(timing);
  progress_ = fieldEditor(editBox_, "path.progress_pct", scene::FieldType::Double, -1000.0, 1000.0, 1.0, "%");
  progress_->setToolTip("The share of the path travelled at the playhead; an edit keys it there (path.progress on "
                        "the timeline: retime, ease or delete those keys like any other)");
  form->addRow("Progress", progress_);
  info_ = new QLabel(editBox_);
  info_->setObjectName("pathInfo");
  info_->setWordWrap(true);
  form->addRow(info_);
  auto* remove = button(editBox_, "Remove Path", "pathRemove",
                        "The camera stops following the path and keeps its own transform");
  form->addRow(remove);
  v->addWidget(editBox_);
  v->addStretch();

  connect(points_, &QListWidget::currentRowChanged, this, [this](int r) { editor_.selectPoint(r); });
  connect(addAtView, &QPushButton::clicked, this, [this] { editor_.addPoint(viewEye_()); });
  connect(insert, &QPushButton::clicked, this, [this] { editor_.insertPointAfter(); });
  connect(delete_, &QPushButton::clicked, this, [this] { editor_.deleteSelectedPoint(); });
  point_->setOnEdited([this](const scene::FieldValue& value, int, const QString& key) {
    editor_.movePoint(editor_.selectedPoint(), std::get<glm::dvec3>(value), key);
  });
  connect(aim_, &QComboBox::activated, this, &CameraPathPanel::chooseAim);
  targetPoint_->setOnEdited([this](const scene::FieldValue& value, int, const QString& key) {
    editor_.aimAtPoint(std::get<glm::dvec3>(value), key);
  });
  connect(targetEntity_, &QComboBox::activated, this,
          [this](int i) { editor_.aimAtEntity(targetEntity_->itemData(i).toULongLong()); });
  auto banking = [this](bool on, std::optional<double> max, std::optional<double> scale, const QString& key) {
    const sequencer::PathFollow* p = editor_.path();
    if (!p) return;
    editor_.setBanking(on, max.value_or(p->maxBankDeg), scale.value_or(p->bankScale), key);
  };
  connect(bank_, &QCheckBox::clicked, this, [banking](bool on) { banking(on, std::nullopt, std::nullopt, {}); });
  bankMax_->setOnEdited([this, banking](const scene::FieldValue& value, int, const QString& key) {
    // A limit of 0 turns banking off, as `path --bank 0` does (the path
    // keeps its last limit for when it is turned on again).
    const double limit = std::get<double>(value);
    if (limit <= 0.0) banking(false, std::nullopt, std::nullopt, key);
    else banking(bank_->isChecked(), limit, std::nullopt, key);
  });
  bankScale_->setOnEdited([this, banking](const scene::FieldValue& value, int, const QString& key) {
    banking(bank_->isChecked(), std::nullopt, std::get<double>(value), key);
  });
  connect(constant, &QPushButton::clicked, this, [this] { editor_.setConstantSpeed(sequencer::Ease::None); });
  connect(eased, &QPushButton::clicked, this, [this] { editor_.setConstantSpeed(sequencer::Ease::InOut); });
  progress_->setOnEdited([this](const scene::FieldValue& value, int, const QString& key) {
    editor_.keyProgress(std::get<double>(value) / 100.0, key);
  });
  connect(remove, &QPushButton::clicked, this, [this] { editor_.removePath(); });
  connect(&editor_, &PathEditor::changed, this, &CameraPathPanel::refresh);
  refresh();
}

void CameraPathPanel::chooseAim(int index) {
  switch (index) {
    case kAlong: editor_.aimAlong(); break;
    case kAtPoint: editor_.aimAtPoint(editor_.defaultAimPoint()); break;
    case kAtEntity:
      refillTargets();
      if (targetEntity_->count() > 0) editor_.aimAtEntity(targetEntity_->itemData(0).toULongLong());
      break;
    default: break;
  }
  refresh();  // a refused choice shows the aim the path still has
}

void CameraPathPanel::refillTargets() {
  const scene::SceneState& s = editor_.document().state();
  const QSignalBlocker block(targetEntity_);
  targetEntity_->clear();
  for (scene::EntityId id : s.depthFirstOrder())
    if (id != editor_.entity())
      targetEntity_->addItem(QString::fromStdString(s.find(id)->name), QVariant::fromValue<qulonglong>(id));
}

void CameraPathPanel::refresh() {
  const scene::SceneState& s = editor_.document().state();
  const scene::Entity* e = s.find(editor_.entity());
  const sequencer::PathFollow* p = editor_.path();
  if (!e) header_->setText("Select a camera to give it a path to follow.");
  else if (!p) header_->setText(QString("<b>%1</b> follows no path.").arg(QString::fromStdString(e->name).toHtmlEscaped()));
  else header_->setText(QString("<b>%1</b> follows this path.").arg(QString::fromStdString(e->name).toHtmlEscaped()));
  createBox_->setVisible(e && !p);
  editBox_->setVisible(p != nullptr);
  fromKeys_->setEnabled(editor_.canCreateFromKeys());
  if (!p) return;

  const int selected = editor_.selectedPoint();
  {
    const QSignalBlocker block(points_);
    if (points_->count() != int(p->path.points.size())) {
      points_->clear();
      for (size_t i = 0; i < p->path.points.size(); ++i) points_->addItem(pointText(i, p->path.points[i]));
    } else {
      for (size_t i = 0; i < p->path.points.size(); ++i) points_->item(int(i))->setText(pointText(i, p->path.points[i]));
    }
    points_->setCurrentRow(selected);
  }
  delete_->setEnabled(selected >= 0 && p->path.points.size() > 2);
  point_->setEnabled(selected >= 0);
  if (selected >= 0) point_->setValue(scene::FieldValue(p->path.points[size_t(selected)]));

  {
    const QSignalBlocker block(aim_);
    aim_->setCurrentIndex(p->aim == sequencer::PathAim::Point ? kAtPoint
                          : p->aim == sequencer::PathAim::Entity ? kAtEntity
                                                                 : kAlong);
  }
  targetPoint_->setValue(scene::FieldValue(p->targetPoint));
  if (auto* form = qobject_cast<QFormLayout*>(editBox_->layout())) {
    form->setRowVisible(targetPoint_, p->aim == sequencer::PathAim::Point);
    form->setRowVisible(targetEntity_, p->aim == sequencer::PathAim::Entity);
    form->setRowVisible(bankMax_, p->bank);
    form->setRowVisible(bankScale_, p->bank);
  }
  if (p->aim == sequencer::PathAim::Entity) {
    refillTargets();
    const QSignalBlocker block(targetEntity_);
    targetEntity_->setCurrentIndex(targetEntity_->findData(QVariant::fromValue<qulonglong>(p->targetEntity)));
  }
  {
    const QSignalBlocker block(bank_);
    bank_->setChecked(p->bank);
  }
  bankMax_->setValue(scene::FieldValue(p->maxBankDeg));
  bankScale_->setValue(scene::FieldValue(p->bankScale));
  const auto share = editor_.progressNow();
  progress_->setValue(scene::FieldValue(share.value_or(0.0) * 100.0));

  const sequencer::PathSampler sampler(p->path.points);
  QString info = QString("%1 points, %2 m").arg(p->path.points.size()).arg(sampler.length(), 0, 'f', 2);
  const auto& keys = p->progress.keys;
  if (keys.size() >= 2 && keys.back().time > keys.front().time)
    info += QString(", %1 s to %2 s (average %3 m/s)")
                .arg(keys.front().time, 0, 'g', 6)
                .arg(keys.back().time, 0, 'g', 6)
                .arg(sampler.length() * std::abs(keys.back().value - keys.front().value) /
                         (keys.back().time - keys.front().time),
                     0, 'f', 2);
  else if (keys.empty())
    info += "; no progress keys: the camera stays at the start (key Progress to move it)";
  info_->setText(info);
}

}  // namespace hs::app
