// "Save a repaired copy" (issue 10 item 1; docs/reliability.md): from a
// scene that does not open, what can still be read is saved to a new file
// and what was lost is listed; the damaged file is never written. Damaged
// fixtures are made here from a small scene: a corrupted mesh blob, a
// corrupted description, a file cut short.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <set>
#include <string>

#include "cli_runner.h"
#include "file_bytes.h"
#include "hscene_sql.h"
#include "ocio_files.h"
#include "mesh/mesh_import.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/hscene_repair.h"
#include "scene/ocio_config.h"
#include "scene/operations.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

namespace {

// Two textured quads, each its own asset and entity: a scene with blobs.
SceneState smallScene() {
  Document doc;
  doc.reset(SceneState{}, {});
  for (const char* name : {"quad", "other quad"}) {
    mesh::ImportResult r = mesh::importMesh(HS_TEST_DATA_DIR "/mesh/textured_quad.obj");
    if (!r.ok()) qFatal("%s", r.error.c_str());
    ops::addImportedMesh(doc, std::move(*r.mesh), name, "textured_quad.obj", r.report);
  }
  return doc.state();
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

}  // namespace

class TestHsceneRepair : public QObject {
  Q_OBJECT

  QTemporaryDir tmp_;
  SceneState scene_;
  std::string good_;

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }
  std::string copyOfGood(const std::string& name) {
    const std::string p = path(name);
    fs::copy_file(good_, p, fs::copy_options::overwrite_existing);
    return p;
  }
  // The asset the first entity with a mesh shows.
  AssetId firstAsset() const { return scene_.assets.begin()->first; }

  // Repairs `damaged` into `out`; checks the damaged file kept its bytes,
  // no salvage folder is left beside `out` and the copy opens; returns the
  // copy's state.
  std::optional<SceneState> repaired(const std::string& damaged, const std::string& out, RepairReport& r) {
    const std::string before = test::readFile(damaged);
    std::string error;
    const bool ok = repairScene(damaged, out, r, error);
    if (!ok) qWarning("repair refused: %s", error.c_str());
    if (test::readFile(damaged) != before) qWarning("the damaged file was written");
    if (!ok || test::readFile(damaged) != before) return std::nullopt;
    for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
      if (e.path().filename().string().find(".salvage-") != std::string::npos) {
        qWarning("the salvage folder %s was left behind", e.path().c_str());
        return std::nullopt;
      }
    std::optional<SceneState> s = loadScene(out, error);
    if (!s) qWarning("the repaired copy does not open: %s", error.c_str());
    return s;
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = smallScene();
    QCOMPARE(scene_.assets.size(), size_t(2));
    good_ = path("good.hscene");
    std::string error;
    QVERIFY2(saveScene(scene_, good_, error), error.c_str());
  }

  // A mesh blob with a flipped byte: the scene does not open; the copy
  // holds everything else, and the entity that showed it keeps its place.
  void corruptedBlob() {
    const std::string damaged = copyOfGood("blob.hscene");
    const AssetId lost = firstAsset();
    std::vector<uint8_t> bytes = test::readBlob(damaged, "mesh/" + std::to_string(lost));
    QVERIFY(bytes.size() > 64);
    bytes[bytes.size() / 2] ^= 0xff;
    test::writeBlob(damaged, "mesh/" + std::to_string(lost), bytes);
    std::string error;
    QVERIFY(!loadScene(damaged, error));

    RepairReport r;
    const auto s = repaired(damaged, path("blob-repaired.hscene"), r);
    QVERIFY(s);
    QVERIFY(!r.wasWhole);
    QVERIFY2(joined(r.dropped).find("mesh asset " + std::to_string(lost)) != std::string::npos, joined(r.dropped).c_str());
    // The reference: the original with that asset gone (its materials and
    // mesh textures with it) and its entity without a mesh.
    SceneState expected = scene_;
    expected.assets.erase(lost);
    std::erase_if(expected.materials, [&](const auto& m) { return m.second.asset == lost; });
    std::erase_if(expected.textures, [&](const auto& t) { return t.second.asset == lost; });
    for (auto& [id, e] : expected.entities)
      if (e.mesh && e.mesh->mesh == lost) e.mesh.reset();
    QCOMPARE(canonicalJson(*s), canonicalJson(expected));
    QCOMPARE(s->assets.size(), size_t(1));
    QCOMPARE(s->assets.begin()->second.contentHash, scene_.assets.rbegin()->second.contentHash);
  }

  // The OpenColorIO config comes through a repair whole when every file
  // verifies, and is dropped (named, the view transform off) when one
  // does not: never half a bundle.
  void anOcioConfigIsKeptOrDroppedWhole() {
    std::string error;
    const std::optional<scene::OcioConfigData> config =
        scene::readOcioConfig(test::writeStudioConfig(fs::path(path("studio"))), error);
    QVERIFY2(config, error.c_str());
    SceneState withConfig = scene_;
    withConfig.settings.post.ocioConfig = *config;
    withConfig.settings.post.viewTransform = true;
    const std::string lutKey = scene::ocioBlobKey(config->files[1].contentHash);
    for (const bool damageTheLut : {false, true}) {
      const std::string damaged = path(damageTheLut ? "ocio-lut.hscene" : "ocio-kept.hscene");
      QVERIFY2(saveScene(withConfig, damaged, error), error.c_str());
      const std::string meshKey = "mesh/" + std::to_string(firstAsset());
      std::vector<uint8_t> bytes = test::readBlob(damaged, meshKey);
      bytes[bytes.size() / 2] ^= 0xff;  // a damaged mesh: the scene needs repairing
      test::writeBlob(damaged, meshKey, bytes);
      if (damageTheLut) {
        std::vector<uint8_t> lut = test::readBlob(damaged, lutKey);
        lut[lut.size() / 2] ^= 0xff;
        test::writeBlob(damaged, lutKey, lut);
      }
      RepairReport r;
      const auto s = repaired(damaged, path(damageTheLut ? "ocio-lut-out.hscene" : "ocio-kept-out.hscene"), r);
      QVERIFY(s);
      const std::string dropped = joined(r.dropped);
      if (damageTheLut) {
        QVERIFY2(dropped.find("the OpenColorIO config 'studio.ocio' ('search0/film.spi1d'") != std::string::npos,
                 dropped.c_str());
        QVERIFY(s->settings.post.ocioConfig.empty() && !s->settings.post.viewTransform);
      } else {
        QVERIFY2(dropped.find("OpenColorIO") == std::string::npos, dropped.c_str());
        QVERIFY(s->settings.post.ocioConfig == *config && s->settings.post.ocioConfig.loaded());
        QVERIFY(s->settings.post.viewTransform);
      }
    }
  }

