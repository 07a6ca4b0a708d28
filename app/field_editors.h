#pragma once
// Editor widgets for the field types of scene/fields.h. The property and
// scene-settings panels build them from the field tables, so a field added
// there appears here with no UI code. An editor reports each change with a
// merge key that stays the same for one gesture (a spin box being dragged,
// scrubbed or typed into, a colour being picked), so the gesture is one undo
// step; a click or a choice from a list has its own step.
#include <functional>
#include <string>
#include <vector>

#include <QDoubleSpinBox>
#include <QString>
#include <QWidget>

#include "scene/document.h"
#include "scene/fields.h"

class QCheckBox;
class QComboBox;
class QLineEdit;
class QToolButton;
class QColorDialog;

namespace hs::app {

// Hands out merge keys: one per gesture, a new one after end().
class GestureKey {
 public:
  QString current();
  void end() { key_.clear(); }
  bool active() const { return !key_.isEmpty(); }

 private:
  QString key_;
};

// A spin box for doubles whose changes carry a gesture key. Besides typing,
// the arrows and the wheel (only when focused, so scrolling the panel never
// edits), it can be scrubbed: drag sideways on the number (Shift: fine,
// Ctrl: coarse). The gesture ends on mouse release, Enter or focus loss.
class ScrubSpinBox : public QDoubleSpinBox {
  Q_OBJECT
 public:
  explicit ScrubSpinBox(QWidget* parent = nullptr);
  // Shows `v` without reporting it as an edit; leaves the text alone if it
  // already shows that value (the user may be typing it).
  void showValue(double v);
  void endGesture() { gesture_.end(); }

 signals:
  void valueEdited(double value, const QString& mergeKey);

 protected:
  bool eventFilter(QObject* watched, QEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;
  void mouseReleaseEvent(QMouseEvent* e) override;

 private:
  GestureKey gesture_;
  bool programmatic_ = false;
  bool scrubbing_ = false;
  QPoint pressPos_;
  double pressValue_ = 0.0;
  bool pressed_ = false;
};

class FieldEditor : public QWidget {
  Q_OBJECT
 public:
  // component: -1 for the whole value, 0..2 for one component of a vector
  // (so a multi-selection keeps its other components).
  using EditFn = std::function<void(const scene::FieldValue& value, int component, const QString& mergeKey)>;

  explicit FieldEditor(QWidget* parent = nullptr) : QWidget(parent) {}
  void setOnEdited(EditFn fn) { onEdited_ = std::move(fn); }
  virtual void setValue(const scene::FieldValue& value) = 0;
  // Only the asset picker needs the document's asset list.
  virtual void setAssets(const scene::SceneState&) {}
  // A text field whose values come from a list (an OpenColorIO config's
  // displays and views): a drop-down of (value, shown text) pairs instead
  // of free text; an empty list gives the free text back.
  virtual void setChoices(const std::vector<std::pair<std::string, std::string>>&) {}

 protected:
  void edited(const scene::FieldValue& value, int component, const QString& key) {
    if (onEdited_) onEdited_(value, component, key);
  }

 private:
  EditFn onEdited_;
};

struct FieldSpec {
  std::string path;  // "transform.translation"; also the widgets' object names
  scene::FieldType type = scene::FieldType::Double;
  double min = -1e300, max = 1e300, step = 0.1;
  std::string unit;
  std::vector<std::string> enumNames;
};

template <class Target>
FieldSpec specOf(const scene::FieldInfo<Target>& f, const std::string& path) {
  return FieldSpec{path, f.type, f.min, f.max, f.step, f.unit, f.enumNames};
}

FieldEditor* createFieldEditor(const FieldSpec& spec, QWidget* parent);

// Linear RGB (what the scene stores) <-> what a colour swatch shows.
QColor linearToDisplay(const glm::dvec3& linear);
glm::dvec3 displayToLinear(const QColor& c);

}  // namespace hs::app
