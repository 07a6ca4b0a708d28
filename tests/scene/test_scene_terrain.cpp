// Terrains in the document: creation and deletion as undo steps, brush
// strokes as TerrainCommands on the document's QUndoStack (undo and redo
// bitwise exact, interleaved with ordinary edits), the undo memory cap
// (oldest dropped first, reported, QUndoStack left consistent), long jobs
// (erosion, paint rules) from snapshots with conflict detection, the
// canonical JSON following tile content, and picking through the scene.
#include <QtTest>

#include <random>

#include "scene/document.h"
#include "scene/edit.h"
#include "scene/operations.h"
#include "scene/scene_json.h"
#include "scene/terrain_edits.h"
#include "scene/terrain_jobs.h"
#include "scene/terrain_layer_ops.h"
#include "scene/terrain_ops.h"
#include "scene/terrain_pick.h"
#include "terrain/stroke.h"
#include "erosion_mass.h"
#include "terrain_compare.h"

using namespace hs;
using namespace hs::scene;

namespace {

EntityId makeTerrain(Document& doc, int samples = 257, double size = 256.0, const std::string& name = "Valley") {
  ops::NewTerrain spec;
  spec.name = name;
  spec.samplesX = spec.samplesY = samples;
  spec.sizeMetres = glm::dvec2(size);
  spec.start = ops::NewTerrain::Start::Hills;
  spec.heightRange = {0.0f, 40.0f};
  std::string error;
  const EntityId id = ops::addTerrain(doc, spec, error);
  if (id == kNoEntity) qFatal("addTerrain: %s", error.c_str());
  return id;
}

TerrainId terrainId(const Document& doc, EntityId e) { return doc.state().find(e)->terrain->terrain; }
TerrainData& data(Document& doc, EntityId e) { return *doc.state().findTerrain(terrainId(doc, e))->data; }

// One stroke of `tool` along a short random path, recorded in the document.
TerrainPushResult stroke(Document& doc, EntityId e, terrain::BrushTool tool, std::mt19937& rng, double radius = 20.0) {
  TerrainData& d = data(doc, e);
  terrain::BrushSettings s;
  s.tool = tool;
  s.radius = radius;
  s.strength = tool == terrain::BrushTool::Raise || tool == terrain::BrushTool::Lower ? 2.0f : 0.6f;
  s.paintLayer = int(rng() % 8);
  s.hydraulicIterationsPerDab = 4;
  s.thermal.iterations = 4;
  std::uniform_real_distribution<double> pos(-100.0, 100.0);
  // Brush positions are local to the heightfield (its origin is the SW corner).
  const glm::dvec2 o(-d.heights().origin());
  terrain::Stroke st(d.terrain(), s);
  glm::dvec2 p = o + glm::dvec2(pos(rng), pos(rng));
  for (int i = 0; i < 5; ++i) {
    const terrain::StrokeUpdate u = st.moveTo(p, 1.0f);
    noteTerrainChange(doc, terrainId(doc, e), d, u.changed, changeKindsOf(tool));
    p += glm::dvec2(pos(rng), pos(rng)) * 0.1;
  }
  return pushTerrainStep(doc, terrainId(doc, e), st.finish(), QString::fromUtf8(terrain::toolName(tool)));
}

const terrain::BrushTool kTools[] = {terrain::BrushTool::Raise,   terrain::BrushTool::Lower,
                                     terrain::BrushTool::Smooth,  terrain::BrushTool::Flatten,
                                     terrain::BrushTool::Noise,   terrain::BrushTool::Terrace,
                                     terrain::BrushTool::Paint,   terrain::BrushTool::Holes,
                                     terrain::BrushTool::ThermalErosion, terrain::BrushTool::HydraulicErosion};

}  // namespace

class TestSceneTerrain : public QObject {
  Q_OBJECT

