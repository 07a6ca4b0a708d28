// The .hscene file: exact round trips (description and mesh data bit for
// bit), incremental saves that write only changed blobs, Save As, and every
// kind of bad file, each refused with a message naming the file while the
// open document stays as it was.
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include <sqlite3.h>
#include <sys/resource.h>
#include <unistd.h>

#include "core/scratch_files.h"
#include "dead_scratch.h"
#include "file_bytes.h"
#include "hscene_sql.h"
#include "mesh/mesh_import.h"
#include "mesh/primitives.h"
#include "scene/demo_scene.h"
#include "scene/cluster_asset.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene/mesh_blob.h"
#include "scene/mesh_materials.h"
#include "scene/operations.h"
#include "scene/scene_json.h"
#include "truncation.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

using hs::test::readBlob;
using hs::test::readDescription;
using hs::test::readFile;
using hs::test::sql;
using hs::test::writeBlob;
using hs::test::writeDescription;
using hs::test::writeFile;

namespace {

const std::string kMeshData = HS_TEST_DATA_DIR "/mesh";

// "line L, column C" of byte `offset` in `text`, counted here by hand
// (lines and characters from 1), to check the places messages name.
std::string lineColumnOf(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Where the n-th (from 0) occurrence of `needle` starts; npos if there is none.
size_t nthOccurrence(const std::string& text, const std::string& needle, int n) {
  size_t at = text.find(needle);
  while (at != std::string::npos && n-- > 0) at = text.find(needle, at + 1);
  return at;
}



template <class T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Bit-exact comparison of two meshes; returns what differs, or "".
std::string meshDifference(const mesh::MeshData& a, const mesh::MeshData& b) {
  if (std::memcmp(&a.origin, &b.origin, sizeof a.origin) != 0) return "origin";
  if (!sameBytes(a.positions, b.positions)) return "positions";
  if (!sameBytes(a.normals, b.normals)) return "normals";
  if (!sameBytes(a.uvs, b.uvs)) return "uvs";
  if (!sameBytes(a.indices, b.indices)) return "indices";
  if (a.submeshes.size() != b.submeshes.size()) return "submesh count";
  for (size_t i = 0; i < a.submeshes.size(); ++i)
    if (a.submeshes[i].firstIndex != b.submeshes[i].firstIndex || a.submeshes[i].indexCount != b.submeshes[i].indexCount ||
        a.submeshes[i].material != b.submeshes[i].material)
      return "submesh " + std::to_string(i);
  if (a.materials.size() != b.materials.size()) return "material count";
  for (size_t i = 0; i < a.materials.size(); ++i)
    if (a.materials[i].name != b.materials[i].name ||
        std::memcmp(&a.materials[i].baseColor, &b.materials[i].baseColor, sizeof(glm::vec4)) != 0 ||
        a.materials[i].diffuseTexture != b.materials[i].diffuseTexture)
      return "material " + std::to_string(i);
  if (a.textures.size() != b.textures.size()) return "texture count";
  for (size_t i = 0; i < a.textures.size(); ++i) {
    const auto &ta = a.textures[i], &tb = b.textures[i];
    if (ta.name != tb.name || ta.width != tb.width || ta.height != tb.height || !sameBytes(ta.encoded, tb.encoded) ||
        !sameBytes(ta.rgba, tb.rgba))
      return "texture " + std::to_string(i);
  }
  return {};
}

// Everything a load must give back: the description and every mesh.
std::string stateDifference(const SceneState& a, const SceneState& b) {
  if (canonicalJson(a) != canonicalJson(b)) return "description (canonicalJson)";
  if (a.entities != b.entities) return "entities";
  if (a.roots != b.roots) return "roots";
  if (!(a.settings == b.settings)) return "settings";
  if (a.assets.size() != b.assets.size()) return "asset count";
  for (const auto& [id, asset] : a.assets) {
    const MeshAsset* other = b.findAsset(id);
    if (!other || !(asset == *other)) return "asset " + std::to_string(id);
    if (!asset.data || !other->data) return "asset " + std::to_string(id) + " has no data";
    if (const std::string d = meshDifference(*asset.data, *other->data); !d.empty())
      return "asset " + std::to_string(id) + ": " + d;
    for (size_t k = 0; k < asset.lods.size(); ++k)  // sizes and hashes compared by ==
      if (const std::string d = meshDifference(*asset.lods[k].data, *other->lods[k].data); !d.empty())
        return "asset " + std::to_string(id) + " LOD " + std::to_string(k + 1) + ": " + d;
  }
  return {};
}

// Logical asset blobs: each mesh and each of its LOD levels (the demo bunny has three).
size_t assetBlobs(const SceneState& s) {
  size_t n = 0;
  for (const auto& [id, a] : s.assets) n += 1 + a.lods.size() + (a.clustersHash != 0 ? 1 : 0);  // mesh, LODs, cluster index
  // Standalone textures (the demo's slabs) have a blob each; a mesh's live in its blob.
  for (const auto& [id, t] : s.textures) n += t.standalone() ? 1 : 0;
  n += s.settings.post.lut.empty() ? 0 : 1;  // the grading LUT (the demo's)
  n += s.settings.post.ocioConfig.files.size();  // the OpenColorIO config and its LUTs (the demo's)
  return n;
}

mesh::ImportResult importFixture(const std::string& name) {
  return mesh::importMesh(kMeshData + "/" + name);
}

// The demo (the bunny, three instances) plus textured meshes: an OBJ with
// its PNG, a glTF with an embedded PNG, and one whose texture has no source
// bytes (raw pixels, as Assimp hands over uncompressed embedded textures).
SceneState richScene() {
  std::string error;
  std::optional<SceneState> demo = buildDemoScene(error);
  if (!demo) qFatal("demo scene: %s", error.c_str());
  Document doc;
  doc.reset(std::move(*demo), {});
  for (const char* f : {"textured_quad.obj", "textured_quad.glb"}) {
    mesh::ImportResult r = importFixture(f);
    if (!r.ok()) qFatal("%s", r.error.c_str());
    ops::addImportedMesh(doc, std::move(*r.mesh), f, f, r.report, {glm::dvec3(5, 5, 0), kNoEntity});
  }
  mesh::ImportResult raw = importFixture("textured_quad.obj");
  raw.mesh->textures.at(0).encoded.clear();
  raw.mesh->textures.at(0).name = "raw pixels";
  ops::addImportedMesh(doc, std::move(*raw.mesh), "raw", "raw", raw.report);
  // A hierarchy edit and a setting, so the description has more than defaults.
  ops::rename(doc, doc.state().findByName("Scans"), "Scans (renamed)");
  ops::setSettingsField(doc, *findSettingsField("antialiasing"), int64_t(1));
  return doc.state();
}

// Asset blobs: the demo's terrain tiles have their own suite (test_terrain_file).
// Asset blobs (meshes, levels, textures): terrain tiles and foliage cells are counted apart.
int blobKeyCount(const std::string& path) {
  // Cluster pages apart (the index blob counts with the assets').
  return test::countBlobKeys(path, "key NOT LIKE 'terrain/%' AND key NOT LIKE 'foliage/%' AND (key NOT LIKE "
                                   "'clusters/%' OR key LIKE 'clusters/index/%')");
}

// How the editor and the CLI open a file: load into a new state and replace
// the open document only when that worked.
bool openInto(Document& doc, const std::string& path, std::string& error) {
  std::optional<SceneState> s = loadScene(path, error);
  if (!s) return false;
  doc.reset(std::move(*s), QString::fromStdString(path));
  return true;
}

// Lowers this process's file size limit for one scope (a disk that fills up
// while saving); root is bound by it too, unlike file permissions.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old_);
    oldHandler_ = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a signal
    rlimit lim = old_;
    lim.rlim_cur = bytes;
    ok_ = setrlimit(RLIMIT_FSIZE, &lim) == 0;
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, oldHandler_);
  }
  bool ok() const { return ok_; }

 private:
  rlimit old_{};
  void (*oldHandler_)(int) = nullptr;
  bool ok_ = false;
};

}  // namespace

