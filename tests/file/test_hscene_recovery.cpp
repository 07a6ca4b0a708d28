// Opening a scene after a crash, and scene files whose tables are not what
// the format says (docs/reliability.md, "Scene files, values, resume"):
// a hot journal left by an interrupted save is played back and the last
// saved state comes back byte for byte; a stray journal is no damage; a
// missing or reshaped table is named, never read (the missing `blobs` table
// crashed `info`, `render` and the editor); data that belongs to nothing is
// reported and dropped at the next save.
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>
#include <random>
#include <string>

#include <sqlite3.h>

#include "cli_runner.h"
#include "file_bytes.h"
#include "hscene_sql.h"
#include "mesh/mesh_import.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/operations.h"
#include "scene/scene_json.h"

using namespace hs;
using namespace hs::scene;
namespace fs = std::filesystem;

using hs::test::readFile;
using hs::test::sql;
using hs::test::writeFile;

namespace {

// Two textured quads (entities 1 and 2): a scene with blobs.
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

bool contains(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

// The state a save killed part-way leaves on disk: a transaction on `path`
// that has written pages into the file (a small cache makes SQLite spill
// them before COMMIT, as a large save does), with the file and its journal
// copied to `crashed` at that moment. The transaction on `path` is then
// rolled back, so `path` keeps the last saved state to compare with.
void makeCrashedCopy(const std::string& path, const std::string& crashed) {
  sqlite3* db = nullptr;
  QVERIFY(sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK);
  char* msg = nullptr;
  const int rc = sqlite3_exec(db,
                              "PRAGMA cache_size = 10; BEGIN IMMEDIATE;"
                              "UPDATE document SET json = '{\"format\": \"half written\"}' WHERE id = 1;"
                              "DELETE FROM blobs;"
                              "INSERT INTO blobs VALUES ('mesh/99', 0, '00', randomblob(2000000));",
                              nullptr, nullptr, &msg);
  QVERIFY2(rc == SQLITE_OK, msg ? msg : "");
  QVERIFY(fs::exists(path + "-journal"));
  fs::copy_file(path, crashed, fs::copy_options::overwrite_existing);
  fs::copy_file(path + "-journal", crashed + "-journal", fs::copy_options::overwrite_existing);
  QVERIFY(sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
}

}  // namespace

class TestHsceneRecovery : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  SceneState scene_;
  std::string good_;

  std::string path(const std::string& name) const { return (fs::path(tmp_.path().toStdString()) / name).string(); }
  std::string copyOfGood(const std::string& name) {
    const std::string p = path(name);
    fs::copy_file(good_, p, fs::copy_options::overwrite_existing);
    return p;
  }

  // `args` run on the CLI: exit 1, one line on stderr naming the file and `what`.
  void expectCliRefuses(const QStringList& args, const std::string& file, const std::string& what) {
    const test::CliRun r = test::runCli(args, tmp_.path());
    QVERIFY2(r.code == 1, qPrintable(QString("exit %1 (a crash is -1): %2").arg(r.code).arg(r.err)));
    QCOMPARE(r.errLines().size(), 1);
    QVERIFY2(r.err.contains(QString::fromStdString(file)), qPrintable(r.err));
    QVERIFY2(r.err.contains(QString::fromStdString(what)), qPrintable(r.err));
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    scene_ = smallScene();
    good_ = path("good.hscene");
    std::string error;
    QVERIFY2(saveScene(scene_, good_, error), error.c_str());
  }

  // ---- interrupted saves ---------------------------------------------------------------

  void hotJournalIsRolledBack() {
    const std::string saved = copyOfGood("saved.hscene");
    const std::string crashed = path("crashed.hscene");
    makeCrashedCopy(saved, crashed);
    const std::string savedBytes = readFile(saved);
    QVERIFY2(readFile(crashed) != savedBytes, "the fixture's save did not reach the file");

    std::string error;
    LoadReport report;
    std::optional<SceneState> s = loadScene(crashed, error, nullptr, &report);
    QVERIFY2(s, error.c_str());  // before: "damaged ... (attempt to write a readonly database)"
    QVERIFY(contains(report.warnings, "recovered from an interrupted save; the last saved state is intact"));
    QCOMPARE(canonicalJson(*s), canonicalJson(scene_));
    QCOMPARE(s->assets.begin()->second.data->positions.size(), scene_.assets.begin()->second.data->positions.size());
    QVERIFY(!fs::exists(crashed + "-journal"));
    QVERIFY2(readFile(crashed) == savedBytes, "the rolled back file differs from the last save");
  }

  void hotJournalThroughTheCli() {
    const std::string saved = copyOfGood("cli_saved.hscene");
    const std::string crashed = path("cli_crashed.hscene");
    makeCrashedCopy(saved, crashed);
    const test::CliRun r = test::runCli({"info", QString::fromStdString(crashed)}, tmp_.path());
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("warning: " + QString::fromStdString(crashed) +
                            ": recovered from an interrupted save; the last saved state is intact"),
             qPrintable(r.err));
    QVERIFY2(r.out.contains("mesh assets: 2"), qPrintable(r.out));
  }

