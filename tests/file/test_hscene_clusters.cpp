// Cluster hierarchies of huge scans in the document and the .hscene file
// (issue 38 item 2; scene/cluster_asset.h, scene/cluster_file.h): an import
// with --clusters carries the hierarchy and a coarse cut as one undo step;
// its pages are blobs keyed by content hash, written once and never again
// when unchanged, read on demand after opening (a damaged page does not stop
// a scene from opening: the page names itself when read); a damaged index or
// one whose errors are not monotonic drops the hierarchy with a warning
// naming the asset and the rest opens; an undo can bring back an asset whose
// pages a save no longer needed; the build gives the same blobs on any
// thread count; `import --clusters` and `info` reach it from the CLI; a
// streamed (out-of-core) build from tile files lands the same way.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>

#include "cli_runner.h"
#include "dead_scratch.h"
#include "file_bytes.h"
#include "hscene_sql.h"
#include "core/content_hash.h"
#include "core/json.h"
#include "core/scratch_files.h"
#include "scene/cluster_asset.h"
#include "scene/document.h"
#include "scene/edit.h"
#include "scene/hscene_file.h"
#include "scene/hscene_repair.h"
#include "scene/import_pipeline.h"
#include "mesh/mesh_import.h"
#include "scene/operations.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;
using hs::test::readBlob;
using hs::test::writeBlob;

namespace {

const std::string kBunny = HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj";

ImportedMesh clusteredBunny(unsigned threads = 0) {
  MeshImportRequest r;
  r.files = {kBunny};
  r.clusters = MeshImportRequest::Clusters::On;
  r.clusterOptions.threads = threads;
  return importMeshFiles(r);
}

uint64_t indexHash(const ClusterAsset& c) {
  const std::vector<uint8_t> bytes = encodeClusterAssetIndex(c);
  return contentHash(bytes.data(), bytes.size());
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

}  // namespace

class TestHsceneClusters : public QObject {
  Q_OBJECT
  QTemporaryDir tmp_;
  Document doc_;
  EntityId bunny_ = kNoEntity;
  std::vector<std::vector<uint8_t>> pages_;  // the fresh import's pages, read before any save
  size_t bunnyTriangles_ = 0;

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }
  const MeshAsset& asset(const SceneState& s) const { return *s.findAsset(s.find(bunny_)->mesh->mesh); }
  std::string saved(const std::string& name, SaveReport* report = nullptr) {
    std::string error;
    const std::string p = path(name);
    if (!saveScene(doc_.state(), p, error, report)) qFatal("%s", error.c_str());
    return p;
  }
  // A saved copy to damage: doc_'s pages are read from the last file saved,
  // which stays whole.
  std::string copyToDamage(const std::string& name) {
    const std::string whole = saved(name + ".whole.hscene"), p = path(name);
    fs::copy_file(whole, p, fs::copy_options::overwrite_existing);
    return p;
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    ImportedMesh m = clusteredBunny();
    QVERIFY2(m.ok(), m.error.c_str());
    QVERIFY(m.clusters);
    bunnyTriangles_ = m.clusterReport.trianglesPerLevel.front();
    const auto& c = *m.clusters;
    for (uint32_t p = 0; p < c.pages->pageCount(); ++p) {
      std::string e;
      auto bytes = c.pages->read(p, e);
      QVERIFY2(bytes, e.c_str());
      pages_.push_back(std::move(*bytes));
    }
    doc_.reset(SceneState{}, QString());
    bunny_ = ops::addImportedMesh(doc_, std::move(m), "Bunny", kBunny);
    QVERIFY(bunny_ != kNoEntity);
  }

