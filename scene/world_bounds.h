#pragma once
// World-space bounding boxes of entities, in double precision: for framing
// the view (Frame Selected, a CLI render with no camera) and for `info`.
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene_state.h"

namespace hs::scene {

struct WorldBox {
  glm::dvec3 min{0.0}, max{0.0};
  bool empty = true;
  void extend(const glm::dvec3& p);
  glm::dvec3 centre() const { return (min + max) * 0.5; }
  glm::dvec3 size() const { return empty ? glm::dvec3(0.0) : max - min; }
};

// Box around the given entities and their subtrees: mesh bounds through the
// world transform, a point for entities without geometry. Empty `ids`: the
// whole scene (visible entities only).
WorldBox worldBounds(const SceneState& state, const std::vector<EntityId>& ids = {});

}  // namespace hs::scene
