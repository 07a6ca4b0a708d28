// Foliage in the document: types and instances through the command API
// (scatter, paint, erase and type edits are undo steps, bitwise exact),
// the .hscene round trip (every instance back with its id; a save after a
// dab writes only the touched cells; a damaged cell blob is dropped with a
// warning naming it while the rest loads), ground following as part of a
// terrain stroke's undo step (measured against the terrain's own surface),
// generated plants as assets with LODs and cut-out leaves; stored impostors
// (undo, file round trip, staleness, a damaged blob dropped alone).
#include <QtTest>

#include <filesystem>
#include <random>

#include <sqlite3.h>

#include "foliage/surface.h"
#include "foliage/tools.h"
#include "mesh/primitives.h"
#include "scene/document.h"
#include "scene/foliage_ops.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene/impostor_key.h"
#include "scene/impostor_ops.h"
#include "scene/scene_json.h"
#include "scene/terrain_edits.h"
#include "scene/terrain_ops.h"
#include "terrain/stroke.h"

using namespace hs;
using namespace hs::scene;

namespace {

EntityId makeTerrain(Document& doc, glm::dvec3 at = glm::dvec3(0.0)) {
  ops::NewTerrain spec;
  spec.name = "Valley";
  spec.samplesX = spec.samplesY = 129;
  spec.sizeMetres = glm::dvec2(256.0);
  spec.start = ops::NewTerrain::Start::Hills;
  spec.heightRange = {0.0f, 30.0f};
  spec.centre = at;
  std::string error;
  const EntityId id = ops::addTerrain(doc, spec, error);
  if (id == kNoEntity) qFatal("addTerrain: %s", error.c_str());
  return id;
}

// A rock asset (small and quick) and a type drawing it.
void addRockType(Document& doc, const std::string& name = "Rocks", double density = 200.0) {
  std::string error;
  if (!doc.state().findMaterialByName("Rock / rock") && ops::addPlantAsset(doc, "Rock", foliage::defaultPlant(foliage::PlantKind::Rock, 3), error) == kNoAsset)
    qFatal("addPlantAsset: %s", error.c_str());
  foliage::FoliageType t;
  t.name = name;
  t.mesh = "Rock";
  t.densityPerHa = density;
  t.spacing = 2.0;
  t.scale = {0.5, 1.5};
  const ops::FoliageOutcome out = ops::addFoliageType(doc, t);
  if (!out.ok) qFatal("addFoliageType: %s", out.error.c_str());
}

std::vector<foliage::Instance> instances(const Document& doc) {
  return doc.state().foliage ? doc.state().foliage->store().allInstances() : std::vector<foliage::Instance>{};
}

bool sameInstances(const std::vector<foliage::Instance>& a, const std::vector<foliage::Instance>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].id != b[i].id || a[i].type != b[i].type || a[i].position != b[i].position ||
        a[i].rotation != b[i].rotation || a[i].scale != b[i].scale)
      return false;
  return true;
}

QString tempPath(const char* name) {
  static QTemporaryDir dir;
  return dir.filePath(name);
}

}  // namespace

class TestSceneFoliage : public QObject {
  Q_OBJECT

