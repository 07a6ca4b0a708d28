#include "scene/terrain_asset.h"

#include <algorithm>

#include "scene/scene_state.h"

namespace hs::scene {

std::vector<terrain::PaintRule> defaultPaintRules(const terrain::Heightfield& hf) {
  // Layers of terrain::defaultMaterials(): 0 soil, 1 grass, 2 sandstone,
  // 3 conglomerate, 4 scree, 5 forest floor, 6 riverbed, 7 snow.
  const terrain::HeightRange r = hf.range();
  const double base = hf.origin().z, lo = double(r.min), hi = double(r.max), span = std::max(1.0, hi - lo);
  std::vector<terrain::PaintRule> rules;
  terrain::PaintRule grass;
  grass.layer = 1;
  grass.useSlope = true;
  grass.slopeMin = 0.0;
  grass.slopeMax = 18.0;
  grass.slopeBlend = 6.0;
  grass.useAltitude = true;
  grass.altitudeMin = base + lo - 1.0;
  grass.altitudeMax = base + lo + 0.55 * span;
  grass.altitudeBlend = 0.1 * span;
  grass.strength = 0.9f;
  rules.push_back(grass);
  terrain::PaintRule scree;
  scree.layer = 4;
  scree.useSlope = true;
  scree.slopeMin = 22.0;
  scree.slopeMax = 38.0;
  scree.slopeBlend = 5.0;
  scree.strength = 0.8f;
  rules.push_back(scree);
  terrain::PaintRule rock;
  rock.layer = 2;
  rock.useSlope = true;
  rock.slopeMin = 38.0;
  rock.slopeMax = 90.0;
  rock.slopeBlend = 6.0;
  rules.push_back(rock);
  terrain::PaintRule snow;
  snow.layer = 7;
  snow.useAltitude = true;
  // Snow by altitude above sea level (a small terrain near 0 m gets none;
  // the Meteora peaks behind the pillars reach 2000 m).
  snow.altitudeMin = std::max(1800.0, base + lo + 0.85 * span);
  snow.altitudeMax = std::max(snow.altitudeMin + 1.0, base + hi + 1.0);
  snow.altitudeBlend = 50.0;
  snow.useSlope = true;
  snow.slopeMin = 0.0;
  snow.slopeMax = 40.0;
  snow.strength = 0.9f;
  rules.push_back(snow);
  return rules;
}

glm::dvec3 terrainWorldOrigin(const SceneState& state, EntityId entity) {
  const TerrainAsset* t = terrainOf(state, entity);
  const glm::dvec3 translation(state.worldMatrix(entity)[3]);
  return translation + (t && t->data ? t->data->heights().origin() : glm::dvec3(0.0));
}

const TerrainAsset* terrainOf(const SceneState& state, EntityId entity) {
  const Entity* e = state.find(entity);
  if (!e || !e->terrain) return nullptr;
  const TerrainAsset* t = state.findTerrain(e->terrain->terrain);
  return t && t->data ? t : nullptr;
}

std::vector<EntityId> terrainEntities(const SceneState& state, bool visibleOnly) {
  std::vector<EntityId> out;
  for (EntityId id : state.depthFirstOrder()) {
    if (!terrainOf(state, id)) continue;
    if (visibleOnly && !state.effectivelyVisible(id)) continue;
    out.push_back(id);
  }
  return out;
}

}  // namespace hs::scene