  // A description that is not JSON: the meshes still verify against the
  // hashes stored beside them and come back as entities of a starter scene.
  void corruptedDescription() {
    const std::string damaged = copyOfGood("json.hscene");
    std::string text = test::readDescription(damaged);
    QVERIFY(text.size() > 100);
    text.resize(text.size() / 2);  // cut mid-document
    test::writeDescription(damaged, text);
    std::string error;
    QVERIFY(!loadScene(damaged, error));

    RepairReport r;
    const auto s = repaired(damaged, path("json-repaired.hscene"), r);
    QVERIFY(s);
    QVERIFY2(joined(r.dropped).find("scene description") != std::string::npos, joined(r.dropped).c_str());
    std::multiset<uint64_t> want, got;
    for (const auto& [id, a] : scene_.assets) want.insert(a.contentHash);
    for (const auto& [id, a] : s->assets) {
      got.insert(a.contentHash);
      QVERIFY(a.data && mesh::contentHash(*a.data) == a.contentHash);
    }
    QVERIFY(want == got);
    int shown = 0;
    for (const auto& [id, e] : s->entities) shown += e.mesh.has_value();
    QCOMPARE(shown, 2);
  }

  // A file cut short: whatever comes back is data of the original, checked
  // by its hash (no mesh is invented), and what was lost is listed.
  void truncatedFile_data() {
    QTest::addColumn<double>("keep");
    for (double k : {0.9, 0.6, 0.3}) QTest::newRow(QByteArray::number(k)) << k;
  }
  void truncatedFile() {
    QFETCH(double, keep);
    const std::string damaged = copyOfGood("cut.hscene");
    fs::resize_file(damaged, uintmax_t(double(fs::file_size(damaged)) * keep));
    std::string error;
    QVERIFY(!loadScene(damaged, error));
    RepairReport r;
    const auto s = repaired(damaged, path("cut-repaired-" + std::to_string(int(keep * 10)) + ".hscene"), r);
    QVERIFY(s);
    QVERIFY(!r.dropped.empty());
    std::set<uint64_t> original;
    for (const auto& [id, a] : scene_.assets) original.insert(a.contentHash);
    for (const auto& [id, a] : s->assets) QVERIFY(original.count(a.contentHash));
    qInfo("cut to %.0f%%: %zu entities, %zu meshes kept; dropped:\n%s", keep * 100, s->entities.size(),
          s->assets.size(), joined(r.dropped).c_str());
  }

  void wholeFileIsCopiedAsIs() {
    RepairReport r;
    const auto s = repaired(good_, path("whole-repaired.hscene"), r);
    QVERIFY(s);
    QVERIFY(r.wasWhole);
    QVERIFY(r.dropped.empty());
    QCOMPARE(canonicalJson(*s), canonicalJson(scene_));
  }

  void refusals() {
    RepairReport r;
    std::string error;
    QVERIFY(!repairScene(good_, good_, r, error));
    QVERIFY2(error.find("is the damaged file itself") != std::string::npos, error.c_str());
    const std::string taken = copyOfGood("taken.hscene");
    QVERIFY(!repairScene(good_, taken, r, error));
    QVERIFY2(error.find(taken + ": already exists") != std::string::npos, error.c_str());
    const std::string text = path("text.hscene");
    test::writeFile(text, std::string(200, 'x'));
    QVERIFY(!repairScene(text, path("text-repaired.hscene"), r, error));
    QVERIFY2(error.find("not an SQLite database") != std::string::npos, error.c_str());
    QVERIFY(!fs::exists(path("text-repaired.hscene")));
  }

  void throughTheCli() {
    const std::string damaged = copyOfGood("cli.hscene");
    std::vector<uint8_t> bytes = test::readBlob(damaged, "mesh/" + std::to_string(firstAsset()));
    bytes[bytes.size() / 2] ^= 0xff;
    test::writeBlob(damaged, "mesh/" + std::to_string(firstAsset()), bytes);
    const QString out = QString::fromStdString(path("cli-repaired.hscene"));
    test::CliRun c = test::runCli({"repair", QString::fromStdString(damaged), out}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    QVERIFY2(c.out.contains("dropped: mesh asset") && c.out.contains("which is unchanged"), qPrintable(c.out));
    c = test::runCli({"info", out}, tmp_.path());
    QVERIFY2(c.code == 0, qPrintable(c.err));
    c = test::runCli({"repair", QString::fromStdString(damaged), out}, tmp_.path());
    QVERIFY2(c.code == 1 && c.errLines().size() == 1 && c.err.contains("already exists"), qPrintable(c.err));
  }
};

QTEST_GUILESS_MAIN(TestHsceneRepair)
#include "test_hscene_repair.moc"
