// The document's foliage drawn (render/foliage_sources.h): what the
// renderer is given equals the store (every record's place, rotation,
// scale, type and id, at UTM coordinates), a scattered store renders as
// the same rocks placed as ordinary mesh entities at the decoded places (an
// independent path: the mesh source), an erase shows on the next frame of
// the same renderer (the sources follow the store's revision), an edit
// uploads only the slots of the cells it touched and draws what sources
// built afresh draw, and a store
// of more than 65,536 cells (or more instances than a source culls)
// becomes several sets, the wind makes frame t the same image whether
// rendered alone or after the frames before it, the GPU culling keeps
// exactly the instance ids a brute-force CPU frustum and cull-distance test
// keeps (read back from its lists), and both eyes of a stereo pair draw
// every instance at the mono LOD view's level.
#include <QtTest>

#include <array>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "foliage/instance.h"
#include "foliage/tools.h"
#include "image_compare.h"
#include "view_from.h"
#include "mesh/primitives.h"
#include "render/foliage_instances.h"
#include "render/foliage_sources.h"
#include "render/instanced_source.h"
#include "render/offscreen_renderer.h"
#include "scene/foliage_ground.h"
#include "scene/foliage_ops.h"
#include "scene/scene_state.h"
#include "plant_asset.h"
#include "scene_parts.h"
#include "terrain/terrain.h"

using namespace hs;

namespace {

test::Rgba8Image toTest(const Image& img) { return {img.width, img.height, img.rgba8}; }

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);
constexpr scene::AssetId kRock = 5, kGround = 1;

// The ground asset kGround as an entity at kUtm, and a sun.
void addGroundAndSun(scene::SceneState& s) {
  test::addMeshEntity(s, 1, "Ground", kGround, kUtm);
  test::addSun(s, 1000, {45, 0, -30});
}

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
  addGroundAndSun(s);

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

render::RenderView camera() { return test::viewFrom(kUtm + glm::dvec3(0.0, -30.0, 18.0), kUtm, 200, 150, 55.0); }

// A field of generated conifers (foliage/plants.h, with their LOD chain)
// on a flat ground 400 m across at UTM, cull distance 150 m with a 20 m
// fade, no wind (so the cull sphere is the bounds sphere alone).
constexpr scene::AssetId kPine = 7;
constexpr double kPineCull = 150.0;

scene::SceneState pineField() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.shadows = false;  // the camera views' lists are the question
  test::addMeshAsset(s, kGround, "Ground", mesh::gridPlane(400.0f, 4), {0.5f, 0.55f, 0.45f});
  foliage::PlantParams pine = foliage::defaultPlant(foliage::PlantKind::Conifer, 11);
  pine.height = 9.0;
  pine.branches = 12;
  pine.leavesPerBranch = 6;
  pine.sides = 5;
  test::addPlantAsset(s, kPine, "Pine", pine);
  addGroundAndSun(s);
  foliage::FoliageStore& store = scene::foliageOf(s).store();
  foliage::FoliageType t;
  t.name = "Pines";
  t.mesh = "Pine";
  t.densityPerHa = 250.0;
  t.spacing = 3.0;
  t.scaleMode = foliage::ScaleMode::XyZ;
  t.scale = {0.6, 1.4};
  t.scaleZ = {0.7, 1.3};
  t.randomPitchDeg = 10.0;
  t.windResponse = 0.0;
  t.cullDistance = kPineCull;
  t.fadeLength = 20.0;
  std::vector<std::string> messages;
  store.addType(t, messages);
  const scene::FoliageGround g(s);
  foliage::scatter(store, g.ground(), {0}, 7, foliage::Region2::rect(glm::dvec2(kUtm) - 190.0, glm::dvec2(kUtm) + 190.0));
  s.foliage->touch();
  return s;
}

// Low over the field, looking along it at a grazing angle: instances
// behind, beside, beyond the cull distance and in view.
render::RenderView grazing() {
  return test::viewFrom(kUtm + glm::dvec3(-20.0, -110.0, 7.0), kUtm + glm::dvec3(15.0, 0.0, 0.0), 240, 135, 50.0);
}

