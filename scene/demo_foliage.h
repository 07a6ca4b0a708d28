#pragma once
// The demo scene's foliage (docs/foliage.md): four generated plants (a
// black pine, a plane tree, a juniper shrub, a boulder) with their LOD
// chains, and four foliage types scattered by rule over the demo valley
// with competition (trees first, shrubs keep room around the trunks): pines
// on the slopes and pillar ledges, plane trees on the low floor, shrubs
// wherever it is not too steep, boulders tilted to the ground. The clearing
// where the bunnies and the samples stand is kept free. Deterministic (fixed
// seeds), made in about a second.
#include <string>
#include <vector>

#include "foliage/plants.h"
#include "scene/scene_state.h"

namespace hs::scene {

// The demo's plants: asset name and generator parameters (black pine, plane
// tree, juniper, boulder; a few thousand triangles each at full detail, so
// the demo renders quickly on a CPU rasteriser). bench_foliage_render draws
// the first two.
struct DemoPlant {
  const char* asset;
  foliage::PlantParams params;
};
std::vector<DemoPlant> demoPlants();

// Adds the plants' assets and materials and the scattered foliage to `s`,
// which must have its terrain already (scene/demo_terrain.h).
bool addDemoFoliage(SceneState& s, std::string& error);

}  // namespace hs::scene
