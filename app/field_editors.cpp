#include "app/field_editors.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPointer>
#include <QToolButton>
#include <QWheelEvent>

#include "core/srgb.h"

namespace hs::app {
namespace {

std::atomic<int> gestureCounter{0};

// Spin boxes size themselves to their widest possible text; with ranges
// of +-1e300 that is absurd, and positions at UTM coordinates need no more
// than this.
constexpr double kSpinLimit = 1e12;

int decimalsFor(const FieldSpec& spec) {
  if (spec.type == scene::FieldType::Color) return 3;
  const int fromStep = spec.step > 0.0 ? int(std::ceil(-std::log10(spec.step))) + 2 : 4;
  return std::clamp(fromStep, 2, 6);
}

void configure(ScrubSpinBox* s, const FieldSpec& spec) {
  s->setRange(std::max(spec.min, -kSpinLimit), std::min(spec.max, kSpinLimit));
  s->setSingleStep(spec.type == scene::FieldType::Color ? 0.01 : spec.step);
  s->setDecimals(decimalsFor(spec));
  if (!spec.unit.empty()) s->setSuffix((spec.unit == "°" ? "" : " ") + QString::fromStdString(spec.unit));
}

class DoubleEditor : public FieldEditor {
 public:
  DoubleEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    spin_ = new ScrubSpinBox(this);
    spin_->setObjectName(QString::fromStdString(spec.path));
    configure(spin_, spec);
    l->addWidget(spin_);
    connect(spin_, &ScrubSpinBox::valueEdited, this,
            [this](double v, const QString& key) { edited(scene::FieldValue(v), -1, key); });
  }
  void setValue(const scene::FieldValue& v) override { spin_->showValue(std::get<double>(v)); }

 private:
  ScrubSpinBox* spin_;
};

class Vec3Editor : public FieldEditor {
 public:
  Vec3Editor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    l->setSpacing(3);
    const char* names[3] = {"x", "y", "z"};
    const char* colors[3] = {"#e8605a", "#7fcf4f", "#5a94f0"};
    for (int i = 0; i < 3; ++i) {
      auto* label = new QLabel(QString(names[i]).toUpper(), this);
      label->setStyleSheet(QString("QLabel { color: %1; font-weight: bold; padding: 0 1px; }").arg(colors[i]));
      spins_[i] = new ScrubSpinBox(this);
      spins_[i]->setObjectName(QString::fromStdString(spec.path) + "." + names[i]);
      configure(spins_[i], spec);
      spins_[i]->setMinimumWidth(48);
      spins_[i]->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
      l->addWidget(label);
      l->addWidget(spins_[i], 1);
      connect(spins_[i], &ScrubSpinBox::valueEdited, this, [this, i](double v, const QString& key) {
        glm::dvec3 value(spins_[0]->value(), spins_[1]->value(), spins_[2]->value());
        value[i] = v;
        edited(scene::FieldValue(value), i, key);
      });
    }
  }
  void setValue(const scene::FieldValue& v) override {
    const glm::dvec3 x = std::get<glm::dvec3>(v);
    for (int i = 0; i < 3; ++i) spins_[i]->showValue(x[i]);
  }

 private:
  ScrubSpinBox* spins_[3];
};

class BoolEditor : public FieldEditor {
 public:
  BoolEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    box_ = new QCheckBox(this);
    box_->setObjectName(QString::fromStdString(spec.path));
    l->addWidget(box_);
    l->addStretch();
    connect(box_, &QCheckBox::clicked, this, [this](bool on) { edited(scene::FieldValue(on), -1, {}); });
  }
  void setValue(const scene::FieldValue& v) override {
    const QSignalBlocker block(box_);
    box_->setChecked(std::get<bool>(v));
  }

 private:
  QCheckBox* box_;
};

class EnumEditor : public FieldEditor {
 public:
  EnumEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    combo_ = new QComboBox(this);
    combo_->setObjectName(QString::fromStdString(spec.path));
    for (const auto& n : spec.enumNames) combo_->addItem(QString::fromStdString(n));
    l->addWidget(combo_);
    connect(combo_, &QComboBox::activated, this, [this](int i) { edited(scene::FieldValue(int64_t(i)), -1, {}); });
  }
  void setValue(const scene::FieldValue& v) override {
    const QSignalBlocker block(combo_);
    combo_->setCurrentIndex(int(std::get<int64_t>(v)));
  }

 private:
  QComboBox* combo_;
};