// The brute-force reference, written from the documented rule alone
// (render/instanced_source.h) in double: an instance is kept by a view when
// its origin is within the type's cull distance of the LOD eye and its
// sphere reaches inside all six planes of the view. The sphere: about level
// 0's box centre (mesh space, scaled, rotated, placed), with a radius that
// holds every level's box (|centre_l - centre_0| + half diagonal_l), times
// the largest |scale|. The planes come from the view's parameters here
// (fovY, aspect, off-axis shift, near, far), not from render/'s frustum.
struct Sphere {
  glm::dvec3 centre;
  double radius;
};

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  double halfDiagonal() const { return 0.5 * glm::length(hi - lo); }
};

Box boxOf(const mesh::MeshData& m) {
  Box b;
  for (const auto& p : m.positions) b.add(glm::dvec3(p));
  return b;
}

// The mesh-space sphere of an asset: level 0's centre, every level inside.
Sphere assetSphere(const scene::MeshAsset& a) {
  const Box b0 = boxOf(*a.data);
  Sphere s{b0.centre(), b0.halfDiagonal()};
  for (const scene::MeshLod& l : a.lods) {
    const Box b = boxOf(*l.data);
    s.radius = std::max(s.radius, glm::length(b.centre() - s.centre) + b.halfDiagonal());
  }
  return s;
}

// Signed distances (m, positive inside) of a world point to the view's six
// planes. In camera space (x right, y up, looking down -z, depth d = -z)
// the projection maps x to ndc = f/aspect x/d + shift.x; -1 <= ndc <= 1
// gives the side planes, nearClip <= d <= farClip the other two.
std::array<double, 6> planeDistances(const render::RenderView& v, const glm::dvec3& world) {
  const glm::dvec3 p = glm::conjugate(v.orientation) * (world - v.eye);
  const double d = -p.z, fy = 1.0 / std::tan(0.5 * v.fovY), fx = fy / v.aspect();
  const glm::dvec2 sh = v.projectionShift;
  // fx x / d + sx <= 1  <=>  (1 - sx) d - fx x >= 0, normalised by |(fx, 1 - sx)|; likewise the others.
  auto plane = [](double f, double c, double shift, double sign, double depth) {
    const double k = 1.0 - sign * shift;  // sign +1: the right (top) plane, -1: the left (bottom)
    return (k * depth - sign * f * c) / std::sqrt(f * f + k * k);
  };
  return {plane(fx, p.x, sh.x, +1.0, d), plane(fx, p.x, sh.x, -1.0, d), plane(fy, p.y, sh.y, +1.0, d),
          plane(fy, p.y, sh.y, -1.0, d), d - v.nearClip, v.farClip - d};
}

// What the reference says of one instance for one view: kept, dropped, or
// within `eps` of a boundary (a plane touching its sphere, or the cull
// distance), where float on the GPU and double here may disagree.
enum class Verdict { In, Out, Near };

Verdict reference(const render::RenderView& view, const glm::dvec3& lodEye, const foliage::Instance& in,
                  const Sphere& mesh, double cullDistance, double eps) {
  const double toEye = glm::length(in.position - lodEye);
  if (toEye > cullDistance + eps) return Verdict::Out;
  bool near = std::abs(toEye - cullDistance) <= eps;
  const glm::dvec3 centre = in.position + in.rotation * (mesh.centre * in.scale);
  const double radius = mesh.radius * std::max({std::abs(in.scale.x), std::abs(in.scale.y), std::abs(in.scale.z)});
  for (double dist : planeDistances(view, centre)) {
    if (dist + radius < -eps) return Verdict::Out;
    near = near || dist + radius <= eps;
  }
  return near ? Verdict::Near : Verdict::In;
}

struct IdCheck {
  size_t compared = 0, in = 0, outByPlanes = 0, outByDistance = 0, near = 0, mismatches = 0;
  std::string firstMismatch;
};

