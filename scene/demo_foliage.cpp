#include "scene/demo_foliage.h"

#include "foliage/tools.h"
#include "scene/foliage_ground.h"
#include "scene/foliage_ops.h"
#include "scene/mesh_materials.h"

namespace hs::scene {

// Sizes kept modest (a few thousand triangles at full resolution) so the
// demo renders quickly on a CPU rasteriser with LODs off (the goldens).
std::vector<DemoPlant> demoPlants() {
  foliage::PlantParams pine = foliage::defaultPlant(foliage::PlantKind::Conifer, 11);
  pine.height = 11.0;
  pine.branches = 20;
  pine.leavesPerBranch = 8;
  pine.sides = 6;
  foliage::PlantParams plane = foliage::defaultPlant(foliage::PlantKind::Broadleaf, 23);
  plane.height = 9.0;
  plane.branches = 14;
  plane.leavesPerBranch = 8;
  plane.sides = 6;
  foliage::PlantParams juniper = foliage::defaultPlant(foliage::PlantKind::Shrub, 5);
  juniper.height = 1.6;
  foliage::PlantParams boulder = foliage::defaultPlant(foliage::PlantKind::Rock, 9);
  boulder.height = 1.4;
  return {{"Black Pine", pine}, {"Plane Tree", plane}, {"Juniper", juniper}, {"Boulder", boulder}};
}

namespace {

std::vector<foliage::FoliageType> types() {
  foliage::FoliageType pines;
  pines.name = "Pines";
  pines.mesh = "Black Pine";
  pines.densityPerHa = 45.0;
  pines.spacing = 6.0;
  pines.scale = {0.7, 1.3};
  pines.slopeDeg = {0.0, 38.0};
  pines.surface = foliage::SurfaceFilter::Terrain;
  pines.cullDistance = 700.0;
  pines.fadeLength = 80.0;
  foliage::FoliageType planes = pines;
  planes.name = "Plane trees";
  planes.mesh = "Plane Tree";
  planes.densityPerHa = 18.0;
  planes.spacing = 9.0;
  planes.slopeDeg = {0.0, 15.0};
  planes.altitude = {-100.0, 6.0};  // the valley floor
  planes.scaleMode = foliage::ScaleMode::XyZ;
  planes.scale = {0.8, 1.3};
  planes.scaleZ = {0.8, 1.1};
  foliage::FoliageType shrubs = pines;
  shrubs.name = "Junipers";
  shrubs.mesh = "Juniper";
  shrubs.densityPerHa = 90.0;
  shrubs.spacing = 2.5;
  shrubs.slopeDeg = {0.0, 45.0};
  shrubs.cullDistance = 300.0;
  shrubs.fadeLength = 50.0;
  shrubs.windResponse = 0.5;
  foliage::FoliageType boulders = pines;
  boulders.name = "Boulders";
  boulders.mesh = "Boulder";
  boulders.densityPerHa = 30.0;
  boulders.spacing = 3.0;
  boulders.scale = {0.4, 1.6};
  boulders.slopeDeg = {0.0, 60.0};
  boulders.alignToNormal = true;
  boulders.alignMaxDeg = 40.0;
  boulders.randomPitchDeg = 15.0;
  boulders.sinkDepth = 0.15;
  boulders.cullDistance = 250.0;
  boulders.fadeLength = 40.0;
  boulders.windResponse = 0.0;
  return {pines, planes, shrubs, boulders};
}

}  // namespace

bool addDemoFoliage(SceneState& s, std::string& error) {
  for (const DemoPlant& p : demoPlants()) {
    std::optional<MeshAsset> a = ops::makePlantAsset(p.asset, p.params, error);
    if (!a) return false;
    a->id = s.maxAssetId() + 1;
    const AssetId id = a->id;
    s.assets.emplace(id, std::move(*a));
    addMeshMaterials(s, id);
    for (MaterialId m : s.assets.at(id).materialSlots) ops::applyPlantLook(s.materials.at(m));
  }
  FoliageData& data = foliageOf(s);
  foliage::FoliageStore& store = data.store();
  std::vector<std::string> messages;
  for (const foliage::FoliageType& t : types())
    if (store.addType(t, messages) < 0) {
      error = "demo foliage: " + messages.back();
      return false;
    }
  const FoliageGround ground(s, false);  // the terrain (the bunnies and samples are no ground)
  foliage::TypeSet all;
  for (size_t t = 0; t < store.types().size(); ++t) all.push_back(uint16_t(t));
  foliage::scatter(store, ground.ground(), all, 2026, std::nullopt, 0, true);
  // The clearing (bunnies, lights, glass, the detail samples) stays open.
  foliage::erase(store, foliage::Region2::rect({-30.0, -40.0}, {30.0, 24.0}));
  store.markSaved();
  data.touch();
  return true;
}

}  // namespace hs::scene