  // The import: the hierarchy, its index hash, a coarse cut as the mesh.
  void importCarriesHierarchy() {
    const MeshAsset& a = asset(doc_.state());
    QVERIFY(a.clusters);
    QCOMPARE(a.clustersHash, indexHash(*a.clusters));
    QCOMPARE(a.clusters->triangles(0), bunnyTriangles_);
    QVERIFY(a.clusters->levels() >= 4);
    QVERIFY(a.clusters->pages->pageCount() >= 4);
    // The coarse cut: far fewer triangles than the scan, at most the proxy budget.
    QVERIFY(a.data->triangleCount() <= kClusterProxyTriangles);
    QVERIFY(a.data->triangleCount() < bunnyTriangles_);
    QVERIFY(a.data->triangleCount() > 0);
    QVERIFY(a.lods.empty());
    // Pages held in memory until the first save.
    QVERIFY(a.clusters->pages->memoryBytes() > 0);
    QVERIFY(a.clusters->pages->file().empty());
    // Every page decodes and holds the clusters the index says.
    size_t triangles = 0;
    for (uint32_t p = 0; p < a.clusters->pages->pageCount(); ++p) {
      std::string e;
      auto clusters = a.clusters->loadPage(p, "bunny", e);
      QVERIFY2(clusters, e.c_str());
      for (const auto& c : *clusters) triangles += c.triangles.size() / 3;
    }
    size_t indexed = 0;
    for (const auto& c : a.clusters->index.clusters) indexed += c.triangleCount;
    QCOMPARE(triangles, indexed);
  }

  // Saved once: every page written; again: none; the store reads from the
  // file from then on and lets its memory go.
  void savesPagesOnce() {
    SaveReport first, second;
    const std::string p = saved("once.hscene", &first);
    const MeshAsset& a = asset(doc_.state());
    QCOMPARE(first.pagesWritten, a.clusters->pages->pageCount());
    QCOMPARE(first.pagesUnchanged, size_t(0));
    QCOMPARE(a.clusters->pages->memoryBytes(), uint64_t(0));
    QCOMPARE(fs::path(a.clusters->pages->file()), fs::weakly_canonical(p));
    {
      Edit e(doc_, "Rename");
      e.entity(bunny_).name = "Bunny renamed";
      e.commit();
    }
    saved("once.hscene", &second);
    QVERIFY(second.incremental);
    QCOMPARE(second.pagesWritten, size_t(0));
    QCOMPARE(second.pagesUnchanged, a.clusters->pages->pageCount());
    // Pages read back from the file are the pages the build made.
    for (uint32_t k = 0; k < a.clusters->pages->pageCount(); ++k) {
      std::string e;
      auto bytes = a.clusters->pages->read(k, e);
      QVERIFY2(bytes, e.c_str());
      QVERIFY(*bytes == pages_[k]);
    }
  }

  // Opening reads the index, not the pages; the loaded asset is the saved one.
  void opensWithoutReadingPages() {
    const std::string p = copyToDamage("lazy.hscene");
    // Damage a page: the file still opens without a word, since no page is read.
    const MeshAsset& a = asset(doc_.state());
    const uint64_t h = a.clusters->pages->pageHash(2);
    std::vector<uint8_t> bytes = readBlob(p, clusterBlobKey(h));
    bytes.resize(bytes.size() / 2);
    writeBlob(p, clusterBlobKey(h), bytes);
    std::string error;
    LoadReport report;
    auto loaded = loadScene(p, error, nullptr, &report);
    QVERIFY2(loaded, error.c_str());
    QVERIFY2(report.warnings.empty(), joined(report.warnings).c_str());
    const MeshAsset& b = asset(*loaded);
    QVERIFY(b.clusters);
    QCOMPARE(b.clustersHash, a.clustersHash);
    QVERIFY(encodeClusterAssetIndex(*b.clusters) == encodeClusterAssetIndex(*a.clusters));
    QCOMPARE(b.clusters->pages->memoryBytes(), uint64_t(0));
    // The damaged page names the file and itself when read; the others load.
    std::string e;
    QVERIFY(!b.clusters->loadPage(2, "asset 'Bunny'", e));
    QVERIFY2(contains(e, p) && contains(e, "cluster page 2") && contains(e, "checksum"), e.c_str());
    QVERIFY2(b.clusters->loadPage(1, "asset 'Bunny'", e), e.c_str());
    QVERIFY(b.data && b.data->triangleCount() == a.data->triangleCount());
  }

