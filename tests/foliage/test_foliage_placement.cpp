// Placement and tools: determinism per seed, the Poisson property across
// strokes (brute force), density, filters at their exact limits, erase,
// selections, undo and redo of every tool, ground following within 1 mm
// and over holes, instances on a mesh at UTM coordinates.
#include <map>
#include <random>

#include "foliage/ground_follow.h"
#include "foliage_fixtures.h"
#include "meshproc/closest_point_bvh.h"
#include "terrain/erosion_thermal.h"
#include "terrain/stroke.h"

using namespace fx;

namespace {

double bumps(double x, double y) { return 20.0 + 6.0 * std::sin(x * 0.031) * std::cos(y * 0.027) + 0.01 * x; }

// The closest pair distance of each type's instances (brute force).
double closestPair(const std::vector<Instance>& all, uint16_t type) {
  std::vector<glm::dvec3> p;
  for (const Instance& in : all)
    if (in.type == type) p.push_back(in.position);
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) best = std::min(best, glm::length(p[i] - p[j]));
  return best;
}

double angleBetween(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

}  // namespace

class TestFoliagePlacement : public QObject {
  Q_OBJECT
 private slots:
  void sameSeedSameInstancesAndIds() {
    const ht::Terrain t = terrain(257, 1.0, {1000, 2000, 5}, bumps);
    Ground g{&t, {}};
    auto run = [&](uint64_t seed, unsigned threads) {
      FoliageStore s;
      addType(s, type("Pine", 400, 2.0));
      addType(s, type("Grass", 3000, 0.5));
      scatter(s, g, {0, 1}, seed, std::nullopt, threads);
      PaintParams p;
      p.region = Region2::disc({1100, 2100}, 30);
      p.types = {0};
      p.densityFactor = 3;
      p.seed = seed + 1;
      p.threads = threads;
      paint(s, g, p);
      return snapshot(s);
    };
    const Snapshot a = run(7, 1), b = run(7, 2), c = run(7, 0), d = run(8, 2);
    QVERIFY(a.inst.size() > 10000);
    QVERIFY(same(a, b));
    QVERIFY(same(a, c));
    QVERIFY(!same(a, d));
  }

