#include "scene/camera_path_edits.h"

#include <algorithm>
#include <cmath>

#include "scene/edit.h"
#include "sequencer/key_edit.h"

namespace hs::scene {

namespace {

bool refuse(std::string* error, const std::string& why) {
  if (error) *error = why;
  return false;
}

std::string nameOf(const SceneState& s, EntityId id) {
  const Entity* e = s.find(id);
  return e ? "'" + e->name + "'" : "#" + std::to_string(id);
}

}  // namespace

const sequencer::PathFollow* findPath(const SceneState& state, EntityId id) {
  const sequencer::Binding* b = state.sequence.findBinding(id);
  return b && b->path ? &*b->path : nullptr;
}

std::pair<double, double> playbackTimes(const sequencer::Sequence& s) {
  return {sequencer::frameTime(s.startFrame, s.rate), sequencer::frameTime(s.endFrame, s.rate)};
}

LocationKeyPoints locationKeyPoints(const SceneState& state, EntityId id) {
  LocationKeyPoints out;
  const Entity* e = state.find(id);
  const sequencer::Binding* b = state.sequence.findBinding(id);
  if (!e || !b) return out;
  const glm::dmat4 parent = e->parent == kNoEntity ? glm::dmat4(1.0) : state.worldMatrix(e->parent);
  for (const sequencer::Track& t : b->tracks) {
    const auto* v = std::get_if<sequencer::VectorTrack>(&t);
    if (!v || v->property != "transform.translation" || v->keys.empty()) continue;
    // A stored track may be unsorted (the compiler sorts its copy): the
    // path runs through the keys in time order.
    std::vector<sequencer::VectorKey> keys = v->keys;
    std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& c) { return a.time < c.time; });
    for (const sequencer::VectorKey& k : keys) out.points.push_back(glm::dvec3(parent * glm::dvec4(k.value, 1.0)));
    out.first = keys.front().time;
    out.last = keys.back().time;
  }
  return out;
}

std::optional<std::string> pathProblem(const SceneState& state, EntityId id, const sequencer::PathFollow& f) {
  if (auto p = sequencer::pathProblem(f)) return p;
  if (f.aim == sequencer::PathAim::Entity) {
    if (f.targetEntity == id) return "an entity cannot look at itself";
    if (!state.find(f.targetEntity)) return "no entity #" + std::to_string(f.targetEntity) + " to look at";
  }
  return std::nullopt;
}

namespace ops {

bool setPath(Document& doc, EntityId id, sequencer::PathFollow follow, const QString& text, std::string* error) {
  const Entity* entity = doc.state().find(id);
  if (!entity) return refuse(error, "no entity #" + std::to_string(id));
  if (auto p = pathProblem(doc.state(), id, follow)) return refuse(error, nameOf(doc.state(), id) + ": " + *p);
  Edit e(doc, text);
  sequencer::Sequence& seq = e.sequence();
  sequencer::Binding* b = seq.findBinding(id);
  if (!b) {
    seq.bindings.push_back(sequencer::Binding{id, entity->name, {}, std::nullopt});
    b = &seq.bindings.back();
  }
  b->label = entity->name;
  std::erase_if(b->tracks, [](const sequencer::Track& t) {
    const std::string& p = sequencer::trackProperty(t);
    return p == "transform.translation" || p == "transform.rotation";
  });
  b->path = std::move(follow);
  return e.commit();
}

bool editPath(Document& doc, EntityId id, const QString& text,
              const std::function<void(sequencer::PathFollow&)>& change, const QString& mergeKey,
              std::string* error) {
  const sequencer::PathFollow* current = findPath(doc.state(), id);
  if (!current) return refuse(error, nameOf(doc.state(), id) + " follows no path");
  sequencer::PathFollow next = *current;
  change(next);
  if (auto p = pathProblem(doc.state(), id, next)) return refuse(error, nameOf(doc.state(), id) + ": " + *p);
  if (next == *current) return false;
  Edit e(doc, text, mergeKey);
  e.sequence().findBinding(id)->path = std::move(next);
  return e.commit();
}

bool removePath(Document& doc, EntityId id, std::string* error) {
  if (!findPath(doc.state(), id)) return refuse(error, nameOf(doc.state(), id) + " follows no path");
  Edit e(doc, "Remove path");
  sequencer::Sequence& seq = e.sequence();
  sequencer::Binding* b = seq.findBinding(id);
  b->path.reset();
  if (b->tracks.empty())
    std::erase_if(seq.bindings, [id](const sequencer::Binding& x) { return x.entity == id; });
  return e.commit();
}

bool insertPathPoint(Document& doc, EntityId id, size_t index, const glm::dvec3& point, std::string* error) {
  const sequencer::PathFollow* f = findPath(doc.state(), id);
  if (f && index > f->path.points.size())
    return refuse(error, "no point " + std::to_string(index + 1) + " to insert before (the path has " +
                             std::to_string(f->path.points.size()) + ")");
  return editPath(
      doc, id, "Add path point",
      [&](sequencer::PathFollow& p) { p.path.points.insert(p.path.points.begin() + std::ptrdiff_t(index), point); }, {},
      error);
}

bool removePathPoint(Document& doc, EntityId id, size_t index, std::string* error) {
  const sequencer::PathFollow* f = findPath(doc.state(), id);
  if (f && index >= f->path.points.size())
    return refuse(error, "no point " + std::to_string(index + 1) + " (the path has " +
                             std::to_string(f->path.points.size()) + ")");
  if (f && f->path.points.size() <= 2)
    return refuse(error, "a path needs at least two points: remove the path instead");
  return editPath(
      doc, id, "Delete path point",
      [&](sequencer::PathFollow& p) { p.path.points.erase(p.path.points.begin() + std::ptrdiff_t(index)); }, {},
      error);
}

bool movePathPoint(Document& doc, EntityId id, size_t index, const glm::dvec3& point, const QString& mergeKey,
                   std::string* error) {
  const sequencer::PathFollow* f = findPath(doc.state(), id);
  if (f && index >= f->path.points.size())
    return refuse(error, "no point " + std::to_string(index + 1) + " (the path has " +
                             std::to_string(f->path.points.size()) + ")");
  return editPath(
      doc, id, "Move path point", [&](sequencer::PathFollow& p) { p.path.points[index] = point; }, mergeKey, error);
}

bool setPathTiming(Document& doc, EntityId id, double t0, double t1, sequencer::Ease ease, std::string* error) {
  if (!std::isfinite(t0) || !std::isfinite(t1) || !(t1 > t0))
    return refuse(error, "the path's end time must be after its start time");
  return editPath(
      doc, id, "Path timing", [&](sequencer::PathFollow& p) { p.progress = sequencer::constantSpeedProgress(t0, t1, ease); },
      {}, error);
}

}  // namespace ops
}  // namespace hs::scene
