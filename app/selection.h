#pragma once
// The selected entities, shared by the viewport, the outliner and the
// property panel. Holds ids (stable across undo), in selection order; the
// last one is the primary (what the property panel shows, the local-space
// gizmo's frame).
#include <vector>

#include <QObject>

#include "scene/ids.h"

namespace hs::scene {
struct SceneState;
}

namespace hs::app {

class Selection : public QObject {
  Q_OBJECT
 public:
  using EntityId = scene::EntityId;
  explicit Selection(QObject* parent = nullptr) : QObject(parent) {}

  const std::vector<EntityId>& ids() const { return ids_; }
  EntityId primary() const { return ids_.empty() ? scene::kNoEntity : ids_.back(); }
  bool contains(EntityId id) const;
  bool empty() const { return ids_.empty(); }
  size_t size() const { return ids_.size(); }

  void set(std::vector<EntityId> ids);  // the last becomes primary
  void select(EntityId id);             // only this one (kNoEntity: none)
  void add(EntityId id);                // makes it primary
  void toggle(EntityId id);
  void clear() { set({}); }
  // Drops ids that left the document (after delete, undo of an import, open).
  void prune(const scene::SceneState& state);

 signals:
  void changed();

 private:
  std::vector<EntityId> ids_;
};

}  // namespace hs::app