  // No two instances of a type closer than its spacing, however many
  // overlapping strokes put them there; other types may come closer.
  void poissonAcrossStrokes() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Pine", 5000, 1.5));
    addType(s, type("Fern", 5000, 0.7));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(20, 108);
    for (int stroke = 0; stroke < 40; ++stroke) {
      PaintParams p;
      p.region = Region2::disc({u(rng), u(rng)}, 12);
      p.types = {uint16_t(stroke % 2), uint16_t(stroke % 3 == 0 ? 1 : 0)};
      p.densityFactor = 2;
      p.seed = uint64_t(stroke);
      paint(s, g, p);
    }
    const auto all = s.allInstances();
    QVERIFY(s.instanceCount(0) > 1000 && s.instanceCount(1) > 1000);
    const double d0 = closestPair(all, 0), d1 = closestPair(all, 1);
    qInfo("closest pairs: %.4f m (spacing 1.5), %.4f m (spacing 0.7)", d0, d1);
    QVERIFY(d0 >= 1.5);
    QVERIFY(d1 >= 0.7);
    QVERIFY(d0 < 1.6 && d1 < 0.75);  // packed close to the limit: the check is not vacuous
  }

  void densityWithinFivePercent() {
    const ht::Terrain t = terrain(513, 1.0, {0, 0, 0}, [](double, double) { return 3.0; });
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Shrub", 800, 1.0));  // 0.08 per m^2, well under the Poisson packing limit at 1 m
    scatter(s, g, {0}, 11);
    const double target = 800.0 * 512.0 * 512.0 / 1e4;
    qInfo("%zu instances for %.0f wanted", s.instanceCount(), target);
    QVERIFY(std::abs(double(s.instanceCount()) / target - 1.0) < 0.05);
    // A second scatter over the same area only tops up what the first missed.
    const size_t before = s.instanceCount();
    scatter(s, g, {0}, 12);
    QVERIFY(double(s.instanceCount() - before) < 0.02 * target);
  }

  void slopeFilterAtExactLimits() {
    // A plane of slope exactly atan(0.5): heights 0.5 * x are exact floats.
    const ht::Terrain t = terrain(65, 1.0, {0, 0, 0}, [](double x, double) { return 0.5 * x; });
    Ground g{&t, {}};
    const double slope = slopeDegrees(glm::dvec3(-0.5, 0.0, 1.0));
    QCOMPARE(terrainSurface(t.height, {10.3, 20.7})->slopeDeg, slope);
    auto count = [&](double lo, double hi) {
      FoliageStore s;
      FoliageType ft = type("T", 2000, 0.5);
      ft.slopeDeg = {lo, hi};
      addType(s, ft);
      scatter(s, g, {0}, 1);
      return s.instanceCount();
    };
    const size_t all = count(0, 90);
    QVERIFY(all > 500);
    QCOMPARE(count(slope, slope), all);
    QCOMPARE(count(std::nextafter(slope, 90.0), 90), size_t(0));
    QCOMPARE(count(0, std::nextafter(slope, 0.0)), size_t(0));
    // Flat ground is exactly 0 degrees.
    const ht::Terrain flat = terrain(33, 1.0, {0, 0, 0}, [](double, double) { return 7.0; });
    Ground gf{&flat, {}};
    FoliageStore s;
    FoliageType ft = type("T", 2000, 0.5);
    ft.slopeDeg = {0, 0};
    addType(s, ft);
    scatter(s, gf, {0}, 1);
    QVERIFY(s.instanceCount() > 100);
    // A vertical wall (a mesh) is exactly 90 degrees.
    hs::mesh::MeshData wall;
    wall.positions = {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}};
    wall.indices = {0, 1, 2, 0, 2, 3};
    wall.submeshes.push_back({0, 6, -1});
    MeshGround mg(wall);
    Ground gw{nullptr, {&mg}};
    for (const auto& [lo, hi, some] : {std::tuple{90.0, 90.0, true}, std::tuple{0.0, std::nextafter(90.0, 0.0), false}}) {
      FoliageStore w;
      FoliageType wt = type("Moss", 5000, 0.3);
      wt.slopeDeg = {lo, hi};
      addType(w, wt);
      scatter(w, gw, {0}, 2, Region2::rect({-1, -1}, {11, 1}));
      QCOMPARE(w.instanceCount() > 0, some);
    }
  }

  void altitudeAndLayerFiltersAtExactLimits() {
    ht::Terrain t = terrain(65, 1.0, {0, 0, 100}, [](double, double) { return 0.0; });
    Ground g{&t, {}};
    auto count = [&](FoliageType ft) {
      FoliageStore s;
      addType(s, ft);
      scatter(s, g, {0}, 1);
      return s.instanceCount();
    };
    FoliageType ft = type("T", 2000, 0.5);
    const size_t all = count(ft);
    QVERIFY(all > 500);
    ft.altitude = {100, 100};
    QCOMPARE(count(ft), all);
    ft.altitude = {std::nextafter(100.0, 200.0), 200};
    QCOMPARE(count(ft), size_t(0));
    ft.altitude = {0, std::nextafter(100.0, 0.0)};
    QCOMPARE(count(ft), size_t(0));
    // Layer 1 at one weight everywhere (not a round number).
    for (int y = 0; y < 65; ++y)
      for (int x = 0; x < 65; ++x) t.paint.blend(x, y, 1, 0.3f);
    const double w = t.paint.raw(1, 10, 10) / 65535.0;
    QVERIFY(w > 0.2 && w < 0.4);
    ft = type("T", 2000, 0.5);
    ft.layer = t.paint.material(1).name;
    ft.layerWeight = {w, 1};
    QCOMPARE(count(ft), all);
    ft.layerWeight = {0, w};
    QCOMPARE(count(ft), all);
    ft.layerWeight = {std::nextafter(w, 1.0), 1};
    QCOMPARE(count(ft), size_t(0));
    ft.layerWeight = {0, std::nextafter(w, 0.0)};
    QCOMPARE(count(ft), size_t(0));
    // A layer the terrain does not have: refused with the type's name.
    FoliageStore s;
    ft.layer = "Lava";
    addType(s, ft);
    const EditResult r = scatter(s, g, {0}, 1);
    QCOMPARE(s.instanceCount(), size_t(0));
    QVERIFY(!r.stats.messages.empty());
    QVERIFY2(r.stats.messages[0].find("foliage type \"T\"") != std::string::npos &&
                 r.stats.messages[0].find("Lava") != std::string::npos,
             r.stats.messages[0].c_str());
  }

  // Fill a paint-layer region: instances only where the layer weighs
  // enough, at the type's density there; undo takes them away exactly.
  void fillPaintLayerRegion() {
    ht::Terrain t = terrain(257, 1.0, {0, 0, 0}, bumps);
    for (int y = 0; y < 257; ++y)
      for (int x = 0; x < 257; ++x)
        if (std::hypot(x - 128.0, y - 100.0) < 70.0) t.paint.blend(x, y, 2, 1.0f);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Heather", 1500, 0.8));
    const Snapshot before = snapshot(s);
    EditResult r = fillLayer(s, g, t.paint.material(2).name, 0.5, {0}, 3);
    const int layer = 2;
    size_t inside = 0;
    for (const Instance& in : s.allInstances()) {
      QVERIFY(terrainLayerWeight(t, layer, glm::dvec2(in.position)) >= 0.5);
      ++inside;
    }
    const double target = 1500.0 / 1e4 * 3.14159265 * 70.0 * 70.0;
    qInfo("layer fill: %zu instances for about %.0f wanted", inside, target);
    QVERIFY(std::abs(double(inside) / target - 1.0) < 0.06);
    // Filling again adds almost nothing; undo restores the empty store.
    const size_t n = s.instanceCount();
    fillLayer(s, g, t.paint.material(2).name, 0.5, {0}, 4);
    QVERIFY(double(s.instanceCount() - n) < 0.03 * target);
    r.undo.swap(s);  // (undo in order: the second fill added no cell of its own)
    FoliageStore e;
    addType(e, type("Heather", 1500, 0.8));
    EditResult again = fillLayer(e, g, t.paint.material(2).name, 0.5, {0}, 3);
    again.undo.swap(e);
    QVERIFY(same(before, snapshot(e)));
    const EditResult none = fillLayer(e, g, "Lava", 0.5, {0}, 3);
    QVERIFY(!none.stats.messages.empty() && none.stats.messages[0].find("Lava") != std::string::npos);
  }

  // Species compete in the rule-based scatter: shrubs keep the mean of the
  // two spacings from trees (without competition some stand closer).
  void speciesCompete() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    auto nearestTree = [](const std::vector<Instance>& all) {
      double best = std::numeric_limits<double>::infinity();
      for (const Instance& a : all)
        if (a.type == 1)
          for (const Instance& b : all)
            if (b.type == 0) best = std::min(best, glm::length(a.position - b.position));
      return best;
    };
    for (bool compete : {false, true}) {
      FoliageStore s;
      addType(s, type("Tree", 150, 6.0));
      addType(s, type("Shrub", 2500, 1.0));
      scatter(s, g, {0, 1}, 9, std::nullopt, 0, compete);
      const auto all = s.allInstances();
      QVERIFY(s.instanceCount(0) > 100 && s.instanceCount(1) > 1000);
      const double d = nearestTree(all);
      qInfo("compete %d: %zu trees, %zu shrubs, nearest shrub to a tree %.3f m", int(compete), s.instanceCount(0),
            s.instanceCount(1), d);
      QCOMPARE(d >= 3.5, compete);
      QVERIFY(closestPair(all, 0) >= 6.0 && closestPair(all, 1) >= 1.0);
    }
  }

  // A scatter cancelled through its Progress changes nothing: not before
  // it starts, not in the second of two types (the first type's instances
  // are given back), not in a paint; the fractions it reports only grow.
  void cancelledScatterChangesNothing() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Tree", 150, 6.0));
    addType(s, type("Shrub", 2500, 1.0));
    scatter(s, g, {0}, 3);  // some trees there already
    const Snapshot before = snapshot(s);
    const size_t cells = s.cellCount();

    hs::Progress early;
    early.cancel();
    EditResult r = scatter(s, g, {0, 1}, 9, std::nullopt, 0, true, &early);
    QVERIFY(r.cancelled && r.undo.empty() && r.stats.placed == 0);
    QVERIFY(same(before, snapshot(s)));

    double last = -1.0;
    bool grew = true;
    std::vector<std::string> stages;
    hs::Progress watching([&](double f, std::string_view stage) {
      grew = grew && f >= last;
      last = f;
      if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
    });
    r = scatter(s, g, {0, 1}, 9, std::nullopt, 0, true, &watching);
    QVERIFY(!r.cancelled && r.stats.placed > 1000);
    QVERIFY(grew && last > 0.5 && last <= 1.0);  // the second type in the second half
    QCOMPARE(stages, (std::vector<std::string>{"Tree", "Shrub"}));
    r.undo.swap(s);
    QVERIFY(same(before, snapshot(s)));

    // Cancelled once the second type's candidates start: the trees it
    // placed first go too.
    hs::Progress cancelling([&](double, std::string_view stage) {
      if (stage == "Shrub") cancelling.cancel();
    });
    r = scatter(s, g, {0, 1}, 9, std::nullopt, 0, true, &cancelling);
    QVERIFY(r.cancelled && r.undo.empty() && r.stats.placed == 0);
    QCOMPARE(r.stats.messages, std::vector<std::string>{"cancelled: nothing changed"});
    QVERIFY(same(before, snapshot(s)));

    PaintParams p;
    p.region = Region2::disc({64.0, 64.0}, 30.0);
    p.types = {1};
    p.progress = &early;
    r = paint(s, g, p);
    QVERIFY(r.cancelled && r.undo.empty());
    QVERIFY(same(before, snapshot(s)));
    QCOMPARE(s.cellCount(), cells);
  }

  // The layer fill and reapply run on the editor's worker too: cancelled,
  // they change nothing, the selection included; the progress a reapply
  // reports only grows, and a reapply watched to the end does what one
  // without a Progress does.
  void cancelledFillLayerAndReapplyChangeNothing() {
    ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    for (int y = 0; y < 129; ++y)
      for (int x = 0; x < 129; ++x)
        if (std::hypot(x - 64.0, y - 64.0) < 50.0) t.paint.blend(x, y, 2, 1.0f);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Heather", 4000, 0.5));
    scatter(s, g, {0}, 3);
    const Snapshot before = snapshot(s);
    hs::Progress early;
    early.cancel();
    EditResult r = fillLayer(s, g, t.paint.material(2).name, 0.5, {0}, 5, std::nullopt, 0, &early);
    QVERIFY(r.cancelled && r.undo.empty() && r.stats.placed == 0);
    QVERIFY(same(before, snapshot(s)));

    Selection sel = selectRegion(s, Region2::rect({0.0, 0.0}, {128.0, 128.0}));
    QVERIFY(sel.size() > 4096);  // past one progress batch
    FoliageType changed = s.type(0);
    changed.scale = {1.5, 2.0};
    std::vector<std::string> warnings;
    s.setType(0, changed, nullptr, warnings);
    const Snapshot retyped = snapshot(s);
    const Selection selected = sel;
    // Cancelled after its first batch: the instances it had redrawn go back.
    hs::Progress cancelling([&](double f, std::string_view) {
      if (f > 0.0) cancelling.cancel();
    });
    r = reapply(s, g, sel, 4, &cancelling);
    QVERIFY(r.cancelled && r.undo.empty() && r.stats.changed == 0);
    QVERIFY(same(retyped, snapshot(s)));
    QVERIFY(sel.items == selected.items);

    double last = -1.0;
    bool grew = true;
    hs::Progress watching([&](double f, std::string_view) {
      grew = grew && f >= last;
      last = f;
    });
    FoliageStore plain = s;
    Selection plainSel = sel;
    r = reapply(s, g, sel, 4, &watching);
    const EditResult q = reapply(plain, g, plainSel, 4);
    QVERIFY(!r.cancelled && r.stats.changed == q.stats.changed && r.stats.removed == q.stats.removed);
    QCOMPARE(r.stats.changed + r.stats.removed, selected.size());
    QVERIFY(r.stats.changed > selected.size() / 2);
    QVERIFY(grew && last > 0.0 && last < 1.0);
    QVERIFY(same(snapshot(plain), snapshot(s)) && sel.items == plainSel.items);
  }

  void badInputIsRefusedClearly() {
    const ht::Terrain t = terrain(65, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Zero", 0, 1));
    addType(s, type("Huge", 1e9, 0));  // sanitized to the cap
    QCOMPARE(s.type(1).densityPerHa, kMaxDensityPerHa);
    addType(s, type("Wide", 1000, 500));
    PaintParams p;
    p.region = Region2::disc({32, 32}, 0);
    p.types = {0, 1, 2};
    EditResult r = paint(s, g, p);
    QCOMPARE(s.instanceCount(), size_t(0));
    QVERIFY(r.undo.empty());
    bool zero = false, radius = false;
    for (const std::string& m : r.stats.messages) {
      zero = zero || (m.find("\"Zero\"") != std::string::npos && m.find("density 0") != std::string::npos);
      radius = radius || m.find("radius or area 0") != std::string::npos;
    }
    QVERIFY(zero && radius);
    // A spacing wider than the region: one instance, not a hang.
    p.region = Region2::disc({32, 32}, 20);
    p.types = {2};
    paint(s, g, p);
    QCOMPARE(s.instanceCount(), size_t(1));
    // The capped density places at most the Poisson packing, fast.
    p.types = {1};
    p.region = Region2::disc({32, 32}, 3);
    r = paint(s, g, p);
    QVERIFY(s.instanceCount() > 1);
  }

  void eraseRemovesOnlyWhatItCovers() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("A", 3000, 0.8));
    addType(s, type("B", 3000, 0.8));
    scatter(s, g, {0, 1}, 4);
    const auto before = s.allInstances();
    const Region2 disc = Region2::disc({64, 64}, 25);
    const EditResult r = erase(s, disc, {0});
    const auto after = s.allInstances();
    size_t expectRemoved = 0;
    for (const Instance& in : before) expectRemoved += in.type == 0 && disc.contains(glm::dvec2(in.position));
    QCOMPARE(r.stats.removed, expectRemoved);
    QCOMPARE(after.size(), before.size() - expectRemoved);
    for (const Instance& in : after) QVERIFY(!(in.type == 0 && disc.contains(glm::dvec2(in.position))));
    // Selections agree with brute force.
    const Region2 lasso = Region2::poly({{10, 10}, {100, 20}, {60, 110}, {40, 50}});
    const Selection sel = selectRegion(s, lasso);
    size_t inLasso = 0;
    for (const Instance& in : after) inLasso += lasso.contains(glm::dvec2(in.position));
    QCOMPARE(sel.size(), inLasso);
    const Instance& some = after[after.size() / 2];
    const Selection click = selectPoint(s, some.position + glm::dvec3(0.01, 0, 0), 0.3);
    QCOMPARE(click.size(), size_t(1));
    QCOMPARE(click.items[0].second, some.id);
  }

  // Undo restores the exact instance set (bits and ids) after every tool,
  // redo the exact result.
  void undoAndRedoOfEveryTool() {
    ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("A", 2000, 1.0));
    FoliageType b = type("B", 2000, 1.0);
    b.alignToNormal = true;
    b.sinkDepth = 0.2;
    addType(s, b);
    addType(s, type("C", 3000, 0.5));  // for the layer fill alone
    scatter(s, g, {0}, 5);
    auto check = [&](const char* what, const std::function<EditResult()>& op) {
      const Snapshot before = snapshot(s);
      EditResult r = op();
      const Snapshot after = snapshot(s);
      QVERIFY2(!same(before, after), what);
      r.undo.swap(s);
      QVERIFY2(same(before, snapshot(s)), what);
      r.undo.swap(s);
      QVERIFY2(same(after, snapshot(s)), what);
    };
    check("paint", [&] {
      PaintParams p;
      p.region = Region2::disc({40, 40}, 20);
      p.types = {1};
      p.seed = 9;
      return paint(s, g, p);
    });
    check("erase", [&] { return erase(s, Region2::disc({60, 60}, 15)); });
    check("fill", [&] { return fill(s, g, Region2::poly({{0, 0}, {128, 0}, {0, 128}}), {1}, 3); });
    check("scatter", [&] { return scatter(s, g, {0, 1}, 77); });
    check("layer fill", [&] {
      for (int y = 20; y < 60; ++y)
        for (int x = 20; x < 60; ++x) t.paint.blend(x, y, 3, 1.0f);
      return fillLayer(s, g, t.paint.material(3).name, 0.5, {2}, 8);
    });
    Selection sel = selectRegion(s, Region2::rect({10, 10}, {50, 90}));
    QVERIFY(sel.size() > 100);
    check("move", [&] { return moveSelection(s, g, sel, {70.0, 3.0, 0.0}, true); });
    check("reapply", [&] {
      FoliageType changed = s.type(1);
      changed.scale = {2.0, 3.0};
      std::vector<std::string> w;
      s.setType(1, changed, nullptr, w);
      return reapply(s, g, sel, 4);
    });
    check("delete", [&] { return deleteSelection(s, sel); });
  }

  void moveKeepsIdsAndSnapsToGround() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("A", 500, 1.0));
    scatter(s, g, {0}, 5);
    Selection sel = selectRegion(s, Region2::rect({10, 10}, {40, 40}));
    const auto ids = sel.ids();
    EditResult moved = moveSelection(s, g, sel, {50.0, 60.0, 0.0}, true);
    QCOMPARE(sel.ids(), ids);
    for (uint32_t id : ids) {
      const auto in = s.find(id);
      QVERIFY(in);
      QVERIFY(in->position.x >= 60 && in->position.y >= 70);
      QVERIFY(std::abs(in->position.z - terrainSurface(t.height, glm::dvec2(in->position))->position.z) <= kMaxPositionError);
    }
    // Undone, the selection still names the cells the move put them in; a
    // second move finds every one where it is now (by id), exactly.
    std::map<uint32_t, glm::dvec3> before;
    moved.undo.swap(s);
    for (uint32_t id : ids) before[id] = s.find(id)->position;
    const EditResult again = moveSelection(s, g, sel, {1.0, -2.0, 0.5}, false);
    QCOMPARE(again.stats.moved, ids.size());
    for (uint32_t id : ids) QCOMPARE(s.find(id)->position, before[id] + glm::dvec3(1.0, -2.0, 0.5));
  }

  // After a sculpt (an analytic plane, then bumps) and a new hole, the
  // instances under the edit stand on the new surface within 1 mm, those
  // over the hole are gone, and undo brings everything back.
  void groundFollowing() {
    ht::Terrain t = terrain(257, 1.0, {5e5, 4.4e6, 300}, [](double x, double y) { return 10.0 + 0.25 * x - 0.125 * y; });
    Ground g{&t, {}};
    FoliageStore s;
    addType(s, type("Flat", 1500, 1.0));
    FoliageType sunk = type("Sunk", 1500, 1.0);
    sunk.alignToNormal = true;
    sunk.alignMaxDeg = 10;
    sunk.randomPitchDeg = 5;
    sunk.sinkDepth = 0.4;
    addType(s, sunk);
    scatter(s, g, {0, 1}, 21);
    QVERIFY(s.instanceCount() > 10000);
    // Sculpt: samples [40, 200)^2 become another plane, then bumps.
    const ht::Region region{40, 40, 200, 200};
    for (int pass = 0; pass < 2; ++pass) {
      const ht::Heightfield before = t.height.clone();
      for (int y = region.y0; y < region.y1; ++y)
        for (int x = region.x0; x < region.x1; ++x)
          t.height.set(x, y, float(pass == 0 ? 40.0 - 0.125 * x + 0.0625 * y : bumps(x * 3.0, y * 2.0)));
      t.height.updateBounds(region);
      const Snapshot prior = snapshot(s);
      FollowStats st;
      FoliageUndo undo = followGround(s, before, t.height, region, &st);
      QVERIFY(st.moved > 1000);
      double worst = 0.0;
      for (const Instance& in : s.allInstances()) {
        const FoliageType& ft = s.type(in.type);
        const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
        const glm::dvec3 anchor = in.position + up * ft.sinkDepth;
        const glm::dvec2 local = glm::dvec2(anchor) - glm::dvec2(5e5, 4.4e6);
        // Instances on the plane of pass 0 (the analytic surface), on the
        // triangles of pass 1.
        double ground;
        if (pass == 0 && local.x >= 41 && local.x <= 198 && local.y >= 41 && local.y <= 198)
          ground = 300.0 + 40.0 - 0.125 * local.x + 0.0625 * local.y;
        else
          ground = terrainSurface(t.height, glm::dvec2(anchor))->position.z;
        worst = std::max(worst, std::abs(anchor.z - ground));
      }
      qInfo("pass %d: %zu moved, worst distance to the surface %.3f mm", pass, st.moved, worst * 1e3);
      QVERIFY(worst <= 1e-3);
      undo.swap(s);
      QVERIFY(same(prior, snapshot(s)));
      undo.swap(s);
    }
    // A hole: the instances over it go, undo brings them back.
    const ht::Heightfield before = t.height.clone();
    for (int y = 100; y < 120; ++y)
      for (int x = 100; x < 120; ++x) t.height.setHole(x, y, true);
    const Snapshot prior = snapshot(s);
    FollowStats st;
    FoliageUndo undo = followGround(s, before, t.height, ht::Region{100, 100, 120, 120}, &st);
    QVERIFY(st.removed > 50);
    for (const Instance& in : s.allInstances()) {
      const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
      QVERIFY(terrainSurface(t.height, glm::dvec2(in.position + up * s.type(in.type).sinkDepth)));
    }
    undo.swap(s);
    QVERIFY(same(prior, snapshot(s)));
  }

  // Through the terrain library's own edits: a raise stroke and a thermal
  // erosion under the instances. After each, every instance stands on the
  // drawn surface within 1 mm; undoing the terrain step and the foliage
  // step of the same edit restores both exactly.
  void followsRealStrokesAndErosion() {
    ht::Terrain t = terrain(257, 1.0, {5e5, 4.4e6, 200}, bumps);
    Ground g{&t, {}};
    FoliageStore s;
    FoliageType ft = type("Birch", 1200, 1.5);
    ft.alignToNormal = true;
    ft.sinkDepth = 0.25;
    addType(s, ft);
    scatter(s, g, {0}, 6);
    auto worst = [&] {
      double w = 0.0;
      for (const Instance& in : s.allInstances()) {
        const glm::dvec3 anchor = in.position + in.rotation * glm::dvec3(0, 0, 1) * ft.sinkDepth;
        w = std::max(w, std::abs(anchor.z - terrainSurface(t.height, glm::dvec2(anchor))->position.z));
      }
      return w;
    };
    const double placed = worst();
    const Snapshot start = snapshot(s);
    // A stroke of raise dabs across the middle.
    ht::Heightfield before = t.height.clone();
    ht::BrushSettings bs;
    bs.tool = ht::BrushTool::Raise;
    bs.radius = 30.0;
    bs.strength = 3.0f;
    ht::Stroke stroke(t, bs, 1);
    for (int i = 0; i <= 10; ++i) stroke.moveTo({60.0 + 14.0 * i, 128.0 + 3.0 * i});
    ht::UndoStep step = stroke.finish();
    FollowStats st;
    FoliageUndo fu = followGround(s, before, t.height, step.region(), &st);
    const double afterStroke = worst();
    // A thermal erosion of the whole terrain.
    before = t.height.clone();
    ht::ThermalParams tp;
    tp.talusDegrees = 20.0;
    tp.iterations = 20;
    ht::erodeThermal(t.height, tp, ht::ErosionMask::whole(t.height));
    FollowStats st2;
    FoliageUndo fu2 = followGround(s, before, t.height, t.height.bounds(), &st2);
    const double afterErosion = worst();
    qInfo("worst distance to the surface: %.3f mm placed, %.3f mm after the stroke (%zu moved), %.3f mm after "
          "erosion (%zu moved)", placed * 1e3, afterStroke * 1e3, st.moved, afterErosion * 1e3, st2.moved);
    QVERIFY(st.moved > 500 && st2.moved > 500);
    QVERIFY(afterStroke <= 1e-3 && afterErosion <= 1e-3);
    // Undo the erosion's foliage step, then the stroke's (the terrain is
    // the document's to restore; the foliage comes back exactly).
    fu2.swap(s);
    fu.swap(s);
    QVERIFY(same(start, snapshot(s)));
  }

  // A scan standing on the terrain (a closed box sunk 5 m into it): with
  // both surfaces, no terrain instance grows inside its footprint, and
  // instances stand on its top and on its sides above the ground (none on
  // the buried part); with the cover test off, the terrain under it fills.
  void noTerrainFoliageInsideAScan() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, [](double, double) { return 10.0; });
    hs::mesh::MeshData box;
    box.origin = {60, 60, 17.5};
    for (int i = 0; i < 8; ++i)
      box.positions.emplace_back(i & 1 ? 20.f : -20.f, i & 2 ? 20.f : -20.f, i & 4 ? 12.5f : -12.5f);
    box.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    box.submeshes.push_back({0, uint32_t(box.indices.size()), -1});
    MeshGround mg(box);
    for (double cover : {100.0, 0.0}) {
      Ground g{&t, {&mg}, cover};
      FoliageStore s;
      addType(s, type("Fern", 2000, 0.6));
      scatter(s, g, {0}, 2);
      size_t inside = 0, onTop = 0, onSides = 0;
      for (const Instance& in : s.allInstances()) {
        const bool within = in.position.x > 40.01 && in.position.x < 79.99 && in.position.y > 40.01 && in.position.y < 79.99;
        if (in.surface == Surface::Terrain) inside += within;
        if (in.surface == Surface::Mesh) (std::abs(in.position.z - 30.0) < 0.01 ? onTop : onSides)++;
        if (in.surface == Surface::Mesh) QVERIFY(in.position.z >= 10.0 - 0.01);  // none buried under the terrain
      }
      qInfo("cover %.0f m: %zu terrain instances inside the box, %zu on its top, %zu on its sides", cover, inside, onTop, onSides);
      QCOMPARE(inside == 0, cover > 0.0);
      QVERIFY(onTop > 100 && onSides > 100);
    }
  }

  // A terrain and a scan 300 km apart: the scatter over both (their joint
  // bounds) throws only where there is ground and keeps its Poisson grid
  // sparse, so it takes what the two surfaces take, not the bounds.
  void groundsFarApart() {
    const ht::Terrain t = terrain(129, 1.0, {0, 0, 0}, bumps);
    const hs::mesh::MeshData m = gridMesh(40, 100.0, {2e5, 2.2e5, 50}, [](double x, double) { return 0.2 * x; });
    MeshGround mg(m);
    Ground g{&t, {&mg}};
    FoliageStore s;
    addType(s, type("Fern", 2000, 0.8));
    QElapsedTimer timer;
    timer.start();
    const EditResult r = scatter(s, g, {0}, 4);
    qInfo("%zu instances (%zu candidates) in %lld ms", s.instanceCount(), r.stats.candidates, timer.elapsed());
    size_t onMesh = 0;
    for (const Instance& in : s.allInstances()) onMesh += in.surface == Surface::Mesh;
    QVERIFY(onMesh > 1000 && s.instanceCount() - onMesh > 2000);
    QVERIFY(r.stats.candidates < 20000);
    QVERIFY(timer.elapsed() < 5000);
    QVERIFY(closestPair(s.allInstances(), 0) >= 0.8);
  }

  // A scan at UTM coordinates: instances lie on its surface within 1 mm,
  // tilted toward its normal by at most the type's maximum angle.
  void onMeshAtUtm() {
    const glm::dvec3 origin(512345.0, 4412345.0, 420.0);
    const hs::mesh::MeshData m = gridMesh(60, 120.0, origin, [](double x, double y) {
      return 8.0 * std::sin(x * 0.05) + 0.3 * y;  // slopes up to about 30 degrees
    });
    MeshGround mg(m);
    Ground g{nullptr, {&mg}};
    FoliageStore s;
    FoliageType ft = type("Shrub", 3000, 0.8);
    ft.surface = SurfaceFilter::Meshes;
    ft.alignToNormal = true;
    ft.alignMaxDeg = 15;
    addType(s, ft);
    scatter(s, g, {0}, 3);
    QVERIFY(s.instanceCount() > 2000);
    hs::mesh::ClosestPointBvh bvh(m);
    double worst = 0.0, worstTilt = 0.0;
    for (const Instance& in : s.allInstances()) {
      QCOMPARE(in.surface, Surface::Mesh);
      const auto hit = bvh.closest(in.position - origin);
      worst = std::max(worst, std::sqrt(hit.distanceSq));
      const glm::dvec3 up = in.rotation * glm::dvec3(0, 0, 1);
      worstTilt = std::max(worstTilt, angleBetween(up, {0, 0, 1}));
      const glm::dvec3 a(m.positions[m.indices[3 * hit.face]]), b(m.positions[m.indices[3 * hit.face + 1]]),
          c(m.positions[m.indices[3 * hit.face + 2]]);
      const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
      const double slope = angleBetween(n, {0, 0, 1});
      // Tilted all the way to the normal, or by the maximum toward it.
      QVERIFY(angleBetween(up, n) <= std::max(0.0, slope - 15.0) + 0.3);
    }
    qInfo("on the scan: worst distance %.3f mm, worst tilt %.2f degrees", worst * 1e3, worstTilt);
    QVERIFY(worst <= 1e-3);
    QVERIFY(worstTilt <= 15.3);
    QVERIFY(worstTilt > 14.0);
    QVERIFY(closestPair(s.allInstances(), 0) >= 0.8);
  }

  // The editor brush's pick on a scan (MeshGround::raycast): the first
  // surface along the ray within 1 mm, at UTM coordinates, from above and
  // at a slant; a ray that misses, or stops short, finds nothing.
  void raycastFindsTheFirstSurface() {
    const glm::dvec3 origin(512345.0, 4412345.0, 420.0);
    // A plane z = 0.25 x (local) under a second layer 10 m above it: the
    // upper one is hit first from above.
    hs::mesh::MeshData m = gridMesh(20, 100.0, origin, [](double x, double) { return 0.25 * x; });
    const hs::mesh::MeshData upper = gridMesh(4, 20.0, origin + glm::dvec3(60, 60, 40), [](double, double) { return 0.0; });
    const uint32_t base = uint32_t(m.positions.size());
    for (const glm::vec3& p : upper.positions) m.positions.push_back(p + glm::vec3(60, 60, 40));
    for (uint32_t i : upper.indices) m.indices.push_back(base + i);
    m.submeshes = {{0, uint32_t(m.indices.size()), -1}};
    MeshGround mg(m);
    const glm::dvec3 down(0, 0, -1);
    auto hit = mg.raycast(origin + glm::dvec3(30.0, 40.0, 500.0), down, 1e4);
    QVERIFY(hit);
    QVERIFY(std::abs(hit->position.z - (origin.z + 7.5)) <= 1e-3);
    QVERIFY(std::abs(hit->slopeDeg - glm::degrees(std::atan(0.25))) < 1e-6);
    hit = mg.raycast(origin + glm::dvec3(70.0, 70.0, 500.0), down, 1e4);  // over the upper layer
    QVERIFY(hit);
    QVERIFY(std::abs(hit->position.z - (origin.z + 40.0)) <= 1e-3);
    // At a slant from the side: the point on the plane along the ray.
    const glm::dvec3 from = origin + glm::dvec3(-50.0, 10.0, 60.0);
    const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 0.0, -1.0));
    hit = mg.raycast(from, dir, 1e4);
    QVERIFY(hit);
    // The ray z = 60 - (x + 50) meets z = 0.25 x at x = 8, z = 2.
    QVERIFY(glm::length(hit->position - (origin + glm::dvec3(8.0, 10.0, 2.0))) <= 2e-3);
    QVERIFY(!mg.raycast(origin + glm::dvec3(200.0, 40.0, 500.0), down, 1e4));  // beside the scan
    QVERIFY(!mg.raycast(origin + glm::dvec3(30.0, 40.0, 500.0), down, 100.0));  // stops short
    QVERIFY(!mg.raycast(origin + glm::dvec3(30.0, 40.0, 500.0), -down, 1e4));  // looking up
  }
};

QTEST_GUILESS_MAIN(TestFoliagePlacement)
#include "test_foliage_placement.moc"
