#include "app/path_editor.h"

#include <algorithm>

#include "app/selection.h"
#include "app/timeline_clock.h"
#include "scene/sequence_edits.h"
#include "sequencer/key_edit.h"

namespace hs::app {

PathEditor::PathEditor(scene::Document& doc, TimelineClock& clock, Selection& selection, QObject* parent)
    : QObject(parent), doc_(doc), clock_(clock), selection_(selection) {
  connect(&selection_, &Selection::changed, this, &PathEditor::changed);
  connect(&doc_, &scene::Document::changed, this, [this](const scene::ChangeSet& c) {
    if (c.sequence || c.reset || c.hierarchy) emit changed();
  });
  connect(&clock_, &TimelineClock::frameChanged, this, &PathEditor::changed);
}

scene::EntityId PathEditor::entity() const {
  const scene::EntityId id = selection_.primary();
  return doc_.state().find(id) ? id : scene::kNoEntity;
}

const sequencer::PathFollow* PathEditor::path() const { return scene::findPath(doc_.state(), entity()); }

int PathEditor::selectedPoint() const {
  // The choice belongs to one entity's path; an undo that took the point
  // away (or a change of selection) leaves none selected.
  const sequencer::PathFollow* p = path();
  if (!p || pointEntity_ != entity() || point_ < 0 || size_t(point_) >= p->path.points.size()) return -1;
  return point_;
}

void PathEditor::selectPoint(scene::EntityId id, int index) {
  if (id != scene::kNoEntity && selection_.primary() != id) selection_.select(id);
  if (pointEntity_ == id && point_ == index) return;
  pointEntity_ = id;
  point_ = index;
  emit changed();
}

bool PathEditor::check(bool ok, const std::string& error) {
  if (!ok && !error.empty()) emit problem("Camera path: " + QString::fromStdString(error));
  return ok;
}

std::pair<double, double> PathEditor::range() const {
  auto [t0, t1] = scene::playbackTimes(doc_.state().sequence);
  if (!(t1 > t0)) t1 = t0 + 1.0;  // a one-frame range: one second to travel
  return {t0, t1};
}

bool PathEditor::createAhead(double distance) {
  const scene::EntityId id = entity();
  const scene::Entity* shown = clock_.state().find(id);
  if (!shown) return check(false, "select a camera to give it a path");
  // Its pose at the playhead (animated), so the flight starts where the
  // camera is seen, looking where it looks (cameras look down local -Z).
  const glm::dmat4 world = clock_.state().worldMatrix(id);
  const glm::dvec3 from(world[3]);
  glm::dvec3 forward = -glm::dvec3(world[2]);
  forward = glm::length(forward) > 0.0 ? glm::normalize(forward) : glm::dvec3(0.0, 1.0, 0.0);
  const auto [t0, t1] = range();
  std::string error;
  const bool ok = scene::ops::setPath(doc_, id, sequencer::makePathFollow({from, from + forward * distance}, t0, t1),
                                      "Follow path", &error);
  if (ok) selectPoint(id, 1);
  return check(ok, error);
}

bool PathEditor::canCreateFromKeys() const {
  return scene::locationKeyPoints(doc_.state(), entity()).points.size() >= 2;
}

bool PathEditor::createFromKeys() {
  const scene::EntityId id = entity();
  const scene::LocationKeyPoints keys = scene::locationKeyPoints(doc_.state(), id);
  if (keys.points.size() < 2) return check(false, "the selection needs two or more location keys to make a path from");
  auto [t0, t1] = range();
  if (keys.last > keys.first) t0 = keys.first, t1 = keys.last;
  std::string error;
  const bool ok = scene::ops::setPath(doc_, id, sequencer::makePathFollow(keys.points, t0, t1),
                                      "Follow path from location keys", &error);
  if (ok) selectPoint(id, -1);
  return check(ok, error);
}

bool PathEditor::removePath() {
  std::string error;
  return check(scene::ops::removePath(doc_, entity(), &error), error);
}

bool PathEditor::addPoint(const glm::dvec3& point) {
  const sequencer::PathFollow* p = path();
  if (!p) return check(false, "the selection follows no path");
  const int sel = selectedPoint();
  const size_t at = sel >= 0 ? size_t(sel) + 1 : p->path.points.size();
  std::string error;
  const bool ok = scene::ops::insertPathPoint(doc_, entity(), at, point, &error);
  if (ok) selectPoint(int(at));
  return check(ok, error);
}

bool PathEditor::insertPointAfter() {
  const sequencer::PathFollow* p = path();
  if (!p) return check(false, "the selection follows no path");
  const int sel = selectedPoint();
  const size_t after = sel >= 0 ? size_t(sel) : p->path.points.size() - 1;
  std::string error;
  const bool ok = scene::ops::insertPathPoint(doc_, entity(), after + 1, sequencer::pointAfter(p->path, after), &error);
  if (ok) selectPoint(int(after + 1));
  return check(ok, error);
}

bool PathEditor::deleteSelectedPoint() {
  const int sel = selectedPoint();
  if (sel < 0) return check(false, "select a point of the path to delete");
  std::string error;
  const bool ok = scene::ops::removePathPoint(doc_, entity(), size_t(sel), &error);
  // The point before it stays selected, so repeated deletes walk back.
  if (ok) selectPoint(std::max(sel - 1, 0));
  return check(ok, error);
}

bool PathEditor::movePoint(int index, const glm::dvec3& point, const QString& mergeKey) {
  if (index < 0) return false;
  std::string error;
  return check(scene::ops::movePathPoint(doc_, entity(), size_t(index), point, mergeKey, &error), error);
}

bool PathEditor::aimAlong() {
  std::string error;
  return check(scene::ops::editPath(doc_, entity(), "Path: look along",
                                    [](sequencer::PathFollow& f) { f.aim = sequencer::PathAim::Tangent; }, {}, &error),
               error);
}

bool PathEditor::aimAtPoint(const glm::dvec3& point, const QString& mergeKey) {
  std::string error;
  return check(scene::ops::editPath(doc_, entity(), "Path: look at point",
                                    [&](sequencer::PathFollow& f) {
                                      f.aim = sequencer::PathAim::Point;
                                      f.targetPoint = point;
                                    },
                                    mergeKey, &error),
               error);
}

bool PathEditor::aimAtEntity(scene::EntityId target) {
  std::string error;
  return check(scene::ops::editPath(doc_, entity(), "Path: look at entity",
                                    [&](sequencer::PathFollow& f) {
                                      f.aim = sequencer::PathAim::Entity;
                                      f.targetEntity = target;
                                    },
                                    {}, &error),
               error);
}

glm::dvec3 PathEditor::defaultAimPoint() const {
  const sequencer::PathFollow* p = path();
  if (!p || p->path.points.empty()) return glm::dvec3(0.0);
  if (p->targetPoint != glm::dvec3(0.0)) return p->targetPoint;
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& x : p->path.points) sum += x;
  return sum / double(p->path.points.size());
}