  void strayJournalIsNoDamage() {
    const std::string p = copyOfGood("stray.hscene");
    std::mt19937 rng(7);
    std::string junk(8192, '\0');
    for (char& c : junk) c = char(rng() | 1);  // a non-zero first byte: SQLite calls it hot
    writeFile(p + "-journal", junk);
    std::string error;
    LoadReport report;
    std::optional<SceneState> s = loadScene(p, error, nullptr, &report);
    QVERIFY2(s, error.c_str());  // before: "damaged ... (attempt to write a readonly database)"
    QVERIFY(contains(report.warnings, "was not one SQLite wrote"));
    QCOMPARE(canonicalJson(*s), canonicalJson(scene_));
    QVERIFY(readFile(p) == readFile(good_));
  }

  // A save onto a file with a hot journal plays the journal back first:
  // left beside the new file it would later be played into it.
  void saveOverAHotJournal() {
    const std::string saved = copyOfGood("save_saved.hscene");
    const std::string crashed = path("save_crashed.hscene");
    makeCrashedCopy(saved, crashed);
    Document doc;
    doc.reset(scene_, {});
    QVERIFY(ops::rename(doc, doc.state().findByName("quad"), "renamed quad"));
    std::string error;
    QVERIFY2(saveScene(doc.state(), crashed, error), error.c_str());
    QVERIFY(!fs::exists(crashed + "-journal"));
    LoadReport report;
    std::optional<SceneState> s = loadScene(crashed, error, nullptr, &report);
    QVERIFY2(s, error.c_str());
    QVERIFY(report.warnings.empty());
    QCOMPARE(canonicalJson(*s), canonicalJson(doc.state()));
  }

