#pragma once
// The rows of the timeline: one per animated entity, material (under its
// name) and the settings ("Settings") (its keys summarised),
// and under it, unless collapsed, one per track ("Location", "Rotation",
// "Interaxial", "Path progress"), in the order the sequence holds them.
#include <set>
#include <string>
#include <vector>

#include <QString>

#include "scene/scene_state.h"
#include "sequencer/key_edit.h"

namespace hs::app {

struct TimelineRow {
  scene::EntityId entity = scene::kNoEntity;
  std::string property;  // "" for the entity's own (summary) row
  QString label;
  bool isEntity() const { return property.empty(); }
};

std::vector<TimelineRow> timelineRows(const scene::SceneState& state, const std::set<scene::EntityId>& collapsed);
// "camera.interaxial_m" -> "Interaxial", "transform.rotation" -> "Rotation",
// "path.progress" -> "Path progress".
QString propertyLabel(const std::string& property);
// The keys a row shows: a track's keys, or every key of the entity.
std::vector<sequencer::KeyRef> rowKeys(const sequencer::Sequence& sequence, const TimelineRow& row);

}  // namespace hs::app