bool PathEditor::setBanking(bool on, double maxDeg, double scale, const QString& mergeKey) {
  std::string error;
  return check(scene::ops::editPath(doc_, entity(), on ? "Path: banking" : "Path: no banking",
                                    [&](sequencer::PathFollow& f) {
                                      f.bank = on;
                                      f.maxBankDeg = maxDeg;
                                      f.bankScale = scale;
                                    },
                                    mergeKey, &error),
               error);
}

bool PathEditor::setConstantSpeed(sequencer::Ease ease) {
  const auto [t0, t1] = range();
  std::string error;
  return check(scene::ops::setPathTiming(doc_, entity(), t0, t1, ease, &error), error);
}

bool PathEditor::keyProgress(double share, const QString& mergeKey) {
  if (!path()) return check(false, "the selection follows no path");
  std::string error;
  const scene::AnimTarget target{sequencer::kPathProgress, scene::TrackKind::Scalar};
  // Linear: between keys the camera keeps a constant speed; eases from the
  // timeline's key menu soften it where wanted.
  return check(scene::ops::setKeys(doc_, {{entity(), target, sequencer::PropertyValue(share)}}, clock_.time(),
                                   sequencer::Interpolation::Linear, "Key path progress", mergeKey, &error),
               error);
}

std::optional<double> PathEditor::progressNow() const {
  const sequencer::PathFollow* p = path();
  if (!p) return std::nullopt;
  return sequencer::evaluate(p->progress, clock_.time());
}

}  // namespace hs::app