  void missingPageIsReported() {
    const std::string p = copyToDamage("missing.hscene");
    const MeshAsset& a = asset(doc_.state());
    hs::test::sql(p, "DELETE FROM blobs WHERE key = '" + clusterBlobKey(a.clusters->pages->pageHash(3)) + "'");
    std::string error;
    LoadReport report;
    auto loaded = loadScene(p, error, nullptr, &report);
    QVERIFY2(loaded, error.c_str());
    const std::string w = joined(report.warnings);
    QVERIFY2(contains(w, "'Bunny'") && contains(w, "1 of its") && contains(w, "page 3"), w.c_str());
    std::string e;
    QVERIFY(!asset(*loaded).clusters->loadPage(3, "bunny", e));
    QVERIFY2(contains(e, "missing"), e.c_str());
  }

  // A damaged index: the hierarchy is dropped with a warning naming the
  // asset; the asset, its coarse mesh and the rest of the scene open.
  void damagedIndexDropsHierarchy() {
    const std::string p = copyToDamage("index.hscene");
    const MeshAsset& a = asset(doc_.state());
    std::vector<uint8_t> bytes = readBlob(p, clusterIndexBlobKey(a.clustersHash));
    bytes.resize(bytes.size() - 7);
    writeBlob(p, clusterIndexBlobKey(a.clustersHash), bytes);
    std::string error;
    LoadReport report;
    auto loaded = loadScene(p, error, nullptr, &report);
    QVERIFY2(loaded, error.c_str());
    const std::string w = joined(report.warnings);
    QVERIFY2(contains(w, "mesh asset") && contains(w, "'Bunny'") && contains(w, "cluster index"), w.c_str());
    QVERIFY(!asset(*loaded).clusters);
    QCOMPARE(asset(*loaded).clustersHash, uint64_t(0));
    QVERIFY(asset(*loaded).data->triangleCount() == a.data->triangleCount());
    QCOMPARE(loaded->entities.size(), doc_.state().entities.size());
  }

  // An index whose errors are not monotonic (a cluster coarser than its
  // parent says) is refused the same way, naming the cluster.
  void nonMonotonicIndexDropsHierarchy() {
    SceneState s = doc_.state();
    MeshAsset& a = s.assets.at(asset(s).id);
    ClusterAsset broken = *a.clusters;
    size_t victim = 0;
    while (!std::isfinite(broken.index.clusters[victim].parentError)) ++victim;
    broken.index.clusters[victim].error = broken.index.clusters[victim].parentError * 2.0f + 1.0f;
    a.clusters = std::make_shared<const ClusterAsset>(broken);
    a.clustersHash = indexHash(broken);
    std::string error;
    const std::string p = path("monotonic.hscene");
    QVERIFY2(saveScene(s, p, error), error.c_str());
    LoadReport report;
    auto loaded = loadScene(p, error, nullptr, &report);
    QVERIFY2(loaded, error.c_str());
    const std::string w = joined(report.warnings);
    QVERIFY2(contains(w, "'Bunny'") && contains(w, "cluster " + std::to_string(victim)), w.c_str());
    QVERIFY(!asset(*loaded).clusters);
  }