  // A message that quotes file content shows its control characters as
  // escapes: a carriage return in a path printed as "v ')" before.
  void controlCharactersInMessagesAreEscaped() {
    const test::CliRun r = test::runCli({"info", "bad\rname\x1b[2J.hscene"}, tmp_.path());
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains("bad\\rname\\x1b[2J.hscene: file not found"), qPrintable(r.err));
    QVERIFY(!r.err.contains('\r') && !r.err.contains('\x1b'));
  }

  // ---- tables that are missing or reshaped -----------------------------------------------

  void missingBlobsTableWithMeshes() {
    const std::string p = copyOfGood("no_blobs.hscene");
    sql(p, "DROP TABLE blobs");
    std::string error;
    QVERIFY(!loadScene(p, error));
    QVERIFY2(error.find("table 'blobs' is missing") != std::string::npos, error.c_str());
    QVERIFY2(error.find("2 mesh asset(s)") != std::string::npos, error.c_str());
    // Each command that crashed (SIGSEGV) on it before.
    const QString f = QString::fromStdString(p);
    expectCliRefuses({"info", f}, p, "table 'blobs' is missing");
    expectCliRefuses({"info", "--json", f}, p, "table 'blobs' is missing");
    expectCliRefuses({"render", f, "--out", QString::fromStdString(path("x.png"))}, p, "table 'blobs' is missing");
  }

  void missingBlobsTableWithoutData() {
    const std::string p = path("empty_blobs.hscene");
    std::string error;
    SceneState s;
    QVERIFY2(saveScene(s, p, error), error.c_str());
    sql(p, "DROP TABLE blobs");
    LoadReport report;
    QVERIFY2(loadScene(p, error, nullptr, &report), error.c_str());
    QVERIFY(contains(report.warnings, "table 'blobs' is missing; the scene needs none"));
    QVERIFY2(saveScene(s, p, error), error.c_str());  // the save adds it back
    report = {};
    QVERIFY2(loadScene(p, error, nullptr, &report), error.c_str());
    QVERIFY(report.warnings.empty());
  }

  void missingDocumentTable() {
    const std::string p = copyOfGood("no_document.hscene");
    sql(p, "DROP TABLE document");
    std::string error;
    QVERIFY(!loadScene(p, error));
    QVERIFY2(error.find(p + ": the scene file is damaged") == 0, error.c_str());
    QVERIFY2(error.find("table 'document'") != std::string::npos, error.c_str());
  }

  void wrongColumnTypes_data() {
    QTest::addColumn<QString>("create");
    QTest::addColumn<QString>("named");
    QTest::newRow("data as text") << "CREATE TABLE blobs(key TEXT, part INTEGER, hash TEXT, data TEXT)"
                                  << "table blobs: column data is declared TEXT, expected BLOB";
    QTest::newRow("no part") << "CREATE TABLE blobs(key TEXT, hash TEXT, data BLOB)"
                             << "table blobs: column part is missing";
    QTest::newRow("untyped key") << "CREATE TABLE blobs(key, part INTEGER, hash TEXT, data BLOB)"
                                 << "table blobs: column key is declared without a type, expected TEXT";
  }
  void wrongColumnTypes() {
    QFETCH(QString, create);
    QFETCH(QString, named);
    const std::string p = copyOfGood("reshaped.hscene");
    sql(p, "DROP TABLE blobs; " + create.toStdString());
    std::string error;
    QVERIFY(!loadScene(p, error));
    QVERIFY2(error.find(named.toStdString()) != std::string::npos, error.c_str());
  }

  void danglingBlobKeysAreReportedAndDropped() {
    const std::string p = copyOfGood("dangling.hscene");
    sql(p, "INSERT INTO blobs VALUES ('mesh/777', 0, '00', x'00'), ('terrain/5/h/0_0', 0, '00', x'00'),"
           " ('notes', 0, '00', x'00')");
    std::string error;
    LoadReport report;
    std::optional<SceneState> s = loadScene(p, error, nullptr, &report);
    QVERIFY2(s, error.c_str());
    QVERIFY(contains(report.warnings, "3 stored data block(s) belong to no asset or terrain (first: 'mesh/777')"));
    QCOMPARE(canonicalJson(*s), canonicalJson(scene_));
    QVERIFY2(saveScene(*s, p, error), error.c_str());
    QCOMPARE(test::countBlobKeys(p, "1"), 2);  // the quads' meshes alone
  }

  void parentCycleAndDuplicateIds_data() {
    QTest::addColumn<QString>("from");
    QTest::addColumn<QString>("to");
    QTest::addColumn<QString>("named");
    QTest::newRow("duplicate id") << "\"id\":2," << "\"id\":1," << "duplicate entity id";
    QTest::newRow("parent cycle") << "\"parent\":0" << "\"parent\":1" << "inconsistent hierarchy";
  }
  void parentCycleAndDuplicateIds() {
    QFETCH(QString, from);
    QFETCH(QString, to);
    QFETCH(QString, named);
    const std::string p = copyOfGood("hierarchy.hscene");
    std::string json = writeJson(sceneToJson(scene_), -1);
    const size_t at = json.find(from.toStdString(), json.find("\"entities\""));
    QVERIFY(at != std::string::npos);
    json.replace(at, size_t(from.size()), to.toStdString());
    test::writeDescription(p, json);
    std::string error;
    QVERIFY(!loadScene(p, error));
    QVERIFY2(error.find(named.toStdString()) != std::string::npos, error.c_str());
  }
};

QTEST_GUILESS_MAIN(TestHsceneRecovery)
#include "test_hscene_recovery.moc"