 private slots:
  void scatterEraseAndTypeEditsAreUndoSteps() {
    Document doc;
    makeTerrain(doc);
    addRockType(doc);
    QCOMPARE(doc.state().foliage->store().types().size(), size_t(1));
    const FoliageGround ground(doc.state());
    const int before = doc.undoStack()->count();
    const ops::FoliageOutcome s = ops::scatterFoliage(doc, ground, {0}, 7);
    QVERIFY2(s.ok, s.error.c_str());
    QVERIFY(s.stats.placed > 200);  // 200/ha over 6.5 ha, thinned by spacing
    QCOMPARE(doc.undoStack()->count(), before + 1);
    const auto scattered = instances(doc);
    QCOMPARE(scattered.size(), s.stats.placed);

    const ops::FoliageOutcome e = ops::eraseFoliage(doc, foliage::Region2::disc({0.0, 0.0}, 50.0), {});
    QVERIFY(e.stats.removed > 0);
    const auto erased = instances(doc);
    QCOMPARE(erased.size(), scattered.size() - e.stats.removed);

    doc.undoStack()->undo();
    QVERIFY(sameInstances(instances(doc), scattered));
    doc.undoStack()->undo();
    QVERIFY(instances(doc).empty());
    doc.undoStack()->redo();
    QVERIFY(sameInstances(instances(doc), scattered));
    doc.undoStack()->redo();
    QVERIFY(sameInstances(instances(doc), erased));

    // A type's settings: one undo step, and its records follow a change of
    // scale encoding (and come back exactly on undo).
    foliage::FoliageType t = doc.state().foliage->store().type(0);
    t.scaleMode = foliage::ScaleMode::XyZ;
    t.densityPerHa = 50.0;
    QVERIFY(ops::setFoliageType(doc, 0, t).ok);
    QCOMPARE(doc.state().foliage->store().type(0).densityPerHa, 50.0);
    doc.undoStack()->undo();
    QCOMPARE(doc.state().foliage->store().type(0).densityPerHa, 200.0);
    QVERIFY(sameInstances(instances(doc), erased));
    // The type add itself undoes.
    while (doc.undoStack()->canUndo() && !doc.state().foliage->store().types().empty()) doc.undoStack()->undo();
    QVERIFY(doc.state().foliage->store().types().empty());
  }

  // The editor's worker path: a scatter on a copy of the store, committed
  // into the document, gives the instances a scatter on the document gives,
  // as one undo step; a commit after the document's foliage changed
  // meanwhile is refused and changes nothing.
  void scatterOnACopyCommitsAsOneStep() {
    Document direct, worked;
    for (Document* d : {&direct, &worked}) {
      makeTerrain(*d);
      addRockType(*d);
    }
    const FoliageGround g1(direct.state()), g2(worked.state());
    // The same two scatters, the second of `worked` on a copy.
    QVERIFY(ops::scatterFoliage(direct, g1, {0}, 3).ok);
    QVERIFY(ops::scatterFoliage(direct, g1, {0}, 7).ok);
    QVERIFY(ops::scatterFoliage(worked, g2, {0}, 3).ok);
    const int before = worked.undoStack()->count();
    const auto had = instances(worked);
    foliage::FoliageStore copy = worked.foliage().store();
    ops::FoliageWork work = ops::scatterOnStore(copy, g2, {0}, 7);
    QVERIFY(instances(worked).size() == had.size());  // the document untouched while it runs
    const ops::FoliageOutcome out = ops::commitFoliageWork(worked, copy, std::move(work));
    QVERIFY2(out.ok, out.error.c_str());
    QCOMPARE(worked.undoStack()->count(), before + 1);
    QVERIFY(out.stats.placed > 0);
    QCOMPARE(instances(worked).size(), had.size() + out.stats.placed);
    QVERIFY(sameInstances(instances(worked), instances(direct)));
    QVERIFY(sameInstances(copy.allInstances(), had));  // the copy as it was copied
    worked.undoStack()->undo();
    QVERIFY(sameInstances(instances(worked), had));

    // An erase in the document while the copy's scatter ran: refused.
    foliage::FoliageStore copy2 = worked.foliage().store();
    ops::FoliageWork late = ops::scatterOnStore(copy2, g2, {0}, 7);
    QVERIFY(ops::eraseFoliage(worked, foliage::Region2::disc({0.0, 0.0}, 40.0), {}).ok);
    const auto erased = instances(worked);
    const int steps = worked.undoStack()->count();
    const ops::FoliageOutcome refused = ops::commitFoliageWork(worked, copy2, std::move(late));
    QVERIFY(!refused.ok);
    QVERIFY2(refused.error.find("changed while it ran") != std::string::npos, refused.error.c_str());
    QCOMPARE(worked.undoStack()->count(), steps);
    QVERIFY(sameInstances(instances(worked), erased));

    // A cancelled work: nothing changes, no step.
    foliage::FoliageStore copy3 = worked.foliage().store();
    Progress cancelled;
    cancelled.cancel();
    const ops::FoliageOutcome c =
        ops::commitFoliageWork(worked, copy3, ops::scatterOnStore(copy3, g2, {0}, 9, std::nullopt, std::nullopt, 0, &cancelled));
    QVERIFY(c.ok && c.summary == "cancelled: nothing changed");
    QCOMPARE(worked.undoStack()->count(), steps);
    QVERIFY(sameInstances(instances(worked), erased));
  }

