#pragma once
// The editor's camera-path editing: which entity's path is being edited (the
// primary selection), which of its points is selected, and every path action
// the Camera Path panel, the viewport and the timeline offer: follow a new
// path (ahead of the camera, or through its location keys), add a point at
// the viewport's view or on the curve after the selected one, delete and move
// points, aim along the path / at a point / at an entity, banking, constant
// speed timing and progress keys. Each action is one undoable edit
// (scene/camera_path_edits.h, scene::ops::setKeys); a refused one says why
// through problem().
#include <optional>

#include <QObject>
#include <QString>

#include "scene/camera_path_edits.h"

namespace hs::app {

class Selection;
class TimelineClock;

class PathEditor : public QObject {
  Q_OBJECT
 public:
  PathEditor(scene::Document& doc, TimelineClock& clock, Selection& selection, QObject* parent = nullptr);

  scene::Document& document() { return doc_; }
  // The entity whose path is edited: the primary selection (kNoEntity if none).
  scene::EntityId entity() const;
  // Its path, or nullptr.
  const sequencer::PathFollow* path() const;
  // The selected point of that path, -1 for none.
  int selectedPoint() const;
  // Selects a point of `entity`'s path, selecting the entity too (-1: no point).
  void selectPoint(scene::EntityId entity, int index);
  void selectPoint(int index) { selectPoint(entity(), index); }

  // --- a new path (replacing location and rotation keys: undo restores them)
  // From the entity's position and heading at the playhead to a point
  // `distance` metres ahead, covering the playback range at constant speed.
  bool createAhead(double distance = sequencer::kDefaultPathLength);
  // Through the entity's location keys (two or more), over their times.
  bool canCreateFromKeys() const;
  bool createFromKeys();
  bool removePath();

  // --- points (the new point becomes the selected one)
  // `point` after the selected point, else at the end (the viewport's eye
  // for "Add Point at View").
  bool addPoint(const glm::dvec3& point);
  // On the curve after the selected point (else after the last).
  bool insertPointAfter();
  bool deleteSelectedPoint();
  bool movePoint(int index, const glm::dvec3& point, const QString& mergeKey = {});

  // --- aim, banking, timing
  bool aimAlong();
  bool aimAtPoint(const glm::dvec3& point, const QString& mergeKey = {});
  bool aimAtEntity(scene::EntityId target);
  // Where "At a point" starts: the current target if one was set, else the
  // middle of the path's points.
  glm::dvec3 defaultAimPoint() const;
  bool setBanking(bool on, double maxDeg, double scale, const QString& mergeKey = {});
  // Progress keys: the playback range at constant speed (InOut: soft start and stop).
  bool setConstantSpeed(sequencer::Ease ease = sequencer::Ease::None);
  // Keys the share of the path travelled (0..1) at the playhead.
  bool keyProgress(double share, const QString& mergeKey = {});
  // The share travelled at the playhead (nullopt without progress keys).
  std::optional<double> progressNow() const;

 signals:
  // The edited entity, its path, the selected point or the playhead changed.
  void changed();
  // An action was refused: the reason, for Messages.
  void problem(const QString& text);

 private:
  bool check(bool ok, const std::string& error);
  std::pair<double, double> range() const;

  scene::Document& doc_;
  TimelineClock& clock_;
  Selection& selection_;
  scene::EntityId pointEntity_ = scene::kNoEntity;
  int point_ = -1;
};

}  // namespace hs::app
