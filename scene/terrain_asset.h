#pragma once
// A terrain held by the document: its small values (name, materials, paint
// rules), which edits change through ScenePatch like any other value, and a
// shared pointer to its tiles (TerrainData), which they do not copy.
//
// An entity shows it through a TerrainInstance component (components.h).
// World placement: sample (i, j) of the heightfield sits at
//   entity world translation + heightfield origin + (i dx, j dy, h(i, j)),
// in double; the entity's rotation and scale are ignored (see components.h).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/ids.h"
#include "scene/terrain_data.h"
#include "terrain/paint_layers.h"
#include "terrain/paint_rules.h"

namespace hs::scene {

struct SceneState;

struct TerrainAsset {
  TerrainId id = kNoTerrain;
  std::string name;
  std::shared_ptr<TerrainData> data;
  // The paint layers' materials (albedo, normal map, roughness, tiling):
  // what the renderer shades with. The weights live in the data; the number
  // of layers is fixed when the terrain is made (8 by default, at most 16).
  std::vector<terrain::Material> materials;
  // What "Apply Paint Rules" runs (editor, `terrain paint-rules`).
  std::vector<terrain::PaintRule> paintRules;

  // Values equal and the same tiles (by identity: tile content is undone by
  // terrain commands, not by patches).
  bool operator==(const TerrainAsset& o) const {
    return id == o.id && name == o.name && data == o.data && materials == o.materials && paintRules == o.paintRules;
  }
};

// The Meteora palette's default rules: sandstone on steep ground, scree at
// the foot of the slopes, grass on gentle low ground, snow high up.
std::vector<terrain::PaintRule> defaultPaintRules(const terrain::Heightfield& hf);

// World position of the terrain's sample (0, 0) at height 0 as shown by
// `entity`: entity world translation + heightfield origin (double).
glm::dvec3 terrainWorldOrigin(const SceneState& state, EntityId entity);

// The terrain an entity shows, if it has a terrain component and the terrain exists.
const TerrainAsset* terrainOf(const SceneState& state, EntityId entity);

// Entities showing a terrain, in depth-first order; with `visibleOnly`, only
// those effectively visible.
std::vector<EntityId> terrainEntities(const SceneState& state, bool visibleOnly);

}  // namespace hs::scene
