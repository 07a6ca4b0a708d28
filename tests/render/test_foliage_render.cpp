// The document's foliage drawn (render/foliage_sources.h): what the
// renderer is given equals the store (every record's place, rotation,
// scale, type and id, at UTM coordinates), a scattered store renders as
// the same rocks placed as ordinary mesh entities at the decoded places (an
// independent path: the mesh source), an erase shows on the next frame of
// the same renderer (the sources follow the store's revision) and a store
// of more than 65,536 cells becomes several sets, and the wind makes frame
// t the same image whether rendered alone or after the frames before it.
#include <QtTest>

#include <map>
#include <set>

#include "foliage/instance.h"
#include "foliage/tools.h"
#include "image_compare.h"
#include "look_from.h"
#include "mesh/primitives.h"
#include "render/foliage_instances.h"
#include "render/offscreen_renderer.h"
#include "scene/foliage_ground.h"
#include "scene/scene_state.h"
#include "scene_parts.h"
#include "terrain/terrain.h"

using namespace hs;

namespace {

test::Rgba8Image toTest(const Image& img) { return {img.width, img.height, img.rgba8}; }

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);
constexpr scene::AssetId kRock = 5, kGround = 1;

// A flat ground mesh entity, a sun, a rock asset and a foliage type of
// rocks (uniform and per-axis scale types) scattered on a flat plane.
scene::SceneState forest(foliage::ScaleMode mode) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.meshLodErrorPixels = 0.0;  // level 0 everywhere: the entities draw it too
  test::addMeshAsset(s, kGround, "Ground", mesh::gridPlane(60.0f, 4), {0.5f, 0.55f, 0.45f});
  test::addMeshAsset(s, kRock, "Rock", mesh::uvSphere(0.5f, 16, 12), {0.7f, 0.6f, 0.5f});
  scene::Entity ground;
  ground.id = 1;
  ground.name = "Ground";
  ground.mesh = scene::MeshInstance{kGround};
  ground.transform.translation = kUtm;
  s.entities.emplace(ground.id, ground);
  s.roots.push_back(ground.id);
  test::addSun(s, 1000, {45, 0, -30});

  foliage::FoliageStore& store = scene::foliageOf(s).store();
  foliage::FoliageType t;
  t.name = "Rocks";
  t.mesh = "Rock";
  t.densityPerHa = 600.0;
  t.spacing = 2.5;
  t.scaleMode = mode;
  t.scale = {0.6, 1.4};
  t.scaleZ = {0.5, 1.8};
  t.randomPitchDeg = 25.0;
  t.windResponse = 0.0;
  t.cullDistance = 0.0;
  t.fadeLength = 0.0;
  std::vector<std::string> messages;
  store.addType(t, messages);
  // The ground as a mesh at UTM: placed through the tools' own ground.
  const scene::FoliageGround g(s);
  foliage::scatter(store, g.ground(), {0}, 42, foliage::Region2::rect(glm::dvec2(kUtm) - 25.0, glm::dvec2(kUtm) + 25.0));
  s.foliage->touch();
  return s;
}

// The same instances as mesh entities at their decoded (stored) places,
// with the rotation and scale the GPU record holds.
scene::SceneState asEntities(const scene::SceneState& with) {
  scene::SceneState s = with;
  const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(with);
  s.foliage.reset();
  scene::EntityId id = 5000;
  for (const render::InstanceSet& set : sets)
    for (const render::GpuInstance& g : set.instances) {
      scene::Entity e;
      e.id = id++;
      e.name = "Rock " + std::to_string(g.id);
      e.mesh = scene::MeshInstance{kRock};
      e.transform.translation = set.cells[g.typeAndCell >> 16] + glm::dvec3(g.position);
      e.transform.rotation = glm::dquat(render::instanceRotation(g));
      e.transform.scale = glm::dvec3(render::instanceScale(g));
      s.entities.emplace(e.id, e);
      s.roots.push_back(e.id);
    }
  return s;
}