class TestHsceneFile : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  SceneState rich_;
  std::string goodFile_;  // rich_ saved once, copied by the damage tests

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }

  // A copy of the good file to damage.
  std::string copyOfGood(const std::string& name) {
    const std::string p = path(name);
    fs::copy_file(goodFile_, p, fs::copy_options::overwrite_existing);
    return p;
  }

  // The bad-file check every damage test ends with: loading fails with a
  // message naming the file (and containing `what`), and a document that
  // holds a scene keeps it, its file name and its undo history.
  void expectRefused(const std::string& file, const std::vector<std::string>& what) {
    Document doc;
    doc.reset(rich_, "open.hscene");
    QVERIFY(ops::rename(doc, doc.state().findByName("Sun"), "Sun (edited)"));
    const std::string before = canonicalJson(doc.state());
    const int undoCount = doc.undoStack()->count();
    std::string error;
    QVERIFY2(!openInto(doc, file, error), "a bad file was opened");
    QVERIFY2(error.find(file) != std::string::npos, error.c_str());
    for (const auto& w : what) QVERIFY2(error.find(w) != std::string::npos, qPrintable(QString("'%1' not in: %2").arg(w.c_str(), error.c_str())));
    QVERIFY(error.find('\n') == std::string::npos);  // one line
    QCOMPARE(canonicalJson(doc.state()), before);
    QCOMPARE(doc.filePath(), QString("open.hscene"));
    QCOMPARE(doc.undoStack()->count(), undoCount);
    QVERIFY(doc.isModified());
    qInfo("refused as expected: %s", error.c_str());
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    rich_ = richScene();
    // The demo's bunny, its two surface-detail slabs, its three glass spheres
    // and pond (scene/demo_glass.h), its six generated plants
    // (scene/demo_foliage.h), its clustered bunny (scene/demo_clusters.h),
    // and three imports.
    QCOMPARE(rich_.assets.size(), size_t(17));
    QVERIFY(rich_.foliage && rich_.foliage->store().instanceCount() > 0);
    goodFile_ = path("good.hscene");
    std::string error;
    QVERIFY2(saveScene(rich_, goodFile_, error), error.c_str());
  }

  // ---- round trips ------------------------------------------------------------

  void saveLoadRoundTrip() {
    const std::string p = path("roundtrip.hscene");
    // What a save killed part-way left beside it (a dead process on this
    // machine) goes with the next new save; a live process's stays.
    const std::string live = path(scratchName("roundtrip.hscene.saving-"));
    const std::string stale = test::asDeadProcess(live).name;
    QVERIFY(!stale.empty());
    writeFile(stale, "half a scene");
    writeFile(stale + "-journal", "its journal");
    writeFile(live, "another save of this process, under way");
    auto temporaries = [&] {
      std::vector<std::string> names;
      for (const auto& e : fs::directory_iterator(tmp_.path().toStdString()))
        if (e.path().filename().string().rfind("roundtrip.hscene.saving-", 0) == 0) names.push_back(e.path().string());
      std::sort(names.begin(), names.end());
      return names;
    };
    QCOMPARE(temporaries().size(), size_t(3));
    std::string error;
    SaveReport report;
    QVERIFY2(saveScene(rich_, p, error, &report), error.c_str());
    QVERIFY(temporaries() == std::vector<std::string>{live});  // its own temporary renamed, the dead one's swept
    fs::remove(live);
    QVERIFY(!report.incremental);
    QCOMPARE(report.blobsWritten, assetBlobs(rich_));
    QCOMPARE(report.blobsUnchanged, size_t(0));
    size_t pages = 0;  // the clustered bunny's, copied from the file they were saved to first
    for (const auto& [id, a] : rich_.assets) pages += a.clusters ? a.clusters->pages->pageCount() : 0;
    QVERIFY(pages > 0);
    QCOMPARE(report.pagesWritten, pages);
    QVERIFY(report.bytesWritten > 1000000);  // the bunny alone is over a megabyte

    std::optional<SceneState> loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    const std::string diff = stateDifference(rich_, *loaded);
    QVERIFY2(diff.empty(), diff.c_str());
    QVERIFY(loaded->validate().empty());
    QCOMPARE(sceneFileVersion(p), kSceneFormatVersion);
    // Textures came back decoded, with their source bytes where there were some.
    int encoded = 0, raw = 0;
    for (const auto& [id, a] : loaded->assets)
      for (const auto& t : a.data->textures) {
        QCOMPARE(t.rgba.size(), size_t(t.width) * size_t(t.height) * 4);
        (t.encoded.empty() ? raw : encoded) += 1;
      }
    QCOMPARE(encoded, 2);
    QCOMPARE(raw, 6);  // one import's, and the generated leaves of the demo's pine, plane tree, juniper, grass and heather
    // Saving what was loaded gives the same description again.
    const std::string p2 = path("roundtrip2.hscene");
    QVERIFY2(saveScene(*loaded, p2, error), error.c_str());
    std::optional<SceneState> again = loadScene(p2, error);
    QVERIFY2(again, error.c_str());
    QVERIFY(stateDifference(rich_, *again).empty());
  }

  void descriptionJsonRoundTrip() {
    std::string error;
    const std::optional<SceneState> back = sceneFromJson(sceneToJson(rich_), error);
    QVERIFY2(back, error.c_str());
    QCOMPARE(canonicalJson(*back), canonicalJson(rich_));
    QVERIFY(back->entities == rich_.entities);
    QVERIFY(back->roots == rich_.roots);
    QVERIFY(back->settings == rich_.settings);
  }

  // The description as the file holds it: write, read, write gives the
  // same bytes (entities, settings, the assets' reports, the sequence).
  void descriptionTextRoundTripsByteForByte() {
    const std::string text = writeJson(sceneToJson(rich_));
    std::string error;
    bool notJson = false;
    const std::optional<SceneState> back = sceneFromJsonText(text, error, notJson);
    QVERIFY2(back, error.c_str());
    QCOMPARE(writeJson(sceneToJson(*back)), text);
    QVERIFY(!rich_.assets.begin()->second.importReport.is_null());
    QVERIFY(!rich_.assets.begin()->second.processReport.is_null());  // the demo bunny's LOD chain
  }

  void loadProgressAndCancel() {
    std::string error;
    int calls = 0;
    Progress progress([&](double f, std::string_view) {
      ++calls;
      QVERIFY(f >= 0.0 && f <= 1.0);
    });
    QVERIFY2(loadScene(goodFile_, error, &progress), error.c_str());
    QVERIFY(calls >= int(rich_.assets.size()));
    Progress* self = nullptr;
    Progress cancelling([&](double, std::string_view) { self->cancel(); });
    self = &cancelling;
    QVERIFY(!loadScene(goodFile_, error, &cancelling));
    QVERIFY2(error.find(goodFile_) != std::string::npos && error.find("cancelled") != std::string::npos, error.c_str());
  }

  // ---- incremental saves ----------------------------------------------------------

  void secondSaveWritesOnlyWhatChanged() {
    const std::string p = path("incremental.hscene");
    std::string error;
    SaveReport first;
    QVERIFY2(saveScene(rich_, p, error, &first), error.c_str());
    const size_t blobs = assetBlobs(rich_);  // 4 meshes and the bunny's 3 LOD levels
    QCOMPARE(first.blobsWritten, blobs);

    Document doc;
    QVERIFY2(openInto(doc, p, error), error.c_str());
    doc.markSaved();

    // One entity changes: the description is rewritten, no blob is.
    QVERIFY(ops::setTransforms(doc, {{doc.state().findByName("Stanford Bunny"), Transform{}}}, "Move"));
    SaveReport second;
    QVERIFY2(saveScene(doc.state(), p, error, &second), error.c_str());
    QVERIFY(second.incremental);
    QCOMPARE(second.blobsWritten, size_t(0));
    QCOMPARE(second.blobsUnchanged, blobs);
    QCOMPARE(second.blobsRemoved, size_t(0));
    QCOMPARE(second.bytesWritten, uint64_t(0));
    std::optional<SceneState> loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(stateDifference(doc.state(), *loaded).empty());

    // One more mesh: one blob.
    mesh::ImportResult ply = importFixture("quad_and_triangle.ply");
    QVERIFY2(ply.ok(), ply.error.c_str());
    ops::addImportedMesh(doc, std::move(*ply.mesh), "ply", "ply", ply.report);
    SaveReport third;
    QVERIFY2(saveScene(doc.state(), p, error, &third), error.c_str());
    QVERIFY(third.incremental);
    QCOMPARE(third.blobsWritten, size_t(1));
    QCOMPARE(third.blobsUnchanged, blobs);
    QVERIFY(third.bytesWritten > 0 && third.bytesWritten < 10000);
    QCOMPARE(blobKeyCount(p), int(blobs) + 1);

    // An asset and the entities showing it go: its blob is removed.
    {
      const AssetId gone = doc.state().find(doc.state().findByName("textured_quad.glb"))->mesh->mesh;
      Edit e(doc, "Delete asset");
      for (const auto& [id, ent] : doc.state().entities)
        if (ent.mesh && ent.mesh->mesh == gone) e.removeEntity(id);
      e.removeAsset(gone);
      QVERIFY(e.commit());
    }
    QVERIFY(doc.state().validate().empty());
    SaveReport fourth;
    QVERIFY2(saveScene(doc.state(), p, error, &fourth), error.c_str());
    QCOMPARE(fourth.blobsWritten, size_t(0));
    QCOMPARE(fourth.blobsRemoved, size_t(1));
    QCOMPARE(fourth.blobsUnchanged, blobs);
    QCOMPARE(blobKeyCount(p), int(blobs));
    loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(stateDifference(doc.state(), *loaded).empty());
    // Undo brings the asset back; the next save writes it again.
    doc.undoStack()->undo();
    SaveReport fifth;
    QVERIFY2(saveScene(doc.state(), p, error, &fifth), error.c_str());
    QCOMPARE(fifth.blobsWritten, size_t(1));
    loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(stateDifference(doc.state(), *loaded).empty());
  }

  // A textured mesh's LOD levels keep its material list without copies of
  // its textures (meshproc/lod_chain.h): such a scene saves and opens again
  // (it was written and then refused as "texture index out of bounds").
  void texturedAssetWithLodsOpensAgain() {
    mesh::MeshData base = mesh::gridPlane(4.0f, 8);
    base.textures.push_back(mesh::Texture{"checks", {}, 2, 2, std::vector<uint8_t>(16, 200)});
    base.materials = {{"tex", glm::vec4(1.0f), 0}};
    for (mesh::Submesh& sm : base.submeshes) sm.material = 0;
    mesh::MeshData level = base;
    level.textures.clear();  // as buildLodChain leaves its levels
    level.indices.resize(level.indices.size() / 2);
    level.submeshes = {{0, uint32_t(level.indices.size()), 0}};
    SceneState s;
    MeshAsset a;
    a.id = 1;
    a.name = "Textured";
    a.contentHash = mesh::contentHash(base);
    a.data = std::make_shared<const mesh::MeshData>(base);
    MeshLod lod;
    lod.contentHash = mesh::contentHash(level);
    lod.triangles = level.triangleCount();
    lod.hausdorff = 0.1;
    lod.data = std::make_shared<const mesh::MeshData>(level);
    a.lods.push_back(lod);
    s.assets.emplace(a.id, a);
    addMeshMaterials(s, a.id);
    const std::string p = path("textured_lods.hscene");
    std::string error;
    QVERIFY2(saveScene(s, p, error), error.c_str());
    const auto loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    QCOMPARE(loaded->findAsset(1)->lods.size(), size_t(1));
    QCOMPARE(loaded->findAsset(1)->lods[0].data->materials[0].diffuseTexture, 0);
    // A level naming a texture its base does not have either is still refused.
    const std::vector<uint8_t> blob = encodeMesh(level);
    QVERIFY(!decodeMesh(blob.data(), blob.size(), "level", error, 0));
    QVERIFY(decodeMesh(blob.data(), blob.size(), "level", error, 1));
  }

  void saveAsToANewPath() {
    std::string error;
    const std::string first = path("first.hscene"), second = path("second.hscene");
    QVERIFY2(saveScene(rich_, first, error), error.c_str());
    const std::string firstBytes = readFile(first);
    Document doc;
    QVERIFY2(openInto(doc, first, error), error.c_str());
    QVERIFY(ops::rename(doc, doc.state().findByName("Main Camera"), "Shot 1"));
    SaveReport report;
    QVERIFY2(saveScene(doc.state(), second, error, &report), error.c_str());
    QVERIFY(!report.incremental);
    QCOMPARE(report.blobsWritten, assetBlobs(rich_));  // a new file holds every blob
    doc.setFilePath(QString::fromStdString(second));
    QCOMPARE(readFile(first), firstBytes);  // the original is untouched
    std::optional<SceneState> a = loadScene(first, error), b = loadScene(second, error);
    QVERIFY(a && b);
    QVERIFY(stateDifference(rich_, *a).empty());
    QVERIFY(stateDifference(doc.state(), *b).empty());
    QVERIFY(b->findByName("Shot 1") != kNoEntity && a->findByName("Shot 1") == kNoEntity);
  }

  // ---- bad files: each refused, the open document untouched ---------------------------

  void corruptedInTheMiddle() {
    // 8 KB of garbage over the middle of a real saved file (the bunny's blob lives there).
    const std::string p = copyOfGood("corrupted.hscene");
    std::string bytes = readFile(p);
    std::mt19937 rng(99);
    for (size_t i = bytes.size() / 2; i < bytes.size() / 2 + 8192; ++i) bytes[i] = char(rng() & 0xff);
    writeFile(p, bytes);
    expectRefused(p, {"damaged"});
  }

  void corruptedTablePages() {
    // Garbage over the pages after the header page: SQLite's own structure is broken.
    const std::string p = copyOfGood("corrupted_pages.hscene");
    std::string bytes = readFile(p);
    for (size_t i = 4096; i < 4 * 4096 && i < bytes.size(); ++i) bytes[i] = char(0x5a ^ (i & 0xff));
    writeFile(p, bytes);
    expectRefused(p, {"damaged"});
  }

  void truncated() {
    const std::string p = copyOfGood("truncated.hscene");
    const std::string bytes = readFile(p);
    writeFile(p, bytes.substr(0, bytes.size() / 2));
    expectRefused(p, {"damaged"});
  }

  // Cut at two dozen lengths, page boundaries among them: SQLite reads the
  // pages past the end as zeros without a word, so what catches the damage
  // is ours (blob checksums, the description's parse); never a partial
  // scene.
  void cutAtManyLengths() {
    const std::string bytes = readFile(goodFile_);
    QVERIFY(bytes.size() > 100000);
    std::vector<size_t> cuts = hs::test::cutLengths(bytes.size(), bytes.size() / 20);
    for (size_t page : {size_t(4096), size_t(8192), bytes.size() / 4096 / 2 * 4096, bytes.size() / 4096 * 4096 - 4096})
      cuts.push_back(page);
    const std::string p = path("cut.hscene");
    for (size_t n : cuts) {
      writeFile(p, bytes.substr(0, n));
      qInfo("cut at byte %zu of %zu:", n, bytes.size());
      expectRefused(p, {});
    }
  }

  // Another program cuts the file and writes it back while it is opened
  // again and again: every load gives the whole scene or an error naming
  // the file. (SQLite reads with pread, never a mapping, so no SIGBUS;
  // SqliteDb turns mapping off even where a build would have it on.)
  void shrinkingAndGrowingWhileLoaded() {
    const std::string p = copyOfGood("flapping.hscene");
    const std::string bytes = readFile(p);
    size_t errors = 0, wholes = 0;
    {
      hs::test::ShrinkAndGrow flapping(p, bytes, bytes.size() / 2 + 1000);
      QVERIFY(flapping.started());
      for (int i = 0; i < 20; ++i) {
        std::string error;
        const std::optional<SceneState> loaded = loadScene(p, error);
        if (!loaded) {
          QVERIFY2(error.find(p) != std::string::npos, error.c_str());
          ++errors;
          continue;
        }
        const std::string diff = stateDifference(rich_, *loaded);
        QVERIFY2(diff.empty(), diff.c_str());
        ++wholes;
      }
      qInfo("20 loads while the file was cut and rewritten %zu times: %zu errors, %zu whole", flapping.cycles(),
            errors, wholes);
    }
  }

  // The mesh blob cut at every length: an error naming the blob, every time.
  void meshBlobCutAtEveryLength() {
    const mesh::ImportResult quad = mesh::importMesh(kMeshData + "/textured_quad.obj");
    QVERIFY2(quad.ok(), quad.error.c_str());
    QCOMPARE(quad.mesh->textures.size(), size_t(1));
    const std::vector<uint8_t> blob = encodeMesh(*quad.mesh);
    std::string error;
    const auto whole = decodeMesh(blob.data(), blob.size(), "mesh asset 7", error);
    QVERIFY2(whole && meshDifference(*whole, *quad.mesh).empty(), error.c_str());
    for (size_t n : hs::test::cutLengths(blob.size(), 1)) {
      // A copy of exactly n bytes, so reading past them is a reading error.
      const std::vector<uint8_t> cut(blob.begin(), blob.begin() + long(n));
      error.clear();
      QVERIFY2(!decodeMesh(cut.data(), cut.size(), "mesh asset 7", error), qPrintable(QString("cut at %1 decoded").arg(n)));
      QVERIFY2(error.rfind("mesh asset 7: ", 0) == 0, error.c_str());
    }
  }

  void newerFormatVersion() {
    const std::string p = copyOfGood("newer.hscene");
    sql(p, "UPDATE meta SET value = '99' WHERE key = 'format_version'");
    QCOMPARE(sceneFileVersion(p), 99);
    expectRefused(p, {"newer", "99"});
  }

  void sqliteDatabaseThatIsNotAScene() {
    const std::string p = path("other.sqlite");
    sqlite3* db = nullptr;
    QCOMPARE(sqlite3_open(p.c_str(), &db), SQLITE_OK);
    QCOMPARE(sqlite3_exec(db, "CREATE TABLE photos(id INTEGER, name TEXT); INSERT INTO photos VALUES (1, 'x');", nullptr,
                          nullptr, nullptr),
             SQLITE_OK);
    sqlite3_close(db);
    QCOMPARE(sceneFileVersion(p), 0);
    expectRefused(p, {"not a Hybridscape scene"});
  }

  void notAnSqliteFile_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<QByteArray>("bytes");
    QTest::newRow("png") << "picture.hscene" << QByteArray::fromStdString(readFile(kMeshData + "/checker_4x2.png"));
    QTest::newRow("text") << "notes.hscene" << QByteArray("This is a text file, not a scene.\n");
    QTest::newRow("short") << "short.hscene" << QByteArray("SQLite format");
  }
  void notAnSqliteFile() {
    QFETCH(QString, name);
    QFETCH(QByteArray, bytes);
    const std::string p = path(name.toStdString());
    writeFile(p, bytes.toStdString());
    expectRefused(p, {"not an SQLite database"});
  }

  void emptyFile() {
    const std::string p = path("empty.hscene");
    writeFile(p, "");
    expectRefused(p, {"empty"});
  }

  void directory() {
    const std::string p = path("folder.hscene");
    fs::create_directories(p);
    expectRefused(p, {"directory"});
  }

  void missingFile() { expectRefused(path("nowhere.hscene"), {"not found"}); }

  void blobHashMismatch() {
    // One byte of the bunny's vertex data changed: still a well-formed mesh
    // blob, but not the one the description's hash names.
    const std::string p = copyOfGood("hash.hscene");
    std::vector<uint8_t> blob = readBlob(p, "mesh/1");
    QVERIFY(blob.size() > 1000);
    blob[100] ^= 0x01;  // inside the positions array
    writeBlob(p, "mesh/1", blob);
    expectRefused(p, {"mesh asset 1", "checksum"});
  }

  void blobThatIsNotAMesh() {
    const std::string p = copyOfGood("badblob.hscene");
    std::vector<uint8_t> blob = readBlob(p, "mesh/1");
    blob.resize(blob.size() / 3);  // a cut-off blob
    writeBlob(p, "mesh/1", blob);
    expectRefused(p, {"mesh asset 1", "truncated"});
  }

  void missingBlob() {
    const std::string p = copyOfGood("noblob.hscene");
    sql(p, "DELETE FROM blobs WHERE key = 'mesh/1'");
    expectRefused(p, {"mesh asset 1", "missing"});
  }

  void damagedDescription() {
    const std::string p = copyOfGood("badjson.hscene");
    sql(p, "UPDATE document SET json = substr(json, 1, 200) WHERE id = 1");
    expectRefused(p, {"description is damaged"});
  }

  void invalidDescriptionNamesThePlace() {
    const std::string p = copyOfGood("badvalue.hscene");
    // The first entity's scale becomes a string.
    sql(p, "UPDATE document SET json = json_set(json, '$.entities[0].transform.scale', 'big') WHERE id = 1");
    expectRefused(p, {"entities[0].transform.scale"});
    const std::string q = copyOfGood("cycle.hscene");
    // A root that claims a parent.
    sql(q, "UPDATE document SET json = json_set(json, '$.entities[0].parent', 3) WHERE id = 1");
    expectRefused(q, {"inconsistent hierarchy"});
  }

  // The description as the file holds it, damaged three ways: each refusal
  // names the file, what is wrong, the JSON path where there is one, and
  // the line and column in the description's text.
  void damagedDescriptionNamesThePlaceInTheText() {
    const std::string good = readDescription(goodFile_);
    QVERIFY(good.size() > 1000);

    // Cut off inside the entities: not JSON any more.
    std::string text = good.substr(0, nthOccurrence(good, "\"visible\"", 1) + 4);
    std::string p = copyOfGood("cut_description.hscene");
    writeDescription(p, text);
    expectRefused(p, {"description is damaged", lineColumnOf(text, text.size()) + ":"});

    // The second entity's scale becomes a string.
    text = good;
    const size_t scale = nthOccurrence(text, "\"scale\": [", 1);
    QVERIFY(scale != std::string::npos);
    const size_t open = text.find('[', scale), close = text.find(']', open);
    text.replace(open, close - open + 1, "\"big\"");
    p = copyOfGood("string_scale.hscene");
    writeDescription(p, text);
    expectRefused(p, {"invalid", "entities[1].transform.scale (" + lineColumnOf(text, open) + "): expected [x, y, z], not a string"});

    // A key twice in one entity.
    text = good;
    const size_t visible = nthOccurrence(text, "\"visible\": true", 0);
    QVERIFY(visible != std::string::npos);
    text.insert(visible, "\"visible\": false, ");
    const size_t second = visible + std::string("\"visible\": false, ").size();
    p = copyOfGood("duplicate_key.hscene");
    writeDescription(p, text);
    expectRefused(p, {"description is damaged", lineColumnOf(text, second) + ": duplicate key \"visible\" in entities[0]"});

    // Valid JSON of the wrong shape: a reader's message, not a parser's.
    p = copyOfGood("array_description.hscene");
    writeDescription(p, "[]");
    expectRefused(p, {"invalid", "line 1, column 1: expected an object, not an array"});
  }

  // Format versions that are no int: far in the future is "newer" with the
  // number as written (it was "version -1"); text that is no number is invalid.
  void formatVersionsBeyondAnInt() {
    std::string p = copyOfGood("far_future.hscene");
    sql(p, "UPDATE meta SET value = '999999999999999999999' WHERE key = 'format_version'");
    expectRefused(p, {"newer", "scene format 999999999999999999999;"});
    p = copyOfGood("version_text.hscene");
    sql(p, "UPDATE meta SET value = '4x' WHERE key = 'format_version'");
    expectRefused(p, {"invalid scene format version '4x'"});
    p = copyOfGood("version_negative.hscene");
    sql(p, "UPDATE meta SET value = '-99999999999999999999' WHERE key = 'format_version'");
    expectRefused(p, {"invalid scene format version '-99999999999999999999'"});
  }

  // ---- saves that fail leave what was there ---------------------------------------------

  void saveToADirectoryPath() {
    const std::string dir = path("a_folder.hscene");
    fs::create_directories(dir);
    writeFile(dir + "/keep.txt", "keep me");
    std::string error;
    QVERIFY(!saveScene(rich_, dir, error));
    QVERIFY2(error.find(dir) != std::string::npos && error.find("directory") != std::string::npos, error.c_str());
    QVERIFY(fs::is_directory(dir));
    QCOMPARE(readFile(dir + "/keep.txt"), std::string("keep me"));
    QCOMPARE(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), std::ptrdiff_t(1));
  }

  void saveIntoAFolderThatCannotHoldIt_data() {
    QTest::addColumn<QString>("target");
    // /proc takes no new files, whoever asks (root included).
    QTest::newRow("unwritable folder") << "/proc/hybridscape-test.hscene";
    QTest::newRow("missing folder") << QString::fromStdString(path("no/such/folder/x.hscene"));
    QTest::newRow("folder is a file") << QString::fromStdString(path("plain.txt/x.hscene"));
  }
  void saveIntoAFolderThatCannotHoldIt() {
    QFETCH(QString, target);
    writeFile(path("plain.txt"), "plain");
    const std::string p = target.toStdString();
    std::string error;
    QVERIFY(!saveScene(rich_, p, error));
    QVERIFY2(error.find(p) != std::string::npos, error.c_str());
    QVERIFY(error.find('\n') == std::string::npos);
    std::error_code ec;
    QVERIFY(!fs::exists(p, ec));
    QCOMPARE(readFile(path("plain.txt")), std::string("plain"));
  }

  void failedSaveKeepsThePreviousFile_data() {
    QTest::addColumn<bool>("overCurrentScene");
    QTest::newRow("in place, over a scene") << true;
    QTest::newRow("new file, over something else") << false;
  }
  void failedSaveKeepsThePreviousFile() {
    // The disk fills up in the middle of a save (a file size limit, which
    // binds root too): the save fails and the file that was there is intact.
    QFETCH(bool, overCurrentScene);
    const std::string p = path(overCurrentScene ? "full_disk.hscene" : "full_disk_other.hscene");
    std::string error;
    if (overCurrentScene) {
      SceneState small = buildStarterScene();
      QVERIFY2(saveScene(small, p, error), error.c_str());
    } else {
      writeFile(p, "an older file that is not a current scene\n");
    }
    const std::string before = readFile(p);
    bool saved = true;
    {
      FileSizeLimit limit(before.size() + 64 * 1024);  // far less than the bunny's blob
      QVERIFY(limit.ok());
      saved = saveScene(rich_, p, error);
    }
    QVERIFY2(!saved, "the save should have run out of space");
    QVERIFY2(error.find(p) != std::string::npos, error.c_str());
    qInfo("failed as expected: %s", error.c_str());
    QCOMPARE(readFile(p), before);
    // Nothing left beside it: no temporary, no journal.
    for (const auto& entry : fs::directory_iterator(tmp_.path().toStdString())) {
      const std::string name = entry.path().filename().string();
      QVERIFY2(name.find(".saving-") == std::string::npos && name.find("-journal") == std::string::npos, name.c_str());
    }
    if (overCurrentScene) {
      std::optional<SceneState> still = loadScene(p, error);
      QVERIFY2(still, error.c_str());
      QCOMPARE(canonicalJson(*still), canonicalJson(buildStarterScene()));
    }
    // With room again the same save works.
    QVERIFY2(saveScene(rich_, p, error), error.c_str());
    std::optional<SceneState> now = loadScene(p, error);
    QVERIFY2(now, error.c_str());
    QVERIFY(stateDifference(rich_, *now).empty());
  }
};

QTEST_GUILESS_MAIN(TestHsceneFile)
#include "test_hscene_file.moc"