 private slots:
  void newTerrainIsOneUndoStep() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    QCOMPARE(doc.undoStack()->count(), 1);
    const TerrainAsset* t = terrainOf(doc.state(), e);
    QVERIFY(t);
    QCOMPARE(t->materials.size(), size_t(8));
    QCOMPARE(t->data->heights().samplesX(), 257);
    QCOMPARE(t->data->heights().sizeMetres(), glm::dvec2(256.0));
    // Centred on the entity.
    QCOMPARE(terrainWorldOrigin(doc.state(), e), glm::dvec3(-128.0, -128.0, 0.0));
    QVERIFY(doc.state().validate().empty());
    const auto keep = t->data;
    doc.undoStack()->undo();
    QVERIFY(doc.state().terrains.empty());
    QVERIFY(!doc.state().find(e));
    doc.undoStack()->redo();
    QVERIFY(terrainOf(doc.state(), e));
    QCOMPARE(terrainOf(doc.state(), e)->data, keep);  // the same tiles, not a copy
    // Bad descriptions are refused with a reason and change nothing.
    ops::NewTerrain bad;
    bad.samplesX = 1;
    std::string error;
    QCOMPARE(ops::addTerrain(doc, bad, error), kNoEntity);
    QVERIFY2(error.find("2..8193") != std::string::npos, error.c_str());
    bad = {};
    bad.heightRange = {10.0f, 0.0f};
    QCOMPARE(ops::addTerrain(doc, bad, error), kNoEntity);
    QCOMPARE(doc.undoStack()->count(), 1);
  }

  // The one naming rule for a terrain made from a DEM (the editor's Import
  // DEM and `terrain import`): a name given must be free; the file's name
  // takes the first free "name 2", "name 3", ...
  void demTerrainsAreNamedByOneRule() {
    Document doc;
    auto grid = [] {
      terrain::HeightfieldDesc d;
      d.samplesX = d.samplesY = 5;
      d.sizeMetres = glm::dvec2(40.0);
      return terrain::Heightfield::create(d).take();
    };
    std::string error, name;
    QVERIFY(ops::addTerrainFromDem(doc, grid(), "/data/dem_wgs84.tif", {}, error, &name) != kNoEntity);
    QCOMPARE(name, std::string("dem_wgs84"));
    QVERIFY(ops::addTerrainFromDem(doc, grid(), "/other/dem_wgs84.tif", {}, error, &name) != kNoEntity);
    QCOMPARE(name, std::string("dem_wgs84 2"));
    QVERIFY(ops::addTerrainFromDem(doc, grid(), "dem_wgs84.tif", {}, error, &name) != kNoEntity);
    QCOMPARE(name, std::string("dem_wgs84 3"));
    const int steps = doc.undoStack()->index();
    name.clear();
    QCOMPARE(ops::addTerrainFromDem(doc, grid(), "x.tif", "dem_wgs84 2", error, &name), kNoEntity);
    QVERIFY2(error.find("'dem_wgs84 2'") != std::string::npos, error.c_str());
    QVERIFY(name.empty());
    QCOMPARE(doc.undoStack()->index(), steps);  // refused: nothing changed
    QVERIFY(ops::addTerrainFromDem(doc, grid(), "x.tif", "Pindus", error, &name) != kNoEntity);
    QCOMPARE(name, std::string("Pindus"));
    QVERIFY(doc.state().findByName("Pindus") != kNoEntity);
  }

  void deletingTheEntityTakesTheTerrainAndUndoBringsItBack() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    std::mt19937 rng(1);
    stroke(doc, e, terrain::BrushTool::Raise, rng);
    const terrain::Terrain afterStroke = data(doc, e).terrain().clone();
    const TerrainId tid = terrainId(doc, e);
    QVERIFY(ops::remove(doc, {e}));
    QVERIFY(!doc.state().findTerrain(tid));
    QVERIFY(doc.state().validate().empty());
    doc.undoStack()->undo();  // the deletion
    QVERIFY(doc.state().findTerrain(tid));
    QVERIFY(test::terrainDifference(data(doc, e).terrain(), afterStroke).empty());
    doc.undoStack()->undo();  // the stroke, on the restored terrain
    QVERIFY(!test::terrainDifference(data(doc, e).terrain(), afterStroke).empty());
    // A duplicate shows the same terrain; deleting one keeps it for the other.
    doc.undoStack()->redo();
    const std::vector<EntityId> copies = ops::duplicate(doc, {e});
    QCOMPARE(copies.size(), size_t(1));
    QVERIFY(ops::remove(doc, {e}));
    QVERIFY(doc.state().findTerrain(tid));
    QVERIFY(ops::removeComponent(doc, copies[0], *findComponent("terrain")));
    QVERIFY(!doc.state().findTerrain(tid));  // nothing shows it any more
    doc.undoStack()->undo();
    QVERIFY(doc.state().findTerrain(tid));
  }

  // The property: 100 random strokes of every tool, undone through
  // the document's QUndoStack, give back the original terrain bit for bit;
  // redo gives back the edited one. Ordinary edits are interleaved.
  void randomStrokesUndoAndRedoBitwise() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    const terrain::Terrain original = data(doc, e).terrain().clone();
    const std::string originalJson = canonicalJson(doc.state());
    const int base = doc.undoStack()->count();
    std::mt19937 rng(42);
    int pushed = 0;
    for (int i = 0; i < 100; ++i) {
      const TerrainPushResult r = stroke(doc, e, kTools[i % 10], rng);
      QVERIFY(r.kept);
      pushed += r.pushed;
      if (i % 17 == 0) QVERIFY(ops::rename(doc, e, "Valley " + std::to_string(i)));
      if (i % 17 == 0) ++pushed;
    }
    QCOMPARE(doc.undoStack()->count(), base + pushed);
    QVERIFY(doc.terrainUndo().bytesUsed() > 0);
    QVERIFY(doc.terrainUndo().bytesUsed() <= doc.terrainUndo().cap());
    const terrain::Terrain edited = data(doc, e).terrain().clone();
    const std::string editedJson = canonicalJson(doc.state());
    QVERIFY(editedJson != originalJson);  // the description follows tile content
    while (doc.undoStack()->index() > base) doc.undoStack()->undo();
    QString diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), original));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QCOMPARE(canonicalJson(doc.state()), originalJson);
    QCOMPARE(data(doc, e).heights().range().max, original.height.range().max);  // bounds restored too
    while (doc.undoStack()->canRedo()) doc.undoStack()->redo();
    diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), edited));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QCOMPARE(canonicalJson(doc.state()), editedJson);
    // Views hear of every undo: the change log reaches back.
    std::vector<TerrainChange> log;
    QVERIFY(data(doc, e).changesSince(0, log) || data(doc, e).serial() > 1000);
  }

  void undoMemoryCapDropsOldestFirst() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    const size_t cap = size_t(3) << 20;
    doc.terrainUndo().setCap(cap);
    std::mt19937 rng(7);
    std::vector<terrain::Terrain> states;
    states.push_back(data(doc, e).terrain().clone());
    size_t dropped = 0;
    for (int i = 0; i < 20; ++i) {
      const TerrainPushResult r = stroke(doc, e, terrain::BrushTool::Raise, rng, 40.0);
      QVERIFY(r.pushed && r.kept);
      dropped += r.dropped;
      QVERIFY2(doc.terrainUndo().bytesUsed() <= cap, qPrintable(QString::number(doc.terrainUndo().bytesUsed())));
      states.push_back(data(doc, e).terrain().clone());
    }
    QVERIFY(dropped > 0);
    QCOMPARE(doc.terrainUndo().droppedTotal(), dropped);
    const size_t kept = doc.terrainUndo().steps();
    QCOMPARE(kept + dropped, size_t(20));
    qInfo("cap %zu KiB: %zu steps kept (%zu KiB), %zu dropped", cap >> 10, kept, doc.terrainUndo().bytesUsed() >> 10,
          dropped);
    // Undo everything QUndoStack offers: the kept steps undo exactly; the
    // dropped ones leave the stack without touching the terrain.
    for (size_t k = 0; k < kept; ++k) {
      doc.undoStack()->undo();
      const QString diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), states[states.size() - 2 - k]));
      QVERIFY2(diff.isEmpty(), qPrintable(diff));
    }
    while (doc.undoStack()->canUndo()) doc.undoStack()->undo();  // the creation
    QVERIFY(doc.state().terrains.empty());
    QCOMPARE(doc.undoStack()->count(), int(kept) + 1);  // obsolete commands are gone
    while (doc.undoStack()->canRedo()) doc.undoStack()->redo();
    const QString diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), states.back()));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    // Lowering the cap drops more (only applied steps), raising keeps them.
    doc.terrainUndo().setCap(0);
    QCOMPARE(doc.terrainUndo().steps(), size_t(0));
    QCOMPARE(doc.terrainUndo().bytesUsed(), size_t(0));
  }

  void stepLargerThanTheCapStaysAppliedButIsNotUndoable() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    doc.undoStack()->setClean();
    doc.terrainUndo().setCap(100 * 1024);  // less than two tiles
    std::mt19937 rng(3);
    const int before = doc.undoStack()->count();
    const terrain::Terrain start = data(doc, e).terrain().clone();
    const TerrainPushResult r = stroke(doc, e, terrain::BrushTool::Raise, rng, 60.0);
    QVERIFY(!r.kept && !r.pushed);
    QCOMPARE(doc.undoStack()->count(), before);
    QVERIFY(!test::terrainDifference(data(doc, e).terrain(), start).empty());  // applied
    QVERIFY(doc.isModified());  // and the document knows it changed
  }

  void thermalJobIsOneUndoStepAndRefusesAConflict() {
    Document doc;
    const EntityId e = makeTerrain(doc, 129, 128.0);
    const TerrainId tid = terrainId(doc, e);
    const terrain::Terrain before = data(doc, e).terrain().clone();
    terrain::ThermalParams p;
    p.talusDegrees = 20.0;
    p.iterations = 30;
    auto job = TerrainJob::thermal(doc, tid, p);
    QVERIFY(job->valid());
    QVERIFY(!TerrainJob::paintRules(doc, tid)->valid());  // one job per terrain
    job->run(nullptr);
    // The live terrain is untouched until commit.
    QVERIFY(test::terrainDifference(data(doc, e).terrain(), before).empty());
    const int steps = doc.undoStack()->count();
    const TerrainJobOutcome out = job->commit(doc);
    QVERIFY2(out.ok, out.error.c_str());
    QVERIFY(out.erosion);
    const double moved = test::movedVolume(before.height, data(doc, e).terrain().height);
    qInfo("thermal job: mass error %.3g m^3, moved %.4g m^3, ratio %.3g (allowed %.2g)", out.erosion->massError, moved,
          out.erosion->massError / moved, test::kErosionMassTolerance);
    QVERIFY(moved > 0.0 && out.erosion->massError < test::kErosionMassTolerance * moved);
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    QVERIFY(!test::terrainDifference(data(doc, e).terrain(), before).empty());
    doc.undoStack()->undo();
    QVERIFY(test::terrainDifference(data(doc, e).terrain(), before).empty());

    // A stroke while the job runs: its result is refused, nothing changes.
    auto job2 = TerrainJob::paintRules(doc, tid);
    QVERIFY(job2->valid());
    std::mt19937 rng(9);
    terrain::BrushSettings s;
    s.tool = terrain::BrushTool::Paint;
    s.paintLayer = 2;
    s.radius = 200.0;  // every tile
    terrain::Stroke st(data(doc, e).terrain(), s);
    st.dabAt(glm::dvec2(64.0));
    pushTerrainStep(doc, tid, st.finish(), "paint");
    const terrain::Terrain painted = data(doc, e).terrain().clone();
    job2->run(nullptr);
    const TerrainJobOutcome out2 = job2->commit(doc);
    QVERIFY2(!out2.ok, out2.summary.c_str());
    QVERIFY2(out2.error.find("edited while") != std::string::npos, out2.error.c_str());
    QVERIFY(test::terrainDifference(data(doc, e).terrain(), painted).empty());
    QVERIFY(!data(doc, e).jobRunning);
  }

  void cancelledJobChangesNothing() {
    Document doc;
    const EntityId e = makeTerrain(doc, 129, 128.0);
    terrain::HydraulicParams p;
    p.iterations = 100000;
    auto job = TerrainJob::hydraulic(doc, terrainId(doc, e), p);
    Progress progress;
    progress.cancel();
    job->run(&progress);
    const int steps = doc.undoStack()->count();
    const TerrainJobOutcome out = job->commit(doc);
    QVERIFY(out.cancelled && !out.ok);
    QCOMPARE(doc.undoStack()->count(), steps);
  }

  void materialsAndRulesAreUndoableValues() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    const TerrainId tid = terrainId(doc, e);
    terrain::Material m = doc.state().findTerrain(tid)->materials[2];
    m.albedo = glm::vec3(0.1f, 0.2f, 0.3f);
    m.tilingMetres = -5.0f;  // refused value keeps the old one
    QVERIFY(ops::setTerrainMaterial(doc, tid, 2, m));
    QCOMPARE(doc.state().findTerrain(tid)->materials[2].albedo, glm::vec3(0.1f, 0.2f, 0.3f));
    QVERIFY(doc.state().findTerrain(tid)->materials[2].tilingMetres > 0.0f);
    QVERIFY(!ops::setTerrainMaterial(doc, tid, 99, m));
    doc.undoStack()->undo();
    QVERIFY(doc.state().findTerrain(tid)->materials[2].albedo != glm::vec3(0.1f, 0.2f, 0.3f));
    QVERIFY(ops::setTerrainPaintRules(doc, tid, {}));
    QVERIFY(doc.state().findTerrain(tid)->paintRules.empty());
    terrain::PaintRule bad;
    bad.layer = 40;
    QVERIFY(!ops::setTerrainPaintRules(doc, tid, {bad}));
    doc.undoStack()->undo();
    QVERIFY(!doc.state().findTerrain(tid)->paintRules.empty());
    // The LOD bound is a field like any other.
    QVERIFY(ops::setField(doc, e, *findEntityField("terrain.lod_error_px"), FieldValue(2.5)));
    QCOMPARE(doc.state().find(e)->terrain->lodErrorPixels, 2.5);
  }

  // Adding and removing paint layers: one undo step each, undo gives back
  // the terrain exactly (description and every weight), weights still sum
  // to 1 exactly after a removal, rules follow the layers, and tile edits
  // before and after the layer edits undo and redo through it.
  void paintLayerEditsAreExactUndoSteps() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    const TerrainId tid = terrainId(doc, e);
    std::mt19937 rng(7);
    for (int i = 0; i < 6; ++i) stroke(doc, e, terrain::BrushTool::Paint, rng, 40.0);
    const std::string originalJson = canonicalJson(doc.state());
    const terrain::Terrain original = data(doc, e).terrain().clone();
    const std::vector<terrain::PaintRule> rules = doc.state().findTerrain(tid)->paintRules;  // layers 1, 4, 2, 7
    const int base = doc.undoStack()->count();

    std::string error;
    QVERIFY2(ops::removeTerrainLayer(doc, tid, 2, error), error.c_str());
    QCOMPARE(doc.undoStack()->count(), base + 1);
    const TerrainAsset* t = doc.state().findTerrain(tid);
    QCOMPARE(t->materials.size(), size_t(7));
    QCOMPARE(t->data->terrain().paint.layerCount(), 7);
    QCOMPARE(t->materials[2].name, std::string("Conglomerate"));
    QCOMPARE(test::paintSumError(t->data->terrain().paint), 0L);  // exactly 1, not nearly
    // The sandstone rule went; later layers' rules moved down one.
    QCOMPARE(t->paintRules.size(), rules.size() - 1);
    QCOMPARE(t->paintRules[1].layer, 3);  // scree, was 4
    QCOMPARE(t->paintRules[2].layer, 6);  // snow, was 7
    QVERIFY(doc.state().validate().empty());
    const std::string removedJson = canonicalJson(doc.state());

    // A stroke on the new layers, then the base layer goes too.
    stroke(doc, e, terrain::BrushTool::Paint, rng, 40.0);
    stroke(doc, e, terrain::BrushTool::Raise, rng);
    QVERIFY2(ops::removeTerrainLayer(doc, tid, 0, error), error.c_str());
    t = doc.state().findTerrain(tid);
    QCOMPARE(test::paintSumError(t->data->terrain().paint), 0L);
    QCOMPARE(t->data->terrain().paint.grid(0).fill(), terrain::kWeightOne);  // the base layer reads 1 untouched
    const int added = ops::addTerrainLayer(doc, tid, terrain::Material{}, error);
    QCOMPARE(added, 6);
    QCOMPARE(doc.state().findTerrain(tid)->data->terrain().paint.layerCount(), 7);
    QCOMPARE(test::paintSumError(doc.state().findTerrain(tid)->data->terrain().paint), 0L);
    const std::string editedJson = canonicalJson(doc.state());
    const terrain::Terrain edited = data(doc, e).terrain().clone();

    // Undo everything: bit for bit the original, and the description too.
    while (doc.undoStack()->index() > base) doc.undoStack()->undo();
    QString diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), original));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QCOMPARE(canonicalJson(doc.state()), originalJson);
    QCOMPARE(doc.state().findTerrain(tid)->paintRules, rules);
    doc.undoStack()->redo();
    QCOMPARE(canonicalJson(doc.state()), removedJson);
    while (doc.undoStack()->canRedo()) doc.undoStack()->redo();
    diff = QString::fromStdString(test::terrainDifference(data(doc, e).terrain(), edited));
    QVERIFY2(diff.isEmpty(), qPrintable(diff));
    QCOMPARE(canonicalJson(doc.state()), editedJson);

    // Refusals change nothing and say why.
    const int steps = doc.undoStack()->count();
    QVERIFY(!ops::removeTerrainLayer(doc, tid, 42, error));
    QVERIFY2(error.find("no paint layer") != std::string::npos, error.c_str());
    while (doc.state().findTerrain(tid)->materials.size() < size_t(terrain::kMaxPaintLayers))
      QVERIFY(ops::addTerrainLayer(doc, tid, terrain::Material{}, error) > 0);
    QCOMPARE(ops::addTerrainLayer(doc, tid, terrain::Material{}, error), -1);
    QVERIFY2(error.find("16") != std::string::npos, error.c_str());
    while (doc.state().findTerrain(tid)->materials.size() > 1) QVERIFY(ops::removeTerrainLayer(doc, tid, 0, error));
    QVERIFY(!ops::removeTerrainLayer(doc, tid, 0, error));
    QVERIFY2(error.find("at least one") != std::string::npos, error.c_str());
    QCOMPARE(doc.state().findTerrain(tid)->data->terrain().paint.weight(0, 10, 10), 1.0f);
    while (doc.undoStack()->index() > steps) doc.undoStack()->undo();
    QCOMPARE(canonicalJson(doc.state()), editedJson);
    // A job running on the terrain keeps its tiles object: layer edits wait.
    auto job = TerrainJob::paintRules(doc, tid);
    QVERIFY(job->valid());
    QCOMPARE(ops::addTerrainLayer(doc, tid, terrain::Material{}, error), -1);
    QVERIFY2(error.find("busy") != std::string::npos, error.c_str());
  }

  // Rule edits: checked and clamped values; a scrubbed spin box (one merge
  // key) is one undo step; layers' names may change but not to nothing.
  void ruleAndMaterialEdits() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    const TerrainId tid = terrainId(doc, e);
    const std::vector<terrain::PaintRule> rules = doc.state().findTerrain(tid)->paintRules;
    const int base = doc.undoStack()->count();
    for (int i = 0; i < 5; ++i) {
      std::vector<terrain::PaintRule> r = rules;
      r[0].slopeMax = 20.0 + i;
      QVERIFY(ops::setTerrainPaintRules(doc, tid, r, "scrub-slope"));
    }
    QCOMPARE(doc.undoStack()->count(), base + 1);
    QCOMPARE(doc.state().findTerrain(tid)->paintRules[0].slopeMax, 24.0);
    std::vector<terrain::PaintRule> r = rules;
    r[1].strength = 7.0f;
    r[1].slopeBlend = -3.0;
    QVERIFY(ops::setTerrainPaintRules(doc, tid, r));
    QCOMPARE(doc.state().findTerrain(tid)->paintRules[1].strength, 1.0f);
    QCOMPARE(doc.state().findTerrain(tid)->paintRules[1].slopeBlend, 0.0);
    r[1].altitudeMin = std::nan("");
    QVERIFY(!ops::setTerrainPaintRules(doc, tid, r));
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    QCOMPARE(doc.state().findTerrain(tid)->paintRules, rules);

    terrain::Material m = doc.state().findTerrain(tid)->materials[3];
    m.name = "  ";
    m.roughness = 0.25f;
    QVERIFY(ops::setTerrainMaterial(doc, tid, 3, m));
    QCOMPARE(doc.state().findTerrain(tid)->materials[3].name, std::string("Conglomerate"));
    m.name = "Pillar rock";
    m.albedoTexture = "/textures/rock.png";
    QVERIFY(ops::setTerrainMaterial(doc, tid, 3, m));
    QCOMPARE(doc.state().findTerrain(tid)->materials[3].name, std::string("Pillar rock"));
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    QCOMPARE(doc.state().findTerrain(tid)->materials[3], terrain::defaultMaterials()[3]);
  }

  // Which terrain a terrain component shows: chosen, or made on the entity;
  // a terrain nothing shows any more goes in the same step.
  void terrainComponentShowsAChosenTerrain() {
    Document doc;
    const EntityId valley = makeTerrain(doc, 129, 128.0, "Valley");
    const TerrainId valleyId = terrainId(doc, valley);
    const EntityId empty = ops::addEmpty(doc, "Marker");
    QVERIFY(empty != kNoEntity);
    QVERIFY(ops::setShownTerrain(doc, empty, valleyId));
    QCOMPARE(terrainOf(doc.state(), empty), doc.state().findTerrain(valleyId));
    QVERIFY(!ops::setShownTerrain(doc, empty, 999));
    // A new terrain on that entity: centred on it, one step; Valley stays (Valley's entity shows it).
    const int steps = doc.undoStack()->count();
    ops::NewTerrain spec;
    spec.name = "Ridge";
    spec.samplesX = spec.samplesY = 65;
    spec.sizeMetres = glm::dvec2(64.0);
    spec.showOn = empty;
    std::string error;
    QCOMPARE(ops::addTerrain(doc, spec, error), empty);
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    const TerrainId ridge = terrainId(doc, empty);
    QVERIFY(ridge != valleyId);
    QCOMPARE(doc.state().terrains.size(), size_t(2));
    QCOMPARE(terrainWorldOrigin(doc.state(), empty), glm::dvec3(-32.0, -32.0, 0.0));
    // Showing Valley instead leaves Ridge unshown: it goes, undo brings it back.
    QVERIFY(ops::setShownTerrain(doc, empty, valleyId));
    QVERIFY(!doc.state().findTerrain(ridge));
    QVERIFY(doc.state().validate().empty());
    doc.undoStack()->undo();
    QVERIFY(doc.state().findTerrain(ridge));
    QCOMPARE(terrainId(doc, empty), ridge);
  }

  void pickingFollowsTheEntityAndSkipsHoles() {
    Document doc;
    const EntityId e = makeTerrain(doc);
    // Move it to UTM-like coordinates: picking works in double.
    Transform t;
    t.translation = glm::dvec3(500000.0, 4400000.0, 300.0);
    QVERIFY(ops::setTransforms(doc, {{e, t}}, "Move"));
    const glm::dvec3 above = t.translation + glm::dvec3(10.0, -5.0, 500.0);
    const auto hit = pickTerrain(doc.state(), above, glm::dvec3(0, 0, -1));
    QVERIFY(hit);
    QCOMPARE(hit->entity, e);
    const auto z = terrainSurfaceAt(doc.state(), e, glm::dvec2(above));
    QVERIFY(z);
    QVERIFY(std::abs(hit->hit.world.z - *z) < 0.05);
    QVERIFY(std::abs(hit->hit.world.x - above.x) < 1e-6);
    // Local brush position: metres from the heightfield's SW corner.
    QVERIFY(std::abs(hit->hit.local.x - 138.0) < 1e-6 && std::abs(hit->hit.local.y - 123.0) < 1e-6);
    // Cut holes there: the ray passes through.
    TerrainData& d = data(doc, e);
    terrain::BrushSettings s;
    s.tool = terrain::BrushTool::Holes;
    s.radius = 8.0;
    s.strength = 1.0f;
    terrain::Stroke st(d.terrain(), s);
    st.dabAt(hit->hit.local);
    pushTerrainStep(doc, terrainId(doc, e), st.finish(), "holes");
    QVERIFY(!pickTerrain(doc.state(), above, glm::dvec3(0, 0, -1)));
    QVERIFY(!terrainSurfaceAt(doc.state(), e, glm::dvec2(above)));
    doc.undoStack()->undo();
    QVERIFY(pickTerrain(doc.state(), above, glm::dvec3(0, 0, -1)));
    // Hidden terrains are not picked.
    QVERIFY(ops::setField(doc, e, *findEntityField("entity.visible"), FieldValue(false)));
    QVERIFY(!pickTerrain(doc.state(), above, glm::dvec3(0, 0, -1)));
  }

  void jsonRoundTripKeepsTheDescription() {
    Document doc;
    makeTerrain(doc, 129, 100.0, "A");
    makeTerrain(doc, 65, 30.0, "B");
    const hs::Json json = sceneToJson(doc.state());
    std::string error;
    std::optional<SceneState> back = sceneFromJson(json, error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(back->terrains.size(), size_t(2));
    for (const auto& [id, t] : doc.state().terrains) {
      const TerrainAsset* b = back->findTerrain(id);
      QVERIFY(b);
      QCOMPARE(b->name, t.name);
      QCOMPARE(b->materials, t.materials);
      QCOMPARE(b->paintRules, t.paintRules);
      QCOMPARE(b->data->heights().spacing(), t.data->heights().spacing());  // bit for bit
      QCOMPARE(b->data->heights().origin(), t.data->heights().origin());
    }
    // A reference to a terrain that is not there is refused.
    hs::Json broken = json;
    broken["terrains"] = hs::Json::array();
    QVERIFY(!sceneFromJson(broken, error));
    QVERIFY2(error.find("missing terrain") != std::string::npos, error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestSceneTerrain)
#include "test_scene_terrain.moc"