  void refusesWhatCannotBeDone() {
    Document doc;
    makeTerrain(doc);
    foliage::FoliageType t;
    t.name = "Ghost";
    t.mesh = "NoSuchAsset";
    const ops::FoliageOutcome a = ops::addFoliageType(doc, t);
    QVERIFY(!a.ok);
    QVERIFY2(a.error.find("NoSuchAsset") != std::string::npos, a.error.c_str());
    addRockType(doc);
    foliage::FoliageType dup = doc.state().foliage->store().type(0);
    const ops::FoliageOutcome d = ops::addFoliageType(doc, dup);
    QVERIFY(!d.ok);
    QVERIFY2(d.error.find("exists") != std::string::npos, d.error.c_str());
    const FoliageGround ground(doc.state());
    QVERIFY(!ops::scatterFoliage(doc, ground, {5}, 1).ok);  // no such type
    std::string error;
    QCOMPARE(ops::addPlantAsset(doc, "Rock", foliage::defaultPlant(foliage::PlantKind::Rock), error), kNoAsset);
    QVERIFY2(error.find("exists") != std::string::npos, error.c_str());
    Document empty;
    const FoliageGround none(empty.state());
    addRockType(empty);
    const ops::FoliageOutcome n = ops::scatterFoliage(empty, none, {0}, 1);
    QVERIFY(!n.ok);
    QVERIFY2(n.error.find("nothing to scatter on") != std::string::npos, n.error.c_str());
  }

  void plantAssetHasLodsAndCutoutLeaves() {
    Document doc;
    std::string error;
    const AssetId id = ops::addPlantAsset(doc, "Oak", foliage::defaultPlant(foliage::PlantKind::Broadleaf, 5), error);
    QVERIFY2(id != kNoAsset, error.c_str());
    const MeshAsset& a = *doc.state().findAsset(id);
    QVERIFY(a.lods.size() >= 2);
    for (size_t k = 1; k < a.lods.size(); ++k) {
      QVERIFY(a.lods[k].triangles < a.lods[k - 1].triangles);
      QVERIFY(a.lods[k].hausdorff >= a.lods[k - 1].hausdorff);
    }
    QCOMPARE(a.materialSlots.size(), size_t(2));
    const Material* bark = doc.state().findMaterial(a.materialSlots[0]);
    const Material* leaves = doc.state().findMaterial(a.materialSlots[1]);
    QVERIFY(bark && leaves);
    QVERIFY(!bark->alphaCutout);
    QVERIFY(leaves->alphaCutout && leaves->twoSided && leaves->baseColorTexture != kNoTexture);
    // The asset survives a save and load (its levels' materials name no
    // texture they lack).
    const std::string path = tempPath("plant.hscene").toStdString();
    QVERIFY2(saveScene(doc.state(), path, error), error.c_str());
    const auto loaded = loadScene(path, error);
    QVERIFY2(loaded, error.c_str());
    QCOMPARE(loaded->findAsset(id)->lods.size(), a.lods.size());
  }