// The GPU's list for `view` against the reference over every instance.
IdCheck compareWithReference(const std::vector<render::InstancedSource::KeptInstance>& kept,
                             const render::RenderView& view, const glm::dvec3& lodEye, const scene::SceneState& s,
                             double eps) {
  IdCheck c;
  std::set<uint32_t> gpu;
  for (const auto& k : kept)
    if (!gpu.insert(k.id).second) {
      ++c.mismatches;  // an instance listed twice in one view
      c.firstMismatch = "id " + std::to_string(k.id) + " twice";
    }
  const Sphere sphere = assetSphere(s.assets.at(kPine));
  const std::vector<foliage::Instance> all = s.foliage->store().allInstances();
  std::set<uint32_t> known;
  for (const foliage::Instance& in : all) {
    known.insert(in.id);
    const Verdict v = reference(view, lodEye, in, sphere, kPineCull, eps);
    if (v == Verdict::Near) {
      ++c.near;
      continue;
    }
    ++c.compared;
    const bool cpuIn = v == Verdict::In;
    if (cpuIn) ++c.in;
    else if (glm::length(in.position - lodEye) > kPineCull) ++c.outByDistance;
    else ++c.outByPlanes;
    if (cpuIn != bool(gpu.count(in.id))) {
      if (c.firstMismatch.empty())
        c.firstMismatch = "id " + std::to_string(in.id) + (cpuIn ? " kept by the CPU only" : " kept by the GPU only");
      ++c.mismatches;
    }
  }
  for (uint32_t id : gpu)
    if (!known.count(id)) {
      ++c.mismatches;
      c.firstMismatch = "unknown id " + std::to_string(id);
    }
  return c;
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

  // An edit inside existing cells (an erase dab, a paint dab, its undo)
  // packs only the cells it touched again and the frame uploads only their
  // slots; the image equals that of sources built afresh from the store,
  // byte for byte. A dab on bare ground (a new cell) takes a slot from the
  // set's spare tail; more than the tail holds rebuilds the sets.
  void anEditUploadsOnlyItsCells() {
    scene::SceneState s = forest(foliage::ScaleMode::Uniform);
    scene::SceneState bare = s;  // drawn by the sources given, not the renderer's own
    bare.foliage.reset();
    render::FoliageSources kept;
    auto draw = [&](const std::vector<std::shared_ptr<render::InstancedSource>>& sources) {
      std::vector<std::shared_ptr<render::DrawSource>> ds(sources.begin(), sources.end());
      r_.renderer().setDrawSources(ds);
      Image img = r_.render(bare, camera());
      r_.renderer().setDrawSources({});
      return img;
    };
    // Sources built afresh from the store as it is: the reference.
    auto fresh = [&] {
      render::FoliageSources f;
      return draw(f.update(s));
    };
    auto liveIds = [](const std::vector<std::shared_ptr<render::InstancedSource>>& sources) {
      std::vector<uint32_t> ids;
      for (const auto& src : sources)
        for (const render::GpuInstance& g : src->instances().instances)
          if ((g.typeAndCell & 0xFFFFu) != 0xFFFFu) ids.push_back(g.id);
      std::sort(ids.begin(), ids.end());
      return ids;
    };
    auto storeIds = [&] {
      std::vector<uint32_t> ids;
      for (const foliage::Instance& in : s.foliage->store().allInstances()) ids.push_back(in.id);
      std::sort(ids.begin(), ids.end());
      return ids;
    };
    auto sameAsFresh = [&](const Image& img) {
      const test::CompareResult c = test::compareImages(toTest(img), toTest(fresh()), 0);
      if (c.maxChannelDiff != 0) qWarning("%s", c.summary().c_str());
      return c.maxChannelDiff == 0;
    };

    const auto& sources = kept.update(s);
    QVERIFY(kept.lastRebuilt());
    QCOMPARE(sources.size(), size_t(1));
    draw(sources);
    const size_t whole = sources[0]->lastUploadBytes();
    QCOMPARE(whole, sources[0]->instances().instances.size() * sizeof(render::GpuInstance));
    QVERIFY(liveIds(sources) == storeIds());
    const size_t cells = s.foliage->store().cellCount();
    QVERIFY(cells >= 2);

    // Erase a dab: one cell's slot uploaded.
    const glm::dvec2 at = glm::dvec2(kUtm) + glm::dvec2(-12.0, 10.0);
    foliage::EditResult e = foliage::erase(s.foliage->store(), foliage::Region2::disc(at, 4.0));
    QVERIFY(e.stats.removed > 0);
    s.foliage->touch();
    kept.update(s);
    QVERIFY(!kept.lastRebuilt());
    QCOMPARE(kept.lastRepackedCells(), e.undo.cellCount());
    Image img = draw(sources);
    const size_t dab = sources[0]->lastUploadBytes();
    qInfo("%zu cells, %zu bytes uploaded at first; an erase of %zu instances in %zu cell(s) uploads %zu bytes",
          cells, whole, size_t(e.stats.removed), e.undo.cellCount(), dab);
    QVERIFY(dab > 0 && dab < whole);
    QVERIFY(liveIds(sources) == storeIds());
    QVERIFY(sameAsFresh(img));

    // Paint it back (within the cell's room), then undo the paint.
    const scene::FoliageGround g(s);
    foliage::PaintParams p;
    p.region = foliage::Region2::disc(at, 4.0);
    p.types = {0};
    p.seed = 5;
    foliage::EditResult painted = foliage::paint(s.foliage->store(), g.ground(), p);
    QVERIFY(painted.stats.placed > 0);
    s.foliage->touch();
    kept.update(s);
    QVERIFY(!kept.lastRebuilt());
    QVERIFY(sameAsFresh(draw(sources)));
    QVERIFY(liveIds(sources) == storeIds());
    painted.undo.swap(s.foliage->store());
    s.foliage->touch();
    kept.update(s);
    QVERIFY(!kept.lastRebuilt());
    QVERIFY(sameAsFresh(draw(sources)));
    QVERIFY(liveIds(sources) == storeIds());

    // Instances in a cell the sets do not have (a dab on bare ground): its
    // slot comes from the set's spare tail, only that slot is uploaded, and
    // the image is what sources built afresh draw.
    const size_t setSize = sources[0]->instances().instances.size();
    const glm::dvec3 bareAt = kUtm + glm::dvec3(-33.0, 26.0, 0.0);  // the cell west of the forest's, in view
    QVERIFY(!s.foliage->store().cell(foliage::cellOf(bareAt)));
    foliage::EditResult fresh1;
    for (int i = 0; i < 12; ++i) {
      foliage::Instance in;
      in.position = bareAt + glm::dvec3(0.0, 2.0 * i, 0.0);
      in.scale = glm::dvec3(1.5);
      s.foliage->store().add(in, &fresh1.undo);
      ++fresh1.stats.placed;
    }
    QCOMPARE(s.foliage->store().cellCount(), cells + 1);
    s.foliage->touch();
    kept.update(s);
    QVERIFY(!kept.lastRebuilt());
    QCOMPARE(sources[0]->instances().instances.size(), setSize);  // the tail had room
    QCOMPARE(sources[0]->instances().cells.size(), cells + 1);
    img = draw(sources);
    const size_t newCell = sources[0]->lastUploadBytes();
    qInfo("%zu instances in a new cell upload %zu bytes", size_t(fresh1.stats.placed), newCell);
    QVERIFY(newCell > 0 && newCell < whole / 4);
    QVERIFY(liveIds(sources) == storeIds());
    QVERIFY(sameAsFresh(img));
    // Its undo empties the slot in place.
    fresh1.undo.swap(s.foliage->store());
    s.foliage->touch();
    kept.update(s);
    QVERIFY(!kept.lastRebuilt());
    QVERIFY(sameAsFresh(draw(sources)));
    QVERIFY(liveIds(sources) == storeIds());

    // More new instances than the tail holds: rebuilt.
    for (size_t i = 0; i < setSize; ++i) {
      foliage::Instance far;
      far.position = kUtm + glm::dvec3(3.0 * foliage::kCellSize + double(i % 200) * 0.25,
                                       double(i / 200) * 0.25, 0.0);
      s.foliage->store().add(far, nullptr);
    }
    s.foliage->touch();
    kept.update(s);
    QVERIFY(kept.lastRebuilt());
    QVERIFY(liveIds(sources) == storeIds());
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

  // The GPU culling (instance_lod.comp's cull distance, instance_cull.comp's
  // planes) keeps exactly the instances the brute-force reference above
  // keeps: the ids read back from the compute pass's list for the view,
  // against every instance of the store. Instances within kEps of a
  // boundary are left out of the comparison: the GPU tests the packed
  // record in float (positions relative to the frame origin, snorm16
  // rotations, half scales: a few mm on a 10 m tree's sphere), the
  // reference the store's doubles. 2 cm is several times that and still
  // small against the 3 m spacing, so few instances fall in it.
  void gpuCullingKeepsTheReferenceIds() {
    constexpr double kEps = 0.02;
    const scene::SceneState s = pineField();
    QVERIFY(s.assets.at(kPine).lods.size() >= 2);
    const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(s);
    QCOMPARE(sets.size(), size_t(1));
    // The source the renderer makes for the document's foliage
    // (foliage_sources.h), given the same set, drawn as an extra source
    // with the document's own foliage taken out.
    auto gpu = std::make_shared<render::InstancedSource>("pines", render::InstancedSource::Culling::Gpu);
    gpu->setInstances(sets[0]);
    gpu->setReportKept(true);
    scene::SceneState bare = s;
    bare.foliage.reset();
    const render::RenderView view = grazing();
    r_.renderer().setDrawSources({gpu});
    r_.renderOnly(bare, view);
    r_.renderOnly(bare, view);  // the lists come back a frame later
    r_.renderer().setDrawSources({});
    const auto kept = gpu->lastKept();
    QCOMPARE(kept.size(), size_t(1));
    const IdCheck c = compareWithReference(kept[0], view, view.eye, s, kEps);
    qInfo("%zu instances: %zu compared (%zu kept, %zu out by the planes, %zu beyond %.0f m), %zu within %.2f m of a "
          "boundary left out; the GPU kept %zu; %zu mismatches %s",
          s.foliage->store().allInstances().size(), c.compared, c.in, c.outByPlanes, c.outByDistance, kPineCull,
          c.near, kEps, kept[0].size(), c.mismatches, c.firstMismatch.c_str());
    QVERIFY2(c.mismatches == 0, c.firstMismatch.c_str());
    // Not a trivial set: many kept, many dropped by each rule.
    QVERIFY(c.in >= 200 && c.outByPlanes >= 200 && c.outByDistance >= 100);
    QVERIFY2(c.near * 100 <= c.compared, "too many instances near a boundary: the comparison says little");
  }

  // Both eyes of a stereo pair draw each instance at the same level, the
  // one the mono LOD view chooses (DESIGN.md "Rendering"): the eyes' lists
  // read back, every id both eyes keep at one level, equal to the mono
  // view's; each eye's list is also the reference's for that eye's
  // off-axis frustum (the cull distance from the LOD eye).
  void stereoEyesDrawOneLevelPerInstance() {
    constexpr double kEps = 0.02;
    const scene::SceneState s = pineField();
    scene::SceneState bare = s;
    bare.foliage.reset();
    const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(s);
    const render::RenderView mono = grazing();
    std::vector<render::RenderView> eyes(2, mono);
    // A landscape's hyperstereo (1 m between the eyes), so the eyes'
    // frusta differ enough at the edges for their lists to differ.
    constexpr double kHalfInteraxial = 0.5;
    for (int e = 0; e < 2; ++e) {
      const double side = e == 0 ? -1.0 : 1.0;  // left, right
      eyes[size_t(e)].eye += side * kHalfInteraxial * mono.right();
      // Converging on a plane 40 m away (a shifted frustum, not a turned one).
      eyes[size_t(e)].projectionShift.x = -side * kHalfInteraxial / (40.0 * std::tan(0.5 * mono.fovY) * mono.aspect());
    }
    auto listOf = [&](const std::vector<render::RenderView>& views, const render::RenderView* lodView) {
      auto gpu = std::make_shared<render::InstancedSource>("pines", render::InstancedSource::Culling::Gpu);
      gpu->setInstances(sets[0]);
      gpu->setReportKept(true);
      render::RenderOptions o;
      o.lodView = lodView;
      r_.renderer().setDrawSources({gpu});
      r_.renderViewsOnly(bare, views, o);
      r_.renderViewsOnly(bare, views, o);
      r_.renderer().setDrawSources({});
      return gpu->lastKept();
    };
    const auto monoKept = listOf({mono}, nullptr);
    const auto stereoKept = listOf(eyes, &mono);
    QCOMPARE(monoKept.size(), size_t(1));
    QCOMPARE(stereoKept.size(), size_t(2));
    std::map<uint32_t, uint32_t> monoLevel;
    for (const auto& k : monoKept[0]) monoLevel[k.id] = k.level;
    std::map<uint32_t, uint32_t> leftLevel;
    for (const auto& k : stereoKept[0]) leftLevel[k.id] = k.level;
    size_t both = 0, differ = 0, notMono = 0;
    std::set<uint32_t> levels;
    for (const auto& k : stereoKept[1]) {
      if (auto it = leftLevel.find(k.id); it != leftLevel.end()) {
        ++both;
        differ += it->second != k.level;
        levels.insert(k.level);
      }
      if (auto it = monoLevel.find(k.id); it != monoLevel.end()) notMono += it->second != k.level;
    }
    for (const auto& k : stereoKept[0])
      if (auto it = monoLevel.find(k.id); it != monoLevel.end()) notMono += it->second != k.level;
    qInfo("left %zu, right %zu, both %zu at levels %zu distinct; %zu differ between the eyes, %zu from mono",
          stereoKept[0].size(), stereoKept[1].size(), both, levels.size(), differ, notMono);
    QCOMPARE(differ, size_t(0));
    QCOMPARE(notMono, size_t(0));
    QVERIFY(both >= 200 && levels.size() >= 2);  // several levels in view: the check can fail
    for (int e = 0; e < 2; ++e) {
      const IdCheck c = compareWithReference(stereoKept[size_t(e)], eyes[size_t(e)], mono.eye, s, kEps);
      qInfo("eye %d: %zu compared, %zu kept, %zu near a boundary, %zu mismatches %s", e, c.compared, c.in, c.near,
            c.mismatches, c.firstMismatch.c_str());
      QVERIFY2(c.mismatches == 0, c.firstMismatch.c_str());
      QVERIFY(c.in >= 200 && c.near * 100 <= c.compared);
    }
    // The eyes' frusta differ: some instance at the edge is in one list only.
    QVERIFY(stereoKept[0].size() != both || stereoKept[1].size() != both);
  }

  // More instances than a source culls (kMaxInstancesPerSource; small
  // here): several sets of whole cells, none over the limit unless one cell
  // alone is, every record once.
  void manyInstancesSplitIntoSets() {
    const scene::SceneState s = pineField();
    const size_t total = s.foliage->store().allInstances().size();
    const size_t cells = s.foliage->store().cellCount();
    QVERIFY(cells >= 20);
    for (size_t cap : {size_t(500), size_t(1)}) {
      const std::vector<render::InstanceSet> sets = render::foliageInstanceSets(s, cap);
      std::set<uint32_t> ids;
      size_t setCells = 0;
      for (const render::InstanceSet& set : sets) {
        QVERIFY(set.instances.size() <= cap || set.cells.size() == 1);
        setCells += set.cells.size();
        for (const render::GpuInstance& g : set.instances) ids.insert(g.id);
      }
      QCOMPARE(ids.size(), total);
      QCOMPARE(setCells, cells);  // whole cells: none in two sets
      if (cap == 1) QCOMPARE(sets.size(), cells);
      else QVERIFY(sets.size() >= total / cap);
    }
    QCOMPARE(render::foliageInstanceSets(s).size(), size_t(1));
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