render::RenderView camera() {
  render::RenderView v;
  v.width = 200;
  v.height = 150;
  v.fovY = glm::radians(55.0);
  v.eye = kUtm + glm::dvec3(0.0, -30.0, 18.0);
  v.orientation = test::lookFrom(v.eye, kUtm).rotation;
  return v;
}

}  // namespace

class TestFoliageRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // Every record reaches the renderer as the store has it.
  void instanceSetsEqualTheStore() {
    for (foliage::ScaleMode mode : {foliage::ScaleMode::Uniform, foliage::ScaleMode::XyZ}) {
      const scene::SceneState s = forest(mode);
      const foliage::FoliageStore& store = s.foliage->store();
      const std::vector<foliage::Instance> all = store.allInstances();
      QVERIFY(all.size() > 50);
      const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(s);
      QCOMPARE(sets.size(), size_t(1));
      const render::InstanceSet& set = sets[0];
      QCOMPARE(set.types.size(), size_t(1));
      QCOMPARE(set.types[0].mesh, kRock);
      QCOMPARE(set.instances.size(), all.size());
      std::map<uint32_t, const foliage::Instance*> byId;
      for (const foliage::Instance& in : all) byId[in.id] = &in;
      double worstPos = 0.0, worstRot = 0.0, worstScale = 0.0;
      for (const render::GpuInstance& g : set.instances) {
        QVERIFY(byId.count(g.id));
        const foliage::Instance& in = *byId[g.id];
        const glm::dvec3 p = set.cells[g.typeAndCell >> 16] + glm::dvec3(g.position);
        worstPos = std::max(worstPos, glm::length(p - in.position));
        // The angle of the rotation between them (atan2: acos near 1 would
        // turn the float's last bit into 1e-3 rad).
        const glm::dquat d = glm::dquat(render::instanceRotation(g)) * glm::conjugate(in.rotation);
        worstRot = std::max(worstRot, 2.0 * std::atan2(glm::length(glm::dvec3(d.x, d.y, d.z)), std::abs(d.w)));
        const glm::dvec3 sc(render::instanceScale(g));
        for (int a = 0; a < 3; ++a) worstScale = std::max(worstScale, std::abs(sc[a] / in.scale[a] - 1.0));
        QCOMPARE(int(g.typeAndCell & 0xFFFFu), int(in.type));
      }
      qInfo("%zu instances: worst position %.3g m, rotation %.3g rad, scale %.3g relative", all.size(), worstPos,
            worstRot, worstScale);
      QCOMPARE(worstPos, 0.0);       // the step grid is exact in float and double
      QVERIFY(worstRot < 1e-4);      // snorm16 of the decoded quaternion
      QVERIFY(worstScale < 5e-4);    // halves: 11 significant bits
    }
  }

  // The renderer draws the store as the mesh entities at the same places.
  void drawnAsTheSameRocksAsEntities() {
    for (foliage::ScaleMode mode : {foliage::ScaleMode::Uniform, foliage::ScaleMode::XyZ}) {
      const scene::SceneState s = forest(mode);
      const scene::SceneState e = asEntities(s);
      render::FrameStats stats;
      const Image a = r_.render(s, camera(), false, &stats);
      const Image b = r_.render(e, camera());
      const Image none = [&] {
        scene::SceneState bare = s;
        bare.foliage.reset();
        return r_.render(bare, camera());
      }();
      const test::CompareResult same = test::compareImages(toTest(a), toTest(b), 2);
      const test::CompareResult differs = test::compareImages(toTest(a), toTest(none), 2);
      qInfo("foliage vs entities: %s; vs no foliage: %s", same.summary().c_str(), differs.summary().c_str());
      QVERIFY2(same.differingShare <= 0.002, same.summary().c_str());
      QVERIFY2(differs.differingShare > 0.02, differs.summary().c_str());  // the rocks are in view
    }
  }

  // An erase reaches the next frame of the same renderer.
  void anEditShowsOnTheNextFrame() {
    render::OffscreenRenderer r;
    std::string error;
    QVERIFY2(r.initialize(error), error.c_str());
    scene::SceneState s = forest(foliage::ScaleMode::Uniform);
    const Image before = r.render(s, camera());
    foliage::erase(s.foliage->store(), foliage::Region2::rect(glm::dvec2(kUtm) - 30.0, glm::dvec2(kUtm) + 30.0));
    s.foliage->touch();
    const Image after = r.render(s, camera());
    scene::SceneState bare = s;
    bare.foliage.reset();
    const Image none = r_.render(bare, camera());
    QVERIFY(test::compareImages(toTest(before), toTest(after), 2).differingShare > 0.02);
    const test::CompareResult cmp = test::compareImages(toTest(after), toTest(none), 0);
    QVERIFY2(cmp.maxChannelDiff == 0, cmp.summary().c_str());
  }

  // More cells than a GpuInstance can name: several sets, every record once.
  // Wind is a pure function of the scene time (DESIGN.md, "Time and
  // determinism"): 2 s rendered by a fresh renderer equals 2 s rendered
  // after 1.0, 1.05, ... 1.95 s by another, byte for byte; and the wind does
  // move the rocks between 1 s and 2 s (the check can fail).
  void windFrameAloneEqualsAfterItsPredecessors() {
    scene::SceneState s = forest(foliage::ScaleMode::Uniform);
    foliage::FoliageType t = s.foliage->store().type(0);
    t.windResponse = 10.0;
    s.foliage->store().setTypes({t});
    s.foliage->touch();
    auto at = [&s](double seconds) {
      scene::SceneState x = s;
      x.time.seconds = seconds;
      x.time.frame = int64_t(std::llround(seconds * 60.0));
      return x;
    };
    render::OffscreenRenderer alone, after;
    std::string error;
    QVERIFY2(alone.initialize(error) && after.initialize(error), error.c_str());
    const Image a = alone.render(at(2.0), camera());
    for (int f = 0; f < 20; ++f) after.render(at(1.0 + 0.05 * f), camera());
    const Image b = after.render(at(2.0), camera());
    QVERIFY2(a.rgba8 == b.rgba8, "frame 2 s differs after its predecessors");
    const test::CompareResult moved = test::compareImages(toTest(a), toTest(alone.render(at(1.0), camera())), 0);
    qInfo("the wind from 1 s to 2 s: %s", moved.summary().c_str());
    QVERIFY2(moved.differingShare > 0.001, "the wind moved nothing: the check above proves nothing");
  }

  void manyCellsSplitIntoSets() {
    scene::SceneState s;
    foliage::FoliageStore& store = scene::foliageOf(s).store();
    foliage::FoliageType t;
    t.name = "Grass";
    t.mesh = "Grass";
    std::vector<std::string> messages;
    store.addType(t, messages);
    const size_t cells = render::kMaxCellsPerSet + 1000;
    for (size_t i = 0; i < cells; ++i) {
      foliage::Instance in;
      in.position = kUtm + glm::dvec3(double(i % 300) * foliage::kCellSize + 1.0,
                                      double(i / 300) * foliage::kCellSize + 1.0, 0.5);
      store.add(in, nullptr);
    }
    QCOMPARE(store.cellCount(), cells);
    const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(s);
    QCOMPARE(sets.size(), size_t(2));
    QCOMPARE(sets[0].cells.size(), render::kMaxCellsPerSet);
    QCOMPARE(sets[0].instances.size() + sets[1].instances.size(), cells);
    std::set<uint32_t> ids;
    for (const auto& set : sets)
      for (const render::GpuInstance& g : set.instances) {
        QVERIFY((g.typeAndCell >> 16) < set.cells.size());
        ids.insert(g.id);
      }
    QCOMPARE(ids.size(), cells);
  }
};

QTEST_MAIN(TestFoliageRender)
#include "test_foliage_render.moc"
