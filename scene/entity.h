#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/components.h"
#include "scene/ids.h"
#include "scene/transform.h"

namespace hs::scene {

struct Entity {
  EntityId id = kNoEntity;
  std::string name;
  EntityId parent = kNoEntity;      // kNoEntity: a root
  std::vector<EntityId> children;   // in outliner order; kept in step with `parent`
  Transform transform;              // relative to the parent
  bool visible = true;

  std::optional<MeshInstance> mesh;
  std::optional<Light> light;
  std::optional<Camera> camera;
  std::optional<TerrainInstance> terrain;
  std::optional<ParticleEmitter> particles;

  bool operator==(const Entity&) const = default;
};

}  // namespace hs::scene