  // Deleting the asset and saving keeps its pages while undo can bring it
  // back; with no undo left, the next save removes them.
  void undoKeepsPages() {
    Document doc;
    std::string error;
    const std::string p = saved("undo.hscene");
    saved("undo_elsewhere.hscene");  // doc_'s own pages are read from there now, not from p
    auto loaded = loadScene(p, error);
    QVERIFY2(loaded, error.c_str());
    doc.reset(std::move(*loaded), QString::fromStdString(p));
    const AssetId id = asset(doc.state()).id;
    const size_t pages = asset(doc.state()).clusters->pages->pageCount();
    {
      Edit e(doc, "Delete");
      e.removeEntity(bunny_);
      e.removeAsset(id);
      e.commit();
    }
    QVERIFY(!doc.state().findAsset(id));
    SaveReport kept;
    QVERIFY2(saveScene(doc.state(), p, error, &kept), error.c_str());
    QCOMPARE(kept.pagesKept, pages);
    QCOMPARE(kept.pagesRemoved, size_t(0));
    doc.undoStack()->undo();
    const MeshAsset* back = doc.state().findAsset(id);
    QVERIFY(back && back->clusters);
    for (uint32_t k = 0; k < pages; ++k) {
      std::string e;
      QVERIFY2(back->clusters->loadPage(k, "bunny", e), e.c_str());
    }
    doc.undoStack()->redo();
    doc.undoStack()->clear();
    SaveReport removed;
    QVERIFY2(saveScene(doc.state(), p, error, &removed), error.c_str());
    QCOMPARE(removed.pagesKept, size_t(0));
    QCOMPARE(removed.pagesRemoved, pages);
    QCOMPARE(hs::test::countBlobKeys(p, "key LIKE 'clusters/%'"), 0);
  }

  // Save As: the pages are copied from the file they are read from.
  void saveAsCopiesPages() {
    const std::string first = saved("first.hscene");
    SaveReport r;
    const std::string second = saved("second.hscene", &r);
    QCOMPARE(r.pagesWritten, asset(doc_.state()).clusters->pages->pageCount());
    fs::remove(first);
    std::string error;
    auto loaded = loadScene(second, error);
    QVERIFY2(loaded, error.c_str());
    for (uint32_t k = 0; k < asset(*loaded).clusters->pages->pageCount(); ++k) {
      std::string e;
      auto bytes = asset(*loaded).clusters->pages->read(k, e);
      QVERIFY2(bytes && *bytes == pages_[k], e.c_str());
    }
  }

  // Repair reads every page: a damaged one drops the hierarchy (noted),
  // the asset and its coarse mesh stay.
  void repairDropsDamagedHierarchy() {
    const std::string p = copyToDamage("repair.hscene");
    const uint64_t h = asset(doc_.state()).clusters->pages->pageHash(1);
    std::vector<uint8_t> bytes = readBlob(p, clusterBlobKey(h));
    bytes[bytes.size() / 2] ^= 0x5a;
    writeBlob(p, clusterBlobKey(h), bytes);
    RepairReport r;
    std::string error;
    const std::string out = path("repaired.hscene");
    QVERIFY2(repairScene(p, out, r, error), error.c_str());
    const std::string dropped = joined(r.dropped);
    QVERIFY2(contains(dropped, "'Bunny'") && contains(dropped, "cluster hierarchy") && contains(dropped, "page 1"),
             dropped.c_str());
    auto loaded = loadScene(out, error);
    QVERIFY2(loaded, error.c_str());
    QVERIFY(!asset(*loaded).clusters);
    QVERIFY(asset(*loaded).data->triangleCount() > 0);
  }

  // The same blobs from any thread count (and any run).
  void buildIsDeterministic() {
    const ImportedMesh one = clusteredBunny(1), two = clusteredBunny(2);
    QVERIFY(one.ok() && two.ok());
    QCOMPARE(one.clustersHash, two.clustersHash);
    QCOMPARE(one.clustersHash, asset(doc_.state()).clustersHash);
    QVERIFY(one.clusters->pages->pageHashes() == two.clusters->pages->pageHashes());
    QCOMPARE(contentHash(*one.mesh), contentHash(*two.mesh));
  }

  // Auto leaves small meshes alone; On refuses a mesh of several materials.
  void autoAndRefusal() {
    MeshImportRequest r;
    r.files = {kBunny};
    const ImportedMesh plain = importMeshFiles(r);
    QVERIFY(plain.ok());
    QVERIFY(!plain.clusters);
    // Two triangles, each with a material of its own.
    const std::string obj = path("two_materials.obj");
    test::writeFile(path("two_materials.mtl"), "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    test::writeFile(obj, "mtllib two_materials.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "usemtl red\nf 1 2 3\nusemtl blue\nf 1 3 4\n");
    r.files = {obj};
    r.clusters = MeshImportRequest::Clusters::On;
    const ImportedMesh refused = importMeshFiles(r);
    QVERIFY(!refused.ok());
    QVERIFY2(contains(refused.error, "one material"), refused.error.c_str());
  }