  void fileRoundTripKeepsEveryInstanceAndWritesOnlyTouchedCells() {
    Document doc;
    makeTerrain(doc, glm::dvec3(500000.0, 4400000.0, 250.0));  // UTM: ids and millimetres kept
    addRockType(doc, "Rocks", 800.0);
    {
      const FoliageGround ground(doc.state());
      QVERIFY(ops::scatterFoliage(doc, ground, {0}, 11).ok);
    }
    const auto all = instances(doc);
    QVERIFY(all.size() > 1000);
    const std::string path = tempPath("forest.hscene").toStdString();
    std::string error;
    SaveReport first;
    QVERIFY2(saveScene(doc.state(), path, error, &first), error.c_str());
    QCOMPARE(first.cellsWritten, doc.state().foliage->store().cellCount());

    LoadReport lr;
    auto loaded = loadScene(path, error, nullptr, &lr);
    QVERIFY2(loaded, error.c_str());
    QVERIFY2(lr.warnings.empty(), lr.warnings.empty() ? "" : lr.warnings.front().c_str());
    QVERIFY(loaded->foliage);
    QVERIFY(sameInstances(loaded->foliage->store().allInstances(), all));
    QCOMPARE(loaded->foliage->store().nextId(), doc.state().foliage->store().nextId());
    QCOMPARE(loaded->foliage->store().types(), doc.state().foliage->store().types());
    QCOMPARE(canonicalJson(*loaded), canonicalJson(doc.state()));

    // One dab: only its cells are written again.
    Document again;
    again.reset(std::move(*loaded), QString::fromStdString(path));
    const glm::dvec3 c = all[all.size() / 2].position;
    const ops::FoliageOutcome e = ops::eraseFoliage(again, foliage::Region2::disc(glm::dvec2(c), 10.0), {});
    QVERIFY(e.stats.removed > 0);
    SaveReport second;
    QVERIFY2(saveScene(again.state(), path, error, &second), error.c_str());
    QVERIFY(second.cellsWritten + second.cellsRemoved >= 1);
    QVERIFY2(second.cellsWritten + second.cellsRemoved <= 4, qPrintable(QString::number(second.cellsWritten)));
    QCOMPARE(second.cellsUnchanged + second.cellsWritten, again.state().foliage->store().cellCount());
    auto reloaded = loadScene(path, error);
    QVERIFY2(reloaded, error.c_str());
    QVERIFY(sameInstances(reloaded->foliage->store().allInstances(), instances(again)));
  }

