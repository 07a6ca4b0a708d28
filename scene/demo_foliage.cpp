#include "scene/demo_foliage.h"

#include "foliage/tools.h"
#include "scene/foliage_ground.h"
#include "scene/foliage_ops.h"
#include "scene/mesh_materials.h"
#include "scene/world_bounds.h"

namespace hs::scene {

// Sizes kept modest (a few thousand triangles at full resolution) so the
// demo renders quickly on a CPU rasteriser with LODs off (the goldens):
// fewer branches, so each leaf card stands for a spray of needles or a
// cluster of leaves (bigger cards), or the crowns look bare from afar.
std::vector<DemoPlant> demoPlants() {
  foliage::PlantParams pine = foliage::defaultPlant(foliage::PlantKind::Conifer, 11);
  pine.height = 11.0;
  pine.branches = 20;
  pine.leavesPerBranch = 8;
  pine.leafSize = 0.9;
  pine.sides = 6;
  foliage::PlantParams plane = foliage::defaultPlant(foliage::PlantKind::Broadleaf, 23);
  plane.height = 9.0;
  plane.branches = 14;
  plane.leavesPerBranch = 8;
  plane.leafSize = 0.75;
  plane.sides = 6;
  foliage::PlantParams juniper = foliage::defaultPlant(foliage::PlantKind::Shrub, 5);
  juniper.height = 1.6;
  foliage::PlantParams boulder = foliage::defaultPlant(foliage::PlantKind::Rock, 9);
  boulder.height = 1.4;
  // Clumps of 16 blades (128 triangles), and a low shrub for the scan.
  foliage::PlantParams grass = foliage::defaultPlant(foliage::PlantKind::Grass, 31);
  grass.height = 0.5;
  grass.branches = 16;
  foliage::PlantParams heather = foliage::defaultPlant(foliage::PlantKind::Shrub, 17);
  heather.height = 0.45;
  heather.branches = 5;
  heather.leavesPerBranch = 4;
  heather.leafSize = 0.06;
  return {{"Black Pine", pine}, {"Plane Tree", plane}, {"Juniper", juniper},
          {"Boulder", boulder},   {"Grass Clump", grass}, {"Heather", heather}};
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
  // Grass on the valley floor, drawn near the camera only.
  foliage::FoliageType grass = pines;
  grass.name = "Grass";
  grass.mesh = "Grass Clump";
  grass.densityPerHa = 1200.0;
  grass.spacing = 0.8;
  grass.scale = {0.7, 1.3};
  grass.slopeDeg = {0.0, 25.0};
  grass.altitude = {-100.0, 6.0};
  grass.alignToNormal = true;
  grass.alignMaxDeg = 20.0;
  grass.cullDistance = 45.0;
  grass.fadeLength = 15.0;
  grass.castShadows = false;
  grass.windResponse = 1.0;
  return {pines, planes, shrubs, boulders, grass};
}

// Heather on the big scan's back and flanks (a mesh surface, at its own
// slope), scattered after the clearing was emptied: the scan stands in it.
foliage::FoliageType heatherOnTheScan() {
  foliage::FoliageType t;
  t.name = "Heather (on the scan)";
  t.mesh = "Heather";
  t.densityPerHa = 150000.0;  // 15 a square metre where it may grow, thinned by the spacing
  t.spacing = 0.2;
  t.scale = {0.6, 1.2};
  t.slopeDeg = {0.0, 60.0};
  t.surface = foliage::SurfaceFilter::Meshes;
  t.alignToNormal = true;
  t.alignMaxDeg = 30.0;
  t.cullDistance = 150.0;
  t.fadeLength = 30.0;
  t.windResponse = 0.3;
  return t;
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
  // The clearing (bunnies, lights, glass, the detail samples) stays open
  // but for the grass, which grows round what stands there and not under
  // it (through the pond, the slabs, the glass).
  foliage::TypeSet tall;
  for (uint16_t t : all)
    if (store.type(t).name != "Grass") tall.push_back(t);
  foliage::erase(store, foliage::Region2::rect({-30.0, -40.0}, {30.0, 24.0}), tall);
  for (const auto& [id, e] : s.entities)
    if (e.mesh) {
      const WorldBox box = worldBounds(s, {id});
      if (!box.empty) foliage::erase(store, foliage::Region2::rect(glm::dvec2(box.min) - 0.3, glm::dvec2(box.max) + 0.3));
    }
  // The big scan (the only mesh this scatter stands on: a ground of its
  // triangles alone, with the terrain to keep its buried foot bare).
  if (const EntityId scan = s.findByName("Stanford Bunny"); scan != kNoEntity) {
    const Entity* e = s.find(scan);
    const MeshAsset* a = e && e->mesh ? s.findAsset(e->mesh->mesh) : nullptr;
    if (a && a->data) {
      const mesh::MeshData world = worldMesh(*a->data, s.worldMatrix(scan));
      const foliage::MeshGround scanGround(world);
      foliage::Ground g = ground.ground();
      g.meshes = {&scanGround};
      const int t = store.addType(heatherOnTheScan(), messages);
      if (t < 0) {
        error = "demo foliage: " + messages.back();
        return false;
      }
      const WorldBox box = worldBounds(s, {scan});
      foliage::scatter(store, g, {uint16_t(t)}, 2026, foliage::Region2::rect(glm::dvec2(box.min), glm::dvec2(box.max)));
    }
  }
  store.markSaved();
  data.touch();
  return true;
}

}  // namespace hs::scene