  // The CLI: import --clusters on, then info (text and JSON).
  void cliImportAndInfo() {
    const QString scene = QString::fromStdString(path("cli.hscene"));
    QCOMPARE(test::runCli({"new", scene}, tmp_.path()).code, 0);
    test::CliRun c = test::runCli({"import", QString::fromStdString(kBunny), scene, "--clusters", "on"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("cluster hierarchy:") && c.out.contains(QString::number(bunnyTriangles_)),
             qPrintable(c.out));
    c = test::runCli({"info", scene}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("Cluster hierarchy:") && c.out.contains("per level:"), qPrintable(c.out));
    c = test::runCli({"info", scene, "--json"}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json info = Json::parse(c.out.toStdString());
    const Json& clusters = info.at("assets").at(0).at("clusters");
    QCOMPARE(clusters.at("triangles").get<size_t>(), bunnyTriangles_);
    QCOMPARE(clusters.at("levels").get<size_t>(), asset(doc_.state()).clusters->levels());
    QCOMPARE(clusters.at("pages").get<size_t>(), asset(doc_.state()).clusters->pages->pageCount());
    QCOMPARE(clusters.at("pages_in_memory_bytes").get<size_t>(), size_t(0));
    // A render waits for the cut's pages and says what it drew.
    const QString png = QString::fromStdString(path("cli.png")), stats = QString::fromStdString(path("cli.json"));
    c = test::runCli({"render", scene, "--out", png, "--size", "160x120", "--stats", stats}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json frame = Json::parse(hs::test::readFile(stats.toStdString()));
    QVERIFY2(frame.at("clusters").is_object(), frame.dump().c_str());
    QCOMPARE(frame.at("clusters").at("instances").get<size_t>(), size_t(1));
    QVERIFY(frame.at("clusters").at("complete").get<bool>());
    QCOMPARE(frame.at("clusters").at("pages_wanted").get<size_t>(), size_t(0));
    c = test::runCli({"import", QString::fromStdString(kBunny), scene, "--clusters", "sometimes"}, tmp_.path());
    QVERIFY(c.code != 0);
    QVERIFY2(c.err.contains("--clusters"), qPrintable(c.err));
  }

  // --clusters streamed: the bunny as two tile files (split by the side of
  // their centre, each file in its own coordinates as a reader recentres
  // them) built out of core; its pages in a scratch file beside the scene
  // until the save takes them; the scene reopens and renders the whole
  // cut. Processing options are refused with it.
  void streamedImport() {
    const mesh::ImportResult bunny = mesh::importMesh(kBunny);
    QVERIFY(bunny.mesh);
    const mesh::MeshData& m = *bunny.mesh;
    std::string tile[2];
    size_t triangles = 0;
    for (size_t f = 0; f < m.triangleCount(); ++f) {
      glm::vec3 c(0.0f);
      for (int k = 0; k < 3; ++k) c += m.positions[m.indices[f * 3 + size_t(k)]];
      std::string& t = tile[c.x < 0.0f ? 0 : 1];
      t += "f";
      for (int k = 0; k < 3; ++k) t += " " + std::to_string(m.indices[f * 3 + size_t(k)] + 1);
      t += "\n";
      ++triangles;
    }
    std::string vertices;
    char line[96];
    for (const glm::vec3& p : m.positions) {
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z));
      vertices += line;
    }
    const fs::path dir = fs::path(tmp_.path().toStdString()) / "streamed";
    fs::create_directories(dir);
    test::writeFile((dir / "a.obj").string(), vertices + tile[0]);
    test::writeFile((dir / "b.obj").string(), vertices + tile[1]);

    MeshImportRequest r;
    r.files = {(dir / "a.obj").string(), (dir / "b.obj").string()};
    r.clusters = MeshImportRequest::Clusters::Streamed;
    r.scratchDir = dir.string();
    ImportedMesh imported = importMeshFiles(r);
    QVERIFY2(imported.ok(), imported.error.c_str());
    QVERIFY(imported.clusters && imported.streamed);
    QCOMPARE(imported.streamed->tiles, size_t(2));
    QCOMPARE(imported.clusters->triangles(0), triangles);
    QCOMPARE(imported.tiles.size(), size_t(2));
    QVERIFY(imported.clusters->pages->memoryBytes() == 0);
    QVERIFY(imported.clusters->pages->scratchBytes() > 0);
    QVERIFY(imported.mesh->triangleCount() > 0 && imported.mesh->triangleCount() <= kClusterProxyTriangles);
    auto scratchFiles = [&] {
      size_t n = 0;
      for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().rfind("hs-", 0) == 0;
      return n;
    };
    QCOMPARE(scratchFiles(), size_t(1));  // the page file; the build's cell files are gone
    // A tile that cannot be read stops the build with the reader's message
    // naming it, and leaves nothing behind; the build first sweeps a page
    // file that a dead process on this machine never handed to a save.
    {
      const std::string stale = test::asDeadProcess(scratchName("hs-cluster-pages-", ".bin")).name;
      QVERIFY(!stale.empty());
      test::writeFile((dir / stale).string(), "pages of a killed import");
      QCOMPARE(scratchFiles(), size_t(2));
      const std::string bad = (dir / "bad.ply").string();
      test::writeFile(bad, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                           "\x01\x02");
      MeshImportRequest broken = r;
      broken.files = {r.files[0], bad};
      const ImportedMesh failed = importMeshFiles(broken);
      QVERIFY(!failed.ok());
      QVERIFY2(contains(failed.error, "bad.ply"), failed.error.c_str());
      QCOMPARE(scratchFiles(), size_t(1));  // still only the good import's page file
      fs::remove(bad);
    }
    Document doc;
    doc.reset(SceneState{}, QString());
    const EntityId id = ops::addImportedMesh(doc, std::move(imported), "Streamed bunny", r.files.front());
    std::string error;
    const std::string file = (dir / "streamed.hscene").string();
    QVERIFY2(saveScene(doc.state(), file, error), error.c_str());
    QCOMPARE(scratchFiles(), size_t(0));  // the save took the pages
    const auto loaded = loadScene(file, error);
    QVERIFY2(loaded, error.c_str());
    const MeshAsset& a = *loaded->findAsset(loaded->find(id)->mesh->mesh);
    QVERIFY(a.clusters);
    QCOMPARE(a.clusters->triangles(0), triangles);

    // The same from the CLI, then a render of the whole cut.
    const QString scene = QString::fromStdString((dir / "cli.hscene").string());
    QCOMPARE(test::runCli({"new", scene}, tmp_.path()).code, 0);
    test::CliRun c = test::runCli({"import", QString::fromStdString(r.files[0]), QString::fromStdString(r.files[1]),
                                   scene, "--clusters", "streamed"},
                                  tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("built out of core") && c.out.contains(QString::number(triangles)), qPrintable(c.out));
    const QString stats = QString::fromStdString((dir / "cli.json").string());
    c = test::runCli({"render", scene, "--out", QString::fromStdString((dir / "cli.png").string()), "--size",
                      "160x120", "--stats", stats},
                     tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    const Json frame = Json::parse(hs::test::readFile(stats.toStdString()));
    QVERIFY(frame.at("clusters").at("complete").get<bool>());
    QVERIFY(frame.at("clusters").at("triangles").get<size_t>() > 0);
    c = test::runCli({"import", QString::fromStdString(r.files[0]), scene, "--clusters", "streamed", "--lods", "2"},
                     tmp_.path());
    QVERIFY(c.code != 0);
    QVERIFY2(c.err.contains("streamed cluster build"), qPrintable(c.err));
  }
};

QTEST_GUILESS_MAIN(TestHsceneClusters)
#include "test_hscene_clusters.moc"