class StringEditor : public FieldEditor {
 public:
  StringEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    edit_ = new QLineEdit(this);
    edit_->setObjectName(QString::fromStdString(spec.path));
    l->addWidget(edit_);
    connect(edit_, &QLineEdit::editingFinished, this, [this] {
      const QString text = edit_->text();
      if (text == shown_) return;
      shown_ = text;
      edited(scene::FieldValue(text.toStdString()), -1, {});
    });
    choices_ = new QComboBox(this);
    choices_->setObjectName(QString::fromStdString(spec.path + ".choices"));
    choices_->hide();
    l->addWidget(choices_);
    connect(choices_, &QComboBox::activated, this, [this](int index) {
      const QString value = choices_->itemData(index).toString();
      if (value == shown_) return;
      shown_ = value;
      edited(scene::FieldValue(value.toStdString()), -1, {});
    });
  }
  void setValue(const scene::FieldValue& v) override {
    const QString text = QString::fromStdString(std::get<std::string>(v));
    shown_ = text;
    if (edit_->text() != text && !edit_->hasFocus()) edit_->setText(text);
    showInChoices();
  }
  void setChoices(const std::vector<std::pair<std::string, std::string>>& choices) override {
    const QSignalBlocker block(choices_);
    choices_->clear();
    for (const auto& [value, text] : choices)
      choices_->addItem(QString::fromStdString(text), QString::fromStdString(value));
    choices_->setVisible(!choices.empty());
    edit_->setVisible(choices.empty());
    showInChoices();
  }

 private:
  void showInChoices() {
    const QSignalBlocker block(choices_);
    int at = choices_->findData(shown_);
    if (at < 0 && choices_->count() > 0) {
      // A value the list lacks (a config changed under it) stays visible as such.
      choices_->addItem(QString("%1 (not in the list)").arg(shown_), shown_);
      at = choices_->count() - 1;
    }
    choices_->setCurrentIndex(at);
  }
  QLineEdit* edit_;
  QComboBox* choices_;
  QString shown_;
};

class ColorEditor : public FieldEditor {
 public:
  ColorEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    swatch_ = new QToolButton(this);
    swatch_->setObjectName(QString::fromStdString(spec.path));
    swatch_->setFixedSize(44, 20);
    swatch_->setToolTip("Pick a colour");
    text_ = new QLabel(this);
    text_->setStyleSheet("QLabel { color: #9a9ba0; }");
    l->addWidget(swatch_);
    l->addWidget(text_, 1);
    connect(swatch_, &QToolButton::clicked, this, &ColorEditor::openDialog);
  }
  void setValue(const scene::FieldValue& v) override {
    value_ = std::get<glm::dvec3>(v);
    const QColor c = linearToDisplay(value_);
    swatch_->setStyleSheet(QString("QToolButton { background: %1; border: 1px solid #1c1c1e; border-radius: 3px; }")
                               .arg(c.name()));
    text_->setText(QString("%1, %2, %3").arg(value_.x, 0, 'f', 3).arg(value_.y, 0, 'f', 3).arg(value_.z, 0, 'f', 3));
  }

 private:
  void openDialog() {
    if (dialog_) {
      dialog_->raise();
      return;
    }
    original_ = value_;
    auto* dialog = new QColorDialog(linearToDisplay(value_), this);
    dialog_ = dialog;
    dialog->setOption(QColorDialog::DontUseNativeDialog);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->setWindowTitle("Colour");
    // Live preview: every change of the picker is part of one undo step;
    // Cancel puts the original back, which leaves that step empty.
    connect(dialog, &QColorDialog::currentColorChanged, this,
            [this](const QColor& c) { edited(scene::FieldValue(displayToLinear(c)), -1, gesture_.current()); });
    connect(dialog, &QColorDialog::colorSelected, this,
            [this](const QColor& c) { edited(scene::FieldValue(displayToLinear(c)), -1, gesture_.current()); });
    connect(dialog, &QDialog::rejected, this, [this] {
      if (gesture_.active()) edited(scene::FieldValue(original_), -1, gesture_.current());
      gesture_.end();
    });
    connect(dialog, &QDialog::accepted, this, [this] { gesture_.end(); });
    dialog->open();
  }

  QToolButton* swatch_;
  QLabel* text_;
  glm::dvec3 value_{0.0}, original_{0.0};
  QPointer<QColorDialog> dialog_;
  GestureKey gesture_;
};

class AssetEditor : public FieldEditor {
 public:
  AssetEditor(const FieldSpec& spec, QWidget* parent) : FieldEditor(parent) {
    auto* l = new QHBoxLayout(this);
    l->setContentsMargins(0, 0, 0, 0);
    combo_ = new QComboBox(this);
    combo_->setObjectName(QString::fromStdString(spec.path));
    combo_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    combo_->setMinimumContentsLength(12);
    l->addWidget(combo_);
    connect(combo_, &QComboBox::activated, this, [this](int i) {
      edited(scene::FieldValue(int64_t(combo_->itemData(i).toLongLong())), -1, {});
    });
  }
  void setAssets(const scene::SceneState& state) override {
    QStringList labels;
    QList<qlonglong> ids{0};
    labels << "(none)";
    for (const auto& [id, a] : state.assets) {
      ids << qlonglong(id);
      labels << QString("%1  (%L2 tris)").arg(QString::fromStdString(a.name)).arg(a.data ? a.data->triangleCount() : 0);
    }
    if (labels == labels_ && ids == ids_) return;
    labels_ = labels;
    ids_ = ids;
    const QSignalBlocker block(combo_);
    combo_->clear();
    for (qsizetype i = 0; i < labels.size(); ++i) combo_->addItem(labels[i], ids[i]);
  }
  void setValue(const scene::FieldValue& v) override {
    const QSignalBlocker block(combo_);
    combo_->setCurrentIndex(std::max(0, combo_->findData(qlonglong(std::get<int64_t>(v)))));
  }

