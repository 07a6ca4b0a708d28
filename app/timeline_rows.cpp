#include "app/timeline_rows.h"

#include "scene/fields.h"
#include "scene/object_tracks.h"

namespace hs::app {

QString propertyLabel(const std::string& property) {
  if (property == "transform.rotation") return "Rotation";
  if (property == sequencer::kPathProgress) return "Path progress";
  if (const scene::EntityField* f = scene::findEntityField(property)) {
    // A camera's own post setting (scene/camera_post.h) shares the scene
    // setting's label: say whose it is.
    const bool cameraPost = property.rfind("camera.post.", 0) == 0;
    return (cameraPost ? QString("Post: ") : QString()) + QString::fromStdString(f->label);
  }
  if (const scene::MaterialField* f = scene::findMaterialTrackField(property)) return QString::fromStdString(f->label);
  if (const scene::SettingsField* f = scene::findSettingsTrackField(property)) return QString::fromStdString(f->label);
  return QString::fromStdString(property);
}

std::vector<TimelineRow> timelineRows(const scene::SceneState& state, const std::set<scene::EntityId>& collapsed) {
  std::vector<TimelineRow> rows;
  for (const sequencer::Binding& b : state.sequence.bindings) {
    // An entity's name, a material's (object_tracks.h), or "Settings".
    const std::string now = scene::targetLabel(state, b.entity);
    QString name = QString::fromStdString(now.empty() ? b.label : now);
    if (now.empty()) name += " (missing)";
    rows.push_back({b.entity, {}, name});
    if (collapsed.count(b.entity)) continue;
    for (const std::string& p : sequencer::trackProperties(b)) rows.push_back({b.entity, p, propertyLabel(p)});
  }
  return rows;
}

std::vector<sequencer::KeyRef> rowKeys(const sequencer::Sequence& sequence, const TimelineRow& row) {
  std::vector<sequencer::KeyRef> out;
  const sequencer::Binding* b = sequence.findBinding(row.entity);
  if (!b) return out;
  for (const std::string& p : sequencer::trackProperties(*b)) {
    if (!row.isEntity() && p != row.property) continue;
    const size_t n = sequencer::keyTimes(sequence, row.entity, p).size();
    for (size_t i = 0; i < n; ++i) out.push_back({row.entity, p, i});
  }
  return out;
}

}  // namespace hs::app
