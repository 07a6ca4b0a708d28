// Grading LUTs in the document (scene/color_lut.h): a file read and checked
// through OpenColorIO, refused with a message naming the file (and the line
// where one is at fault) when empty, malformed, truncated, of the wrong
// size, holding NaN or infinity, binary or a folder; stored in the .hscene
// as a blob (a render node needs no copy of the file), saved once, loaded
// back byte for byte; a damaged or missing blob costs the LUT with a
// warning, never the scene; Import LUT is one undo step.
#include <QtTest>

#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "core/content_hash.h"
#include "scene/color_lut.h"
#include "scene/document.h"
#include "scene/hscene_file.h"
#include "scene/scene_json.h"
#include "lut_files.h"

using namespace hs;

class TestSceneLut : public QObject {
  Q_OBJECT
  std::filesystem::path dir_;

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    if (!test::writeText(path, text)) qFatal("cannot write %s", path.c_str());
    return path;
  }
  // The message readLutFile gives for `text` in a file `name` ("" if it reads it).
  std::string refusal(const std::string& name, const std::string& text) {
    const std::string path = write(name, text);
    std::string error;
    const std::optional<scene::LutData> lut = scene::readLutFile(path, error);
    if (lut) return "";
    qInfo("%s: %s", name.c_str(), error.c_str());
    return error;
  }

  scene::SceneState sceneWithLut(const scene::LutData& lut) {
    scene::SceneState s;
    scene::Entity e;
    e.id = 1;
    e.name = "Anchor";
    s.entities[1] = e;
    s.roots = {1};
    s.settings.post.lut = lut;
    s.settings.post.lutEnabled = true;
    s.settings.post.lutIntensity = 0.75f;
    return s;
  }

  static void exec(const std::string& path, const std::string& sql) {
    sqlite3* db = nullptr;
    QCOMPARE(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    QCOMPARE(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  }

 private slots:
  void initTestCase() {
    dir_ = std::filesystem::temp_directory_path() / ("hs_test_scene_lut_" + std::to_string(QCoreApplication::applicationPid()));
    std::filesystem::create_directories(dir_);
  }
  void cleanupTestCase() { std::filesystem::remove_all(dir_); }

  void readsWhatOpenColorIoReads() {
    const std::string text = test::cube3dText(5, test::tealOrangeLook);
    const std::string path = write("look.cube", text);
    std::string error;
    const std::optional<scene::LutData> lut = scene::readLutFile(path, error);
    QVERIFY2(lut, error.c_str());
    QCOMPARE(lut->fileName, std::string("look.cube"));
    QVERIFY(lut->bytes && *lut->bytes == text);
    QCOMPARE(lut->contentHash, contentHash(text.data(), text.size()));
    // A 1D table too, and the formats OpenColorIO lists include the usual ones.
    QVERIFY(refusal("curve.cube", test::cube1dText(64, test::identityLook)).empty());
    const std::vector<std::string> ext = scene::lutFileExtensions();
    for (const char* e : {"cube", "3dl", "spi3d", "csp"})
      QVERIFY2(std::find(ext.begin(), ext.end(), e) != ext.end(), e);
  }

  void badFilesAreRefusedByName() {
    const std::string good = test::cube3dText(4, test::identityLook);
    // Empty.
    QVERIFY(refusal("empty.cube", "").find("empty.cube: the file is empty") != std::string::npos);
    // Malformed: words where numbers belong.
    std::string malformed = good;
    malformed.replace(malformed.find("0.000000 0.000000 0.000000"), 26, "zero zero zero");
    // OpenColorIO's own message says where: the line and what it found.
    std::string e = refusal("malformed.cube", malformed);
    QVERIFY(e.find("malformed.cube: OpenColorIO cannot read it as a LUT") != std::string::npos);
    QVERIFY(e.find("At line (4): 'zero zero zero'") != std::string::npos);
    QVERIFY(e.find('\n') == std::string::npos);  // one line
    // Truncated: the last entries missing.
    e = refusal("truncated.cube", good.substr(0, good.size() - 60));
    QVERIFY(e.find("truncated.cube") != std::string::npos && e.find("expected 64") != std::string::npos);
    // The wrong size: 4^3 entries under a declared size of 5.
    std::string wrongSize = good;
    wrongSize.replace(wrongSize.find("LUT_3D_SIZE 4"), 13, "LUT_3D_SIZE 5");
    e = refusal("wrong_size.cube", wrongSize);
    QVERIFY(e.find("wrong_size.cube") != std::string::npos && e.find("Found 64, expected 125") != std::string::npos);
    // NaN and infinity: named with their line.
    std::string nan = good;
    const size_t at = nan.find("0.333333 0.000000 0.000000");  // the second entry: line 5
    QVERIFY(at != std::string::npos);
    nan.replace(at, 8, "nan");
    e = refusal("nan.cube", nan);
    QVERIFY2(e.find("nan.cube:5: 'nan' is not a finite number") != std::string::npos, e.c_str());
    std::string inf = good;
    inf.replace(inf.find("0.333333 0.000000 0.000000"), 8, "1e999");
    QVERIFY(refusal("inf.cube", inf).find("inf.cube:5: '1e999' is not a finite number") != std::string::npos);
    // Not a LUT at all: a PNG's first bytes under a .cube name, text of another kind.
    e = refusal("picture.cube", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    QVERIFY(e.find("picture.cube") != std::string::npos && e.find("OpenColorIO cannot read it") != std::string::npos);
    QVERIFY(!refusal("notes.cube", "these are my notes\nnot a table\n").empty());
    // A folder, a missing file.
    std::string error;
    QVERIFY(!scene::readLutFile(dir_.string(), error));
    QVERIFY(error.find("a folder") != std::string::npos);
    QVERIFY(!scene::readLutFile((dir_ / "missing.cube").string(), error));
    QVERIFY(error.find("missing.cube: cannot open it") != std::string::npos);
  }

  void storedInTheSceneFile() {
    const std::string text = test::cube3dText(9, test::tealOrangeLook);
    std::string error;
    const std::optional<scene::LutData> lut = scene::readLutFile(write("stored.cube", text), error);
    QVERIFY2(lut, error.c_str());
    const std::string path = (dir_ / "stored.hscene").string();
    scene::SaveReport report;
    QVERIFY2(scene::saveScene(sceneWithLut(*lut), path, error, &report), error.c_str());
    QCOMPARE(report.blobsWritten, size_t(1));
    // The LUT file can go: the scene holds it.
    std::filesystem::remove(dir_ / "stored.cube");
    scene::LoadReport load;
    std::optional<scene::SceneState> back = scene::loadScene(path, error, nullptr, &load);
    QVERIFY2(back, error.c_str());
    QVERIFY(load.warnings.empty());
    QCOMPARE(back->settings.post.lut.fileName, std::string("stored.cube"));
    QVERIFY(back->settings.post.lut.bytes && *back->settings.post.lut.bytes == text);
    QVERIFY(back->settings.post.lutEnabled);
    QCOMPARE(back->settings.post.lutIntensity, 0.75f);
    QVERIFY(scene::canonicalJson(*back) == scene::canonicalJson(sceneWithLut(*lut)));
    QCOMPARE(scene::sceneFileVersion(path), scene::kSceneFormatVersion);
    // Saved again: the blob is not rewritten.
    scene::SaveReport again;
    QVERIFY(scene::saveScene(*back, path, error, &again));
    QCOMPARE(again.blobsWritten, size_t(0));
    QCOMPARE(again.blobsUnchanged, size_t(1));
    // Without a LUT the blob goes.
    scene::SceneState none = *back;
    none.settings.post.lut = {};
    QVERIFY(scene::saveScene(none, path, error));
    back = scene::loadScene(path, error, nullptr, &load);
    QVERIFY(back && back->settings.post.lut.empty() && load.warnings.empty());
  }

  void aDamagedBlobCostsTheLutNotTheScene() {
    std::string error;
    const std::optional<scene::LutData> lut =
        scene::readLutFile(write("damaged.cube", test::cube3dText(5, test::identityLook)), error);
    QVERIFY(lut);
    const std::string key = scene::lutBlobKey(lut->contentHash);
    for (const char* damage : {"UPDATE blobs SET data = X'00112233' WHERE key = '%1'",
                               "DELETE FROM blobs WHERE key = '%1'"}) {
      const std::string path = (dir_ / "damaged.hscene").string();
      QVERIFY(scene::saveScene(sceneWithLut(*lut), path, error));
      exec(path, QString(damage).arg(QString::fromStdString(key)).toStdString());
      scene::LoadReport report;
      const std::optional<scene::SceneState> s = scene::loadScene(path, error, nullptr, &report);
      QVERIFY2(s, error.c_str());
      QCOMPARE(s->entities.size(), size_t(1));  // the rest is there
      QVERIFY(s->settings.post.lut.empty());
      QVERIFY(!s->settings.post.lutEnabled);
      QCOMPARE(report.warnings.size(), size_t(1));
      qInfo("%s", report.warnings[0].c_str());
      QVERIFY(report.warnings[0].find("LUT 'damaged.cube'") != std::string::npos);
      QVERIFY(report.warnings[0].find("renders without it") != std::string::npos);
    }
  }

  void importIsOneUndoStep() {
    std::string error;
    const std::optional<scene::LutData> lut =
        scene::readLutFile(write("undo.cube", test::cube3dText(3, test::identityLook)), error);
    QVERIFY(lut);
    scene::Document doc;
    QVERIFY(scene::ops::setLut(doc, *lut));
    QCOMPARE(doc.state().settings.post.lut.fileName, std::string("undo.cube"));
    QVERIFY(doc.state().settings.post.lutEnabled);
    doc.undoStack()->undo();
    QVERIFY(doc.state().settings.post.lut.empty());
    QVERIFY(!doc.state().settings.post.lutEnabled);
    doc.undoStack()->redo();
    QVERIFY(doc.state().settings.post.lut.bytes);
    QVERIFY(scene::ops::setLut(doc, {}));
    QVERIFY(doc.state().settings.post.lut.empty());
    QVERIFY(!scene::ops::setLut(doc, {}));  // nothing to remove: no step
  }
};

QTEST_GUILESS_MAIN(TestSceneLut)
#include "test_scene_lut.moc"
