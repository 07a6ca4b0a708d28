#pragma once
// The Camera Path dock: the selected camera's path, like Blender's Follow
// Path constraint and Unreal's camera rig rail in one place. Without a path:
// Follow Path (from the camera ahead along its view) or From Location Keys.
// With one: its points (a list; the selected one is the viewport's selected
// point), Add at View / Insert After / Delete, the selected point's
// position, the aim (along the path, at a point, at an entity from a list),
// banking with its limit and strength, the timing (constant speed over the
// range, eased, and the progress keyed at the playhead) and Remove Path.
// Everything goes through PathEditor: one undoable edit each.
#include <functional>

#include <QWidget>

#include <glm/glm.hpp>

class QCheckBox;
class QComboBox;
class QLabel;
class QListWidget;
class QPushButton;

namespace hs::app {

class FieldEditor;
class PathEditor;

class CameraPathPanel : public QWidget {
  Q_OBJECT
 public:
  // `viewEye`: where the viewport looks from (for Add at View).
  CameraPathPanel(PathEditor& editor, std::function<glm::dvec3()> viewEye, QWidget* parent = nullptr);

  PathEditor& editor() { return editor_; }
  QListWidget* pointList() const { return points_; }

 private:
  void refresh();
  void refillTargets();
  void chooseAim(int index);

  PathEditor& editor_;
  std::function<glm::dvec3()> viewEye_;
  QLabel* header_ = nullptr;
  QWidget* createBox_ = nullptr;
  QWidget* editBox_ = nullptr;
  QPushButton* fromKeys_ = nullptr;
  QListWidget* points_ = nullptr;
  QPushButton* delete_ = nullptr;
  FieldEditor* point_ = nullptr;
  QComboBox* aim_ = nullptr;
  FieldEditor* targetPoint_ = nullptr;
  QComboBox* targetEntity_ = nullptr;
  QCheckBox* bank_ = nullptr;
  FieldEditor* bankMax_ = nullptr;
  FieldEditor* bankScale_ = nullptr;
  FieldEditor* progress_ = nullptr;
  QLabel* info_ = nullptr;
};

}  // namespace hs::app