  void damagedCellIsDroppedWithAWarningAndTheRestLoads() {
    Document doc;
    makeTerrain(doc);
    addRockType(doc, "Rocks", 500.0);
    {
      const FoliageGround ground(doc.state());
      QVERIFY(ops::scatterFoliage(doc, ground, {0}, 5).ok);
    }
    const foliage::FoliageStore& store = doc.state().foliage->store();
    const size_t total = store.instanceCount(), cells = store.cellCount();
    QVERIFY(cells >= 4);
    const std::string path = tempPath("damaged.hscene").toStdString();
    std::string error;
    QVERIFY(saveScene(doc.state(), path, error));
    // Flip bytes inside one cell's payload.
    const foliage::CellKey victim = store.cells().begin()->first;
    const size_t lost = store.cell(victim)->count();
    {
      sqlite3* db = nullptr;
      QCOMPARE(sqlite3_open(path.c_str(), &db), SQLITE_OK);
      const std::string sql = "UPDATE blobs SET data = CAST(substr(data, 1, 44) || X'DEADBEEF' || substr(data, 49) AS "
                              "BLOB) WHERE key = '" + foliage::cellBlobKey(victim) + "'";
      QCOMPARE(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
      QCOMPARE(sqlite3_changes(db), 1);
      sqlite3_close(db);
    }
    LoadReport lr;
    auto loaded = loadScene(path, error, nullptr, &lr);
    QVERIFY2(loaded, error.c_str());  // the scene opens
    QCOMPARE(loaded->foliage->store().instanceCount(), total - lost);
    QCOMPARE(loaded->foliage->store().cellCount(), cells - 1);
    bool named = false;
    for (const std::string& w : lr.warnings)
      named |= w.find(foliage::cellName(victim)) != std::string::npos && w.find(path) != std::string::npos &&
               w.find(std::to_string(lost)) != std::string::npos;
    QVERIFY2(named, lr.warnings.empty() ? "no warning" : lr.warnings.front().c_str());
    // Ids of the lost instances are never handed out again.
    QCOMPARE(loaded->foliage->store().nextId(), store.nextId());
  }

  // A baked impostor (here made up: the bake needs GL, tests/render's
  // test_impostors bakes real ones) stored in its asset is one undo step,
  // survives the file (written once, not again when unchanged), goes stale
  // when the leaves' material changes, and a damaged blob loses only it.
  void impostorIsStoredUndoneAndSurvivesTheFile() {
    Document doc;
    addRockType(doc);
    const AssetId rock = foliageTypeAsset(doc.state(), doc.state().foliage->store().type(0));
    QVERIFY(rock != kNoAsset);
    QCOMPARE(ops::impostorsToBake(doc.state(), false), std::vector<AssetId>{rock});
    QCOMPARE(impostorStatus(doc.state(), *doc.state().findAsset(rock)), ImpostorStatus::None);

    auto images = [&](uint64_t key) {
      auto im = std::make_shared<foliage::ImpostorImages>();
      im->frames = foliage::kImpostorFrames;
      im->framePixels = foliage::kImpostorFramePixels;
      im->sphere = glm::vec4(0.0f, 0.0f, 0.5f, 1.0f);
      im->sourceKey = key;
      im->albedo.assign(im->imageBytes(), 0);
      im->normalDepth.assign(im->imageBytes(), 0);
      for (size_t i = 0; i < im->albedo.size(); i += 4 * 97) im->albedo[i] = 200, im->albedo[i + 3] = 255;
      return std::shared_ptr<const foliage::ImpostorImages>(im);
    };
    const uint64_t key = impostorSourceKey(doc.state(), *doc.state().findAsset(rock));
    // Images baked from something else (the asset changed during the bake) are refused.
    ops::StoredImpostors st = ops::storeImpostors(doc, {{rock, images(key + 1)}});
    QCOMPARE(st.stored, size_t(0));
    QVERIFY(!st.skipped.empty() && st.skipped[0].find("Rock") != std::string::npos);
    const int steps = doc.undoStack()->count();
    st = ops::storeImpostors(doc, {{rock, images(key)}, {12345, images(key)}});
    QCOMPARE(st.stored, size_t(1));
    QCOMPARE(st.skipped.size(), size_t(1));  // the asset that is not there
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    QCOMPARE(impostorStatus(doc.state(), *doc.state().findAsset(rock)), ImpostorStatus::Stored);
    QVERIFY(ops::impostorsToBake(doc.state(), false).empty());
    QCOMPARE(ops::impostorsToBake(doc.state(), true), std::vector<AssetId>{rock});

    const std::string path = tempPath("impostor.hscene").toStdString();
    std::string error;
    SaveReport first, second;
    QVERIFY2(saveScene(doc.state(), path, error, &first), error.c_str());
    QVERIFY2(saveScene(doc.state(), path, error, &second), error.c_str());
    QCOMPARE(second.blobsWritten, size_t(0));  // nothing changed: the impostor is not written again
    LoadReport lr;
    auto loaded = loadScene(path, error, nullptr, &lr);
    QVERIFY2(loaded, error.c_str());
    QVERIFY2(lr.warnings.empty(), lr.warnings.empty() ? "" : lr.warnings.front().c_str());
    const MeshAsset& back = *loaded->findAsset(rock);
    QVERIFY(back.impostor);
    QVERIFY(back.impostor->albedo == doc.state().findAsset(rock)->impostor->albedo);
    QCOMPARE(back.impostorHash, doc.state().findAsset(rock)->impostorHash);
    QCOMPARE(impostorStatus(*loaded, back), ImpostorStatus::Stored);
    QCOMPARE(canonicalJson(*loaded), canonicalJson(doc.state()));

    // The leaves' colour changed: stale, and listed for a bake again.
    {
      Edit e(doc, "Darker");
      e.material(doc.state().findAsset(rock)->materialSlots.front()).baseColor *= 0.5f;
      QVERIFY(e.commit());
    }
    QCOMPARE(impostorStatus(doc.state(), *doc.state().findAsset(rock)), ImpostorStatus::Stale);
    QCOMPARE(ops::impostorsToBake(doc.state(), false), std::vector<AssetId>{rock});
    doc.undoStack()->undo();
    doc.undoStack()->undo();  // the store itself
    QVERIFY(!doc.state().findAsset(rock)->impostor);

    // A damaged impostor blob: the scene opens without it, saying so.
    {
      sqlite3* db = nullptr;
      QCOMPARE(sqlite3_open(path.c_str(), &db), SQLITE_OK);
      const std::string sql = "UPDATE blobs SET data = CAST(substr(data, 1, 60) || X'DEADBEEF' || substr(data, 65) AS "
                              "BLOB) WHERE key = 'mesh/" + std::to_string(rock) + "/impostor'";
      QCOMPARE(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
      QCOMPARE(sqlite3_changes(db), 1);
      sqlite3_close(db);
    }
    lr = {};
    loaded = loadScene(path, error, nullptr, &lr);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(!loaded->findAsset(rock)->impostor);
    QCOMPARE(loaded->findAsset(rock)->impostorHash, uint64_t(0));
    QVERIFY(loaded->findAsset(rock)->data);  // the mesh itself is kept
    QCOMPARE(lr.warnings.size(), size_t(1));
    QVERIFY2(lr.warnings[0].find(path) != std::string::npos && lr.warnings[0].find("'Rock'") != std::string::npos &&
                 lr.warnings[0].find("impostor") != std::string::npos && lr.warnings[0].find("dropped") != std::string::npos,
             lr.warnings[0].c_str());
  }

  void foliageFollowsASculptedGroundInTheSameUndoStep() {
    Document doc;
    const glm::dvec3 at(500000.0, 4400000.0, 100.0);
    const EntityId te = makeTerrain(doc, at);
    addRockType(doc, "Rocks", 400.0);
    {
      const FoliageGround ground(doc.state(), false);
      QVERIFY(ops::scatterFoliage(doc, ground, {0}, 3).ok);
    }
    const auto placed = instances(doc);
    const int steps = doc.undoStack()->count();
    // A raise stroke through the middle.
    const TerrainId tid = doc.state().find(te)->terrain->terrain;
    TerrainData& data = *doc.state().findTerrain(tid)->data;
    terrain::BrushSettings s;
    s.tool = terrain::BrushTool::Raise;
    s.radius = 40.0;
    s.strength = 3.0f;
    terrain::Stroke st(data.terrain(), s);
    for (int i = 0; i < 6; ++i) {
      const terrain::StrokeUpdate u = st.moveTo(glm::dvec2(100.0 + 10.0 * i, 128.0), 1.0f);
      noteTerrainChange(doc, tid, data, u.changed, kTerrainHeights);
    }
    pushTerrainStep(doc, tid, st.finish(), "Raise");
    QCOMPARE(doc.undoStack()->count(), steps + 1);  // one step for both
    const auto moved = instances(doc);
    QCOMPARE(moved.size(), placed.size());
    // Against the terrain's own surface (placed at the entity's origin).
    terrain::Heightfield hf = data.terrain().height.clone();
    hf.setOrigin(terrainWorldOrigin(doc.state(), te));
    size_t changed = 0;
    double worst = 0.0;
    for (size_t i = 0; i < moved.size(); ++i) {
      if (moved[i].position.z != placed[i].position.z) ++changed;
      const auto sp = foliage::terrainSurface(hf, glm::dvec2(moved[i].position));
      QVERIFY(sp);
      // Rocks have no sink: they stand on the ground.
      worst = std::max(worst, std::abs(moved[i].position.z - sp->position.z));
    }
    QVERIFY2(changed > 10, qPrintable(QString::number(changed)));
    QVERIFY2(worst <= 1e-3, qPrintable(QString::number(worst)));
    doc.undoStack()->undo();
    QVERIFY(sameInstances(instances(doc), placed));
    doc.undoStack()->redo();
    QVERIFY(sameInstances(instances(doc), moved));
  }

  // A scan as an import leaves it: vertices relative to the mesh's origin
  // at UTM, the entity's translation that origin (turned and scaled here).
  // The foliage ground is the surface where the renderer draws it (the
  // entity's matrix times each vertex), and so is what a scatter stands on
  // and what a brush's ray meets.
  void scanAtUtmIsTheGroundWhereItIsDrawn() {
    const glm::dvec3 utm(500000.0, 4400000.0, 300.0);
    mesh::MeshData m = mesh::gridPlane(10.0f, 4);  // 10 m square, z = 0
    for (glm::vec3& p : m.positions) p.z = 0.5f;
    m.origin = utm;
    SceneState st;
    MeshAsset a;
    a.id = 1;
    a.name = "Ledge";
    a.data = std::make_shared<const mesh::MeshData>(std::move(m));
    st.assets.emplace(a.id, a);
    Entity e;
    e.id = 1;
    e.name = "Ledge";
    e.mesh = MeshInstance{a.id};
    e.transform.translation = utm;
    e.transform.rotation = fromEulerDegrees({0.0, 0.0, 30.0});
    e.transform.scale = glm::dvec3(2.0);
    st.entities.emplace(e.id, e);
    st.roots.push_back(e.id);
    const glm::dmat4 world = st.worldMatrix(e.id);
    const double drawnZ = utm.z + 1.0;  // 0.5 m up, scaled twice
    // Inside the drawn (turned) 20 m square, as M p puts it.
    auto onDrawnSquare = [&](const glm::dvec3& p) {
      const glm::dvec3 local = glm::inverse(world) * glm::dvec4(p, 1.0);
      return std::abs(local.x) <= 5.0 + 1e-6 && std::abs(local.y) <= 5.0 + 1e-6 && std::abs(p.z - drawnZ) <= 1e-3;
    };

    const FoliageGround ground(st);
    QCOMPARE(ground.ground().meshes.size(), size_t(1));
    const glm::dvec3 target = glm::dvec3(world * glm::dvec4(3.0, -2.0, 0.5, 1.0));
    const auto hit = ground.ground().meshes[0]->raycast(target + glm::dvec3(0.0, 0.0, 50.0), {0.0, 0.0, -1.0}, 100.0);
    QVERIFY(hit);
    QVERIFY2(glm::length(hit->position - target) < 1e-6, qPrintable(QString::number(glm::length(hit->position - target))));

    foliage::FoliageStore store;
    foliage::FoliageType t;
    t.name = "Moss";
    t.mesh = "Ledge";
    t.densityPerHa = 2000.0;
    t.spacing = 0.5;
    t.surface = foliage::SurfaceFilter::Meshes;
    std::vector<std::string> messages;
    QCOMPARE(store.addType(t, messages), 0);
    const foliage::EditResult r = foliage::scatter(store, ground.ground(), {0}, 4);
    QVERIFY2(r.stats.placed > 40, qPrintable(QString::number(r.stats.placed)));  // 400 m2 at 0.2 a square metre
    for (const foliage::Instance& in : store.allInstances())
      QVERIFY2(onDrawnSquare(in.position), qPrintable(QString("%1 %2 %3").arg(in.position.x, 0, 'f', 3)
                                                            .arg(in.position.y, 0, 'f', 3).arg(in.position.z, 0, 'f', 3)));
  }
};

QTEST_MAIN(TestSceneFoliage)
#include "test_scene_foliage.moc"