 private:
  QComboBox* combo_;
  QStringList labels_;
  QList<qlonglong> ids_;
};

}  // namespace

QString GestureKey::current() {
  if (key_.isEmpty()) key_ = QString("gesture-%1").arg(++gestureCounter);
  return key_;
}

ScrubSpinBox::ScrubSpinBox(QWidget* parent) : QDoubleSpinBox(parent) {
  setKeyboardTracking(true);
  setFocusPolicy(Qt::StrongFocus);
  setAccelerated(true);
  setButtonSymbols(QAbstractSpinBox::NoButtons);
  setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  lineEdit()->installEventFilter(this);
  lineEdit()->setCursor(Qt::SizeHorCursor);
  setToolTip("Drag sideways to change (Shift: fine, Ctrl: coarse), or click and type");
  connect(this, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    if (!programmatic_) emit valueEdited(v, gesture_.current());
  });
  connect(this, &QAbstractSpinBox::editingFinished, this, [this] { gesture_.end(); });
}

void ScrubSpinBox::showValue(double v) {
  const double tolerance = 0.5 * std::pow(10.0, -decimals());
  if (std::abs(value() - v) <= tolerance) return;
  programmatic_ = true;
  setValue(v);
  programmatic_ = false;
}

bool ScrubSpinBox::eventFilter(QObject* watched, QEvent* e) {
  if (watched != lineEdit()) return QDoubleSpinBox::eventFilter(watched, e);
  switch (e->type()) {
    case QEvent::MouseButtonPress: {
      auto* m = static_cast<QMouseEvent*>(e);
      if (m->button() != Qt::LeftButton) break;
      pressed_ = true;
      scrubbing_ = false;
      pressPos_ = m->globalPosition().toPoint();
      pressValue_ = value();
      break;  // the line edit still places its cursor
    }
    case QEvent::MouseMove: {
      if (!pressed_) break;
      auto* m = static_cast<QMouseEvent*>(e);
      const int dx = m->globalPosition().toPoint().x() - pressPos_.x();
      if (!scrubbing_ && std::abs(dx) > 3) {
        scrubbing_ = true;
        lineEdit()->deselect();
      }
      if (!scrubbing_) break;
      double factor = 1.0;
      if (m->modifiers() & Qt::ShiftModifier) factor = 0.1;
      if (m->modifiers() & Qt::ControlModifier) factor = 10.0;
      setValue(pressValue_ + dx * singleStep() * factor);
      return true;
    }
    case QEvent::MouseButtonRelease:
      if (!pressed_) break;
      pressed_ = false;
      if (scrubbing_) {
        scrubbing_ = false;
        gesture_.end();
        return true;
      }
      break;
    default: break;
  }
  return QDoubleSpinBox::eventFilter(watched, e);
}

void ScrubSpinBox::wheelEvent(QWheelEvent* e) {
  if (!hasFocus()) {
    e->ignore();  // let the panel scroll
    return;
  }
  QDoubleSpinBox::wheelEvent(e);
}

void ScrubSpinBox::mouseReleaseEvent(QMouseEvent* e) {
  QDoubleSpinBox::mouseReleaseEvent(e);
  gesture_.end();
}

FieldEditor* createFieldEditor(const FieldSpec& spec, QWidget* parent) {
  switch (spec.type) {
    case scene::FieldType::Double: return new DoubleEditor(spec, parent);
    case scene::FieldType::Bool: return new BoolEditor(spec, parent);
    case scene::FieldType::Enum: return new EnumEditor(spec, parent);
    case scene::FieldType::Vec3: return new Vec3Editor(spec, parent);
    case scene::FieldType::Color: return new ColorEditor(spec, parent);
    case scene::FieldType::String: return new StringEditor(spec, parent);
    case scene::FieldType::AssetRef: return new AssetEditor(spec, parent);
  }
  return nullptr;
}

QColor linearToDisplay(const glm::dvec3& linear) {
  return QColor::fromRgbF(float(linearToSrgb(linear.x)), float(linearToSrgb(linear.y)), float(linearToSrgb(linear.z)));
}

glm::dvec3 displayToLinear(const QColor& c) {
  return {srgbToLinear(double(c.redF())), srgbToLinear(double(c.greenF())), srgbToLinear(double(c.blueF()))};
}

}  // namespace hs::app
