// hybridscape-cli as a user runs it: the built program through QProcess.
// Each subcommand's work is checked through the file it wrote (read back
// with the scene library or OpenImageIO), and every error must exit non-zero
// with exactly one line on stderr that names the problem.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

#include <filesystem>

#include <OpenImageIO/imageio.h>

#include "cli_runner.h"
#include "file_bytes.h"
#include "look_from.h"
#include "scene/hscene_file.h"
#include "scene/object_tracks.h"
#include "scene/scene_json.h"
#include "sequencer/key_edit.h"

using namespace hs;
namespace fs = std::filesystem;

using hs::test::kCli;
using hs::test::readFile;
using hs::test::writeFile;

namespace {

const QString kMeshData = HS_TEST_DATA_DIR "/mesh";

using Run = hs::test::CliRun;

QJsonObject parseJson(const QByteArray& text) {
  QJsonParseError err;
  const QJsonDocument d = QJsonDocument::fromJson(text, &err);
  if (err.error != QJsonParseError::NoError) qWarning("bad JSON: %s", qPrintable(err.errorString()));
  return d.object();
}

// World-space box of the mesh vertices of the scene's entities (or of one).
// A mesh's positions are relative to its own origin, and the entity that
// shows it carries that origin in its transform (ops::addImportedMesh).
struct Box {
  glm::dvec3 min{INFINITY}, max{-INFINITY};
  void add(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
};
Box vertexBox(const scene::SceneState& s, const std::string& onlyEntity = {}) {
  Box b;
  for (const auto& [id, e] : s.entities) {
    if (!e.mesh || (!onlyEntity.empty() && e.name != onlyEntity)) continue;
    if (onlyEntity.empty() && !s.effectivelyVisible(id)) continue;  // info's bounds are of what is drawn
    const scene::MeshAsset* a = s.findAsset(e.mesh->mesh);
    const glm::dmat4 w = s.worldMatrix(id);
    for (const auto& p : a->data->positions) b.add(glm::dvec3(w * glm::dvec4(glm::dvec3(p), 1.0)));
  }
  // Terrains' boxes too (the demo's valley): every sample lies within them.
  for (scene::EntityId id : scene::terrainEntities(s, true)) {
    if (!onlyEntity.empty() && s.find(id)->name != onlyEntity) continue;
    const terrain::Heightfield& hf = scene::terrainOf(s, id)->data->heights();
    const glm::dvec3 o = scene::terrainWorldOrigin(s, id);
    b.add(o + glm::dvec3(0.0, 0.0, double(hf.range().min)));
    b.add(o + glm::dvec3(hf.sizeMetres(), double(hf.range().max)));
  }
  return b;
}

glm::dvec3 vec3(const QJsonValue& v) {
  const QJsonArray a = v.toArray();
  return {a.at(0).toDouble(NAN), a.at(1).toDouble(NAN), a.at(2).toDouble(NAN)};
}

}  // namespace

class TestCli : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString demo_;  // a demo scene written once

  QString path(const QString& name) const { return tmp_.filePath(name); }

  Run cli(const QStringList& args) { return test::runCli(args, tmp_.path()); }

  // A failure: non-zero exit (`code`), one line on stderr containing each of `names`.
  void expectError(const QStringList& args, int code, const QStringList& names) {
    const Run r = cli(args);
    const QString cmd = "hybridscape-cli " + args.join(' ');
    QVERIFY2(r.code == code, qPrintable(QString("%1: exit %2, expected %3; stderr: %4").arg(cmd).arg(r.code).arg(code).arg(r.err)));
    QVERIFY2(r.errLines().size() == 1 && r.err.endsWith('\n'),
             qPrintable(QString("%1: expected one line on stderr, got:\n%2").arg(cmd, r.err)));
    for (const QString& n : names)
      QVERIFY2(r.err.contains(n), qPrintable(QString("%1: '%2' not in: %3").arg(cmd, n, r.err)));
  }

  std::optional<scene::SceneState> load(const QString& file) {
    std::string error;
    auto s = scene::loadScene(file.toStdString(), error);
    if (!s) qWarning("%s", error.c_str());
    return s;
  }

  QJsonObject infoJson(const QString& file) {
    const Run r = cli({"info", file, "--json"});
    if (r.code != 0) qWarning("info failed: %s", qPrintable(r.err));
    return parseJson(r.out.toUtf8());
  }

 private slots:
  void initTestCase() {
    QVERIFY(tmp_.isValid());
    QVERIFY2(QFileInfo(kCli).isExecutable(), qPrintable(kCli + " is not built"));
    demo_ = path("demo.hscene");
    const Run r = cli({"demo", demo_});
    QVERIFY2(r.code == 0, qPrintable(r.err));
  }

  // ---- help ---------------------------------------------------------------------

  void helpOnEveryCommand_data() {
    QTest::addColumn<QString>("command");
    for (const char* c : {"new", "demo", "import", "info", "render", "set", "material", "key", "sequence", "path", "farm",
                          "terrain", "mesh"})
      QTest::newRow(c) << QString(c);
  }
  void helpOnEveryCommand() {
    QFETCH(QString, command);
    for (const QString& flag : {QString("--help"), QString("-h")}) {
      const Run r = cli({command, flag});
      QCOMPARE(r.code, 0);
      QVERIFY2(r.out.startsWith("usage: hybridscape-cli " + command), qPrintable(r.out));
      QVERIFY2(r.err.isEmpty(), qPrintable(r.err));
    }
    // The top-level help lists the command.
    const Run top = cli({"--help"});
    QCOMPARE(top.code, 0);
    QVERIFY(top.out.contains("  " + command + " "));
  }

  void noArgumentsPrintsUsage() {
    const Run r = cli({});
    QCOMPARE(r.code, 2);
    QVERIFY(r.out.contains("usage: hybridscape-cli <command>"));
    const Run v = cli({"--version"});
    QCOMPARE(v.code, 0);
    QVERIFY(v.out.startsWith("hybridscape-cli "));
  }

  // ---- commands -----------------------------------------------------------------

  void newScene() {
    const QString f = path("new.hscene");
    const Run r = cli({"new", f});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const auto s = load(f);
    QVERIFY(s);
    QCOMPARE(s->entities.size(), size_t(2));
    QCOMPARE(s->cameras().size(), size_t(1));
    QVERIFY(s->assets.empty());
    // Not over an existing file without --force; with it, yes.
    const std::string before = readFile(f.toStdString());
    expectError({"new", f}, 1, {f, "--force"});
    QCOMPARE(readFile(f.toStdString()), before);
    QCOMPARE(cli({"new", f, "--force"}).code, 0);
    QVERIFY(load(f));
  }

  // Without the image module (core/image_io.h) the CLI still opens, edits
  // and saves a scene, and the textures it could not decode come back
  // unchanged; what needs an image says the module is missing.
  void withoutTheImageModuleTexturesSurviveASave() {
    const QString f = path("no_images.hscene");
    QVERIFY(QFile::copy(demo_, f));
    qputenv("HS_IMAGE_IO_MODULE", "/nonexistent/hybridscape-image-io.so");
    const Run edit = cli({"sequence", f, "--fps", "30"});
    const Run render = cli({"render", f, "--out", path("no_images.png"), "--size", "64x32"});
    qunsetenv("HS_IMAGE_IO_MODULE");
    QVERIFY2(edit.code == 0, qPrintable(edit.err));
    QCOMPARE(render.code, 1);
    QVERIFY2(render.err.contains("the image module hybridscape-image-io.so (OpenImageIO) is missing") &&
                 render.err.contains("/nonexistent/hybridscape-image-io.so (not there)"),
             qPrintable(render.err));
    const auto before = load(demo_), after = load(f);
    QVERIFY(before && after);
    QCOMPARE(after->sequence.rate.fps(), 30.0);
    QVERIFY(!before->textures.empty());
    QCOMPARE(after->textures.size(), before->textures.size());
    for (const auto& [id, t] : before->textures) {
      const auto& u = after->textures.at(id);
      QVERIFY(t.image && u.image);
      QVERIFY(!t.image->rgba.empty());
      QCOMPARE(u.image->encoded, t.image->encoded);
      QCOMPARE(u.image->rgba, t.image->rgba);
    }
  }

  void demoAndInfoJson() {
    const auto s = load(demo_);
    QVERIFY(s);
    const QJsonObject info = infoJson(demo_);
    QCOMPARE(info["format_version"].toInt(), scene::kSceneFormatVersion);
    // Entities: every one, with its name and components.
    const QJsonArray entities = info["entities"].toArray();
    QCOMPARE(size_t(entities.size()), s->entities.size());
    QStringList names;
    for (const auto& e : entities) names << e.toObject()["name"].toString();
    for (const auto& [id, e] : s->entities) QVERIFY(names.contains(QString::fromStdString(e.name)));
    for (const auto& v : entities) {
      const QJsonObject e = v.toObject();
      const scene::Entity* ent = s->find(scene::EntityId(e["id"].toDouble()));
      QVERIFY(ent);
      QCOMPARE(e["components"].toArray().contains("mesh"), ent->mesh.has_value());
      QCOMPARE(e["components"].toArray().contains("camera"), ent->camera.has_value());
      const glm::dvec3 wp = vec3(e["world_position_m"]);
      QVERIFY(glm::length(wp - glm::dvec3(s->worldMatrix(ent->id)[3])) < 1e-9);
    }
    // Assets: the bunny, with the triangle count of the scan's OBJ file,
    // then the two surface-detail slabs (scene/demo_materials.h) and the
    // three glass spheres and the pond (scene/demo_glass.h), then the six
    // generated plants its foliage draws (scene/demo_foliage.h), one type
    // each, then the bunny again as a cluster hierarchy (scene/demo_clusters.h).
    const QJsonArray assets = info["assets"].toArray();
    QCOMPARE(assets.size(), 14);
    const QJsonObject clustered = assets.last().toObject()["clusters"].toObject();
    QCOMPARE(clustered["triangles"].toInt(), assets.first().toObject()["triangles"].toInt());
    QVERIFY(clustered["levels"].toInt() > 4 && clustered["pages"].toInt() > 10);
    QCOMPARE(clustered["pages_in_memory_bytes"].toInt(), 0);  // opened from the file: none read yet
    QVERIFY(assets.first().toObject()["clusters"].isNull());
    QCOMPARE(info["foliage"].toObject()["types"].toArray().size(), 6);
    QVERIFY(info["foliage"].toObject()["instances"].toInt() > 1000);
    // The far level of every mesh the foliage draws with an impostor: baked
    // by `demo` and stored in the file (with --no-impostors, not stored).
    const Run plain = cli({"demo", path("demo_plain.hscene"), "--no-impostors"});
    QVERIFY2(plain.code == 0, qPrintable(plain.err));
    const QJsonArray plainAssets = infoJson(path("demo_plain.hscene"))["assets"].toArray();
    QCOMPARE(plainAssets.size(), assets.size());
    int impostors = 0;
    for (qsizetype i = 0; i < assets.size(); ++i) {
      const QJsonObject a = assets[i].toObject();
      if (!a.contains("impostor")) continue;
      ++impostors;
      QVERIFY2(a["impostor"].toString() == "stored", qPrintable(a["name"].toString()));
      QCOMPARE(plainAssets[i].toObject()["impostor"].toString(), QString("none"));
    }
    QVERIFY(impostors >= 2);
    const std::string bunny = readFile(HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj");
    size_t faces = 0;
    for (size_t pos = 0; (pos = bunny.find("\nf ", pos)) != std::string::npos; ++pos) ++faces;
    QCOMPARE(size_t(assets[0].toObject()["triangles"].toDouble()), faces);
    QVERIFY(assets[0].toObject()["vertices"].toDouble() > 30000);
    // Cameras.
    QCOMPARE(info["cameras"].toArray(), (QJsonArray{"Main Camera", "Flight Camera", "Crane Camera", "Scan Camera"}));  // the stereo flight's, the cut to the crane's, the clustered scan's
    // Bounds: hold every vertex of every instance, and the size is max - min.
    const QJsonObject bounds = info["bounds_m"].toObject();
    const glm::dvec3 bmin = vec3(bounds["min"]), bmax = vec3(bounds["max"]), bsize = vec3(bounds["size"]);
    const Box vb = vertexBox(*s);
    for (int k = 0; k < 3; ++k) {
      QVERIFY(bmin[k] <= vb.min[k] + 1e-6);
      QVERIFY(bmax[k] >= vb.max[k] - 1e-6);
      QVERIFY(std::abs(bsize[k] - (bmax[k] - bmin[k])) < 1e-9);
      QVERIFY(bsize[k] < (vb.max[k] - vb.min[k]) * 1.5 + 0.5);  // a box around them, not far beyond
    }
    // The timeline: the range, and every track (a camera path counts as its
    // progress track) with its number of keys.
    QCOMPARE(info["sequence"].toObject()["start_frame"].toInt(), int(s->sequence.startFrame));
    QCOMPARE(info["sequence"].toObject()["end_frame"].toInt(), int(s->sequence.endFrame));
    size_t expectedTracks = 0;
    for (const sequencer::Binding& b : s->sequence.bindings) expectedTracks += b.tracks.size() + (b.path ? 1 : 0);
    QVERIFY(expectedTracks >= 3);  // the demo's flight path, interaxial, the spinning bunny
    const QJsonArray tracks = info["tracks"].toArray();
    QCOMPARE(size_t(tracks.size()), expectedTracks);
    for (const QJsonValue& v : tracks) {
      const QJsonObject t = v.toObject();
      // A material's and the settings' tracks (the demo animates one of
      // each) name their target in place of an entity.
      uint64_t entity = scene::EntityId(t["entity_id"].toDouble());
      if (t.contains("material_id")) {
        const auto material = scene::MaterialId(t["material_id"].toDouble());
        QCOMPARE(t["material"].toString().toStdString(), s->findMaterial(material)->name);
        entity = scene::materialTarget(material);
      } else if (t.contains("settings")) {
        entity = scene::settingsTarget();
      } else {
        QCOMPARE(t["entity"].toString().toStdString(), s->find(entity)->name);
      }
      const std::string property = t["property"].toString().toStdString();
      const size_t keys = property == "path.progress"
                              ? s->sequence.findBinding(entity)->path->progress.keys.size()
                              : sequencer::keyTimes(s->sequence, entity, property).size();
      QCOMPARE(size_t(t["keys"].toInt()), keys);
    }
    // The text form names the same things.
    const Run text = cli({"info", demo_});
    QCOMPARE(text.code, 0);
    for (const auto& [id, e] : s->entities) QVERIFY(text.out.contains(QString::fromStdString(e.name)));
    QVERIFY(text.out.contains("69451 triangles"));
    QVERIFY2(text.out.contains(QString("tracks: %1").arg(expectedTracks)), qPrintable(text.out));
    QVERIFY(text.out.contains("transform.rotation: 13 keys"));
    // The rockfall draws a mesh, and says so instead of its sprite.
    QVERIFY2(text.out.contains("Rockfall: mesh \"Rockfall stone\""), qPrintable(text.out));
  }

  void importWithOptions() {
    const QString f = path("import.hscene");
    QCOMPARE(cli({"new", f}).code, 0);
    const QString report = path("report.json");
    const Run r = cli({"import", kMeshData + "/textured_quad.obj", f, "--at", "1,2,3", "--up", "y", "--report", report});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.isEmpty(), qPrintable(r.err));
    // The report: plain field names.
    QFile rf(report);
    QVERIFY(rf.open(QIODevice::ReadOnly));
    const QJsonObject rep = parseJson(rf.readAll());
    QCOMPARE(rep["file"].toString(), kMeshData + "/textured_quad.obj");
    QCOMPARE(rep["reader"].toString(), QString("obj"));
    QCOMPARE(rep["triangles_in"].toInt(), 2);
    QCOMPARE(rep["triangles_out"].toInt(), 2);
    QCOMPARE(rep["vertices_out"].toInt(), 4);
    QCOMPARE(rep["polygons_triangulated"].toInt(), 1);
    QCOMPARE(rep["up_axis_converted"].toBool(), true);
    QVERIFY(rep["warnings"].isArray() && rep["warnings"].toArray().isEmpty());
    for (const char* key : {"vertices_in", "non_finite_vertices", "out_of_range_faces", "degenerate_faces", "seconds"})
      QVERIFY2(rep[key].isDouble(), key);
    QVERIFY(!rep.contains("error"));
    // --at: the centre of the base of the mesh's box lands there.
    auto s = load(f);
    QVERIFY(s);
    QCOMPARE(s->assets.size(), size_t(1));
    QVERIFY(s->findByName("textured_quad") != scene::kNoEntity);
    const Box b = vertexBox(*s, "textured_quad");
    QVERIFY(std::abs((b.min.x + b.max.x) / 2 - 1.0) < 1e-6);
    QVERIFY(std::abs((b.min.y + b.max.y) / 2 - 2.0) < 1e-6);
    QVERIFY(std::abs(b.min.z - 3.0) < 1e-6);
    // Y-up: the file's 1 m of height is world Z.
    QVERIFY(std::abs((b.max.z - b.min.z) - 1.0) < 1e-6);
    QVERIFY(std::abs(b.max.y - b.min.y) < 1e-6);
    QCOMPARE(s->assets.begin()->second.data->textures.size(), size_t(1));

    // --up z --name --reader assimp: without --at the mesh stays at its file coordinates.
    const Run z = cli({"import", kMeshData + "/textured_quad.obj", f, "--up", "z", "--name", "Upright", "--reader", "assimp"});
    QVERIFY2(z.code == 0, qPrintable(z.err));
    s = load(f);
    QVERIFY(s);
    QCOMPARE(s->assets.size(), size_t(2));
    const Box bz = vertexBox(*s, "Upright");
    QVERIFY(glm::length(bz.min - glm::dvec3(10, 20, 30)) < 1e-5);
    QVERIFY(glm::length(bz.max - glm::dvec3(12, 21, 30)) < 1e-5);
    const QJsonObject info = infoJson(f);
    QCOMPARE(info["assets"].toArray().size(), 2);
    QCOMPARE(info["assets"].toArray()[1].toObject()["source"].toString(), kMeshData + "/textured_quad.obj");
    QCOMPARE(info["assets"].toArray()[1].toObject()["textures"].toInt(), 1);
  }

  void importWarningsDoNotFail() {
    const QString f = path("warn.hscene");
    QCOMPARE(cli({"new", f}).code, 0);
    QFile obj(path("holes.obj"));
    QVERIFY(obj.open(QIODevice::WriteOnly));
    obj.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    obj.close();
    const Run r = cli({"import", path("holes.obj"), f});
    QCOMPARE(r.code, 0);
    QVERIFY2(r.err.contains("warning:") && r.err.contains("holes.obj:5:"), qPrintable(r.err));
    QCOMPARE(load(f)->assets.begin()->second.data->triangleCount(), size_t(1));
  }

  void importOfABadFileLeavesTheScene() {
    const QString f = path("keep.hscene");
    QCOMPARE(cli({"new", f}).code, 0);
    const std::string before = readFile(f.toStdString());
    QFile bad(path("broken.obj"));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n");
    bad.close();
    const QString report = path("broken.json");
    expectError({"import", path("broken.obj"), f, "--report", report}, 1, {"broken.obj:3:"});
    QCOMPARE(readFile(f.toStdString()), before);  // byte for byte
    // The report says what went wrong too.
    QFile rf(report);
    QVERIFY(rf.open(QIODevice::ReadOnly));
    QVERIFY(parseJson(rf.readAll())["error"].toString().contains("broken.obj:3:"));
    // A missing mesh file, and a file that is not a mesh.
    expectError({"import", path("nothing.obj"), f}, 1, {"nothing.obj", "not found"});
    expectError({"import", kMeshData + "/checker_4x2.png", f}, 1, {"checker_4x2.png", "'.png'"});
    QCOMPARE(readFile(f.toStdString()), before);
  }

  void setFieldsAndSettings() {
    const QString f = path("set.hscene");
    QVERIFY(QFile::copy(demo_, f));
    QCOMPARE(cli({"set", "Main Camera", "camera.fov_deg", "35", f}).code, 0);
    QCOMPARE(cli({"set", "Stanford Bunny", "transform.translation", "10,0,-1.5", f}).code, 0);
    QCOMPARE(cli({"set", "settings.antialiasing", "fxaa", f}).code, 0);
    QCOMPARE(cli({"set", "settings.exposure_ev100", "14.5", f}).code, 0);
    // The post chain's settings (docs/rendering.md "Post-processing").
    QCOMPARE(cli({"set", "settings.post.bloom.enabled", "true", f}).code, 0);
    QCOMPARE(cli({"set", "settings.post.grade.gain", "1.1,1,0.9", f}).code, 0);
    QCOMPARE(cli({"set", "settings.tonemap", "agx", f}).code, 0);
    auto s = load(f);
    QVERIFY(s);
    QVERIFY(s->settings.post.bloom);
    QCOMPARE(s->settings.post.gain, glm::vec3(1.1f, 1.0f, 0.9f));
    QVERIFY(s->settings.tonemap == scene::Tonemap::AgX);
    const scene::EntityId sun = s->findByName("Sun");
    QCOMPARE(cli({"set", QString::number(sun), "entity.visible", "false", f}).code, 0);  // by id
    s = load(f);
    QCOMPARE(s->find(s->findByName("Main Camera"))->camera->verticalFovDeg, 35.0);
    QCOMPARE(s->find(s->findByName("Stanford Bunny"))->transform.translation, glm::dvec3(10, 0, -1.5));
    QVERIFY(s->settings.antialiasing == scene::Antialiasing::Fxaa);
    QCOMPARE(s->settings.exposureEv100, 14.5f);
    QVERIFY(!s->find(sun)->visible);
    // The same value again changes nothing and says so.
    const Run same = cli({"set", "settings.exposure_ev100", "14.5", f});
    QCOMPARE(same.code, 0);
    QVERIFY(same.out.contains("unchanged"));
    // Errors leave the file as it was.
    const std::string before = readFile(f.toStdString());
    expectError({"set", "Nobody", "camera.fov_deg", "35", f}, 1, {"Nobody"});
    expectError({"set", "Main Camera", "camera.zoom", "35", f}, 1, {"camera.zoom"});
    expectError({"set", "Main Camera", "camera.fov_deg", "wide", f}, 1, {"wide"});
    expectError({"set", "Main Camera", "camera.fov_deg", "nan", f}, 1, {"nan"});
    expectError({"set", "Sun", "camera.fov_deg", "35", f}, 1, {"Sun", "camera"});
    expectError({"set", "settings.colour", "1", f}, 1, {"colour"});
    expectError({"set", "settings.antialiasing", "ssaa", f}, 1, {"ssaa"});
    expectError({"set", "settings.post.grade.gain", "1,2,11", f}, 1, {"post.grade.gain", "0 to 10"});
    expectError({"set", "settings.post.bloom.intensity", "-1", f}, 1, {"post.bloom.intensity"});
    expectError({"set", "Stanford Bunny", "mesh.asset", "99", f}, 1, {"mesh.asset"});
    expectError({"set", "99999999999999999999999", "entity.visible", "true", f}, 1, {"99999999999999999999999"});
    expectError({"set", "Main Camera", "camera.fov_deg", f}, 2, {"expected"});
    QCOMPARE(readFile(f.toStdString()), before);
  }

  void renderFormats_data() {
    QTest::addColumn<QString>("ext");
    QTest::addColumn<QString>("aa");
    QTest::newRow("png") << "png" << "msaa4";
    QTest::newRow("jpg") << "jpg" << "fxaa";
    QTest::newRow("tif") << "tif" << "none";
    QTest::newRow("png-smaa") << "png" << "smaa";
    QTest::newRow("exr") << "exr" << "msaa4";
  }
  void renderFormats() {
    QFETCH(QString, ext);
    QFETCH(QString, aa);
    const QString out = path("frame." + ext);
    const Run r = cli({"render", demo_, "--out", out, "--size", "96x54", "--camera", "Main Camera", "--aa", aa});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("96x54") && r.out.contains("Main Camera"), qPrintable(r.out));
    auto in = OIIO::ImageInput::open(out.toStdString());
    QVERIFY2(in, OIIO::geterror().c_str());
    const OIIO::ImageSpec& spec = in->spec();
    QCOMPARE(spec.width, 96);
    QCOMPARE(spec.height, 54);
    QVERIFY(spec.nchannels >= 3);
    QCOMPARE(spec.format == OIIO::TypeDesc::HALF, ext == "exr");  // EXR is half float, the rest 8-bit
    in->close();
    // Written whole under a temporary name: nothing else is left in the folder.
    for (const auto& entry : fs::directory_iterator(tmp_.path().toStdString()))
      QVERIFY2(entry.path().filename().string().rfind(".tmp-", 0) != 0, entry.path().c_str());
  }

  void renderWithoutCameraFramesTheScene() {
    auto s = load(demo_);
    QVERIFY(s);
    for (scene::EntityId cam : s->cameras()) s->entities.at(cam).camera.reset();
    std::string error;
    const QString f = path("nocam.hscene");
    QVERIFY2(scene::saveScene(*s, f.toStdString(), error), error.c_str());
    const Run r = cli({"render", f, "--out", path("framed.png"), "--size", "40x30", "--no-grid"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("a view framing the scene"), qPrintable(r.out));
    auto in = OIIO::ImageInput::open(path("framed.png").toStdString());
    QVERIFY(in);
    QCOMPARE(in->spec().width, 40);
    QCOMPARE(in->spec().height, 30);
  }

  // --stats: the passes that ran and what they hold, read from the renderer's
  // registry. The byte counts are checked against the formats' sizes
  // (RGBA16F: 8 bytes, DEPTH32F: 4 bytes a sample), not against the
  // renderer's own arithmetic.
  void renderStats_data() {
    QTest::addColumn<QString>("aa");
    QTest::addColumn<bool>("grid");
    QTest::newRow("no aa, no grid") << "none" << false;
    QTest::newRow("msaa4, grid") << "msaa4" << true;
    QTest::newRow("fxaa") << "fxaa" << false;
  }
  void renderStats() {
    QFETCH(QString, aa);
    QFETCH(bool, grid);
    const int w = 64, h = 48;
    QStringList args{"render", demo_, "--out", path("stats.png"), "--size", "64x48", "--aa", aa, "--stats",
                     path("stats.json")};
    if (!grid) args << "--no-grid";
    const Run r = cli(args);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QFile f(path("stats.json"));
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject j = QJsonDocument::fromJson(f.readAll()).object();
    QStringList ran;
    QJsonObject opaque;
    for (const QJsonValue& v : j["passes"].toArray()) {
      const QJsonObject p = v.toObject();
      ran << p["name"].toString();
      QVERIFY(p["cpu_ms"].toDouble() >= 0.0);
      QVERIFY2(p["gpu_ms"].isDouble() && p["gpu_ms"].toDouble() >= 0.0, qPrintable(p["name"].toString()));
      if (p["name"] == "opaque") opaque = p;
    }
    for (const char* always : {"opaque", "terrain", "sky", "tonemap"})
      QVERIFY2(ran.contains(always), qPrintable(ran.join(',')));
    QCOMPARE(ran.contains("grid"), grid);
    QCOMPARE(ran.contains("resolve"), aa == "msaa4");
    QCOMPARE(ran.contains("fxaa"), aa == "fxaa");
    QVERIFY(!ran.contains("overlay"));  // nothing to overlay headless
    // The demo's spot and point lights are in view: the clustered light
    // list ran, and none of its clusters overflowed.
    const QJsonObject lights = j["lights"].toObject();
    QVERIFY2(lights["in_view"].toInteger() > 0, "the demo's lights are in view");
    QVERIFY(ran.contains("light_culling"));
    QCOMPARE(lights["clusters_over_cap"].toInteger(), qint64(0));
    const qint64 samples = aa == "msaa4" ? 4 : 1;
    QCOMPARE(opaque["gpu_bytes"].toInteger(), qint64(w) * h * (8 + 4) * samples);
    // The frame's memory is the registry's, entry by entry.
    qint64 sum = 0;
    for (const QJsonValue& v : j["resources"].toArray()) sum += v.toObject()["bytes"].toInteger();
    QCOMPARE(j["gpu_bytes"].toInteger(), sum);
    QVERIFY(sum >= opaque["gpu_bytes"].toInteger());
    QVERIFY(j["triangles"].toInteger() > 0);
    QVERIFY(j["draw_calls"].toInteger() > 0);
  }

  void statsIsForOneFrame() {
    expectError({"render", demo_, "--frames", "0-1", "--out", path("sq/f_%03d.png"), "--stats", path("s.json")}, 2,
                {"--stats"});
  }

  // ---- errors: non-zero exit, one line naming the problem ------------------------------

  void unknownCommand() { expectError({"frobnicate", demo_}, 2, {"frobnicate"}); }

  void unknownOption() {
    expectError({"info", demo_, "--colour"}, 2, {"--colour"});
    expectError({"render", demo_, "--out", path("x.png"), "--fast"}, 2, {"--fast"});
    expectError({"import", kMeshData + "/textured_quad.obj", demo_, "--up", "sideways"}, 2, {"--up"});
    expectError({"render", demo_, "--out"}, 2, {"--out"});  // option without its value
  }

  void missingScene() {
    expectError({"info", path("missing.hscene")}, 1, {"missing.hscene", "not found"});
    expectError({"render", path("missing.hscene"), "--out", path("m.png")}, 1, {"missing.hscene"});
    expectError({"import", kMeshData + "/textured_quad.obj", path("missing.hscene")}, 1, {"missing.hscene"});
    expectError({"set", "settings.exposure_ev100", "2", path("missing.hscene")}, 1, {"missing.hscene"});
    QVERIFY(!fs::exists(path("missing.hscene").toStdString()));
    QVERIFY(!fs::exists(path("m.png").toStdString()));
  }

  void badSize() {
    for (const QString& size : {QString("10y"), QString("0x10"), QString("99999x10"), QString("x"), QString("-5x5"), QString("12x")})
      expectError({"render", demo_, "--out", path("s.png"), "--size", size}, 2, {size});
    QVERIFY(!fs::exists(path("s.png").toStdString()));
  }

  void unknownCamera() {
    expectError({"render", demo_, "--out", path("c.png"), "--camera", "Drone"}, 1, {"Drone", "Main Camera"});
    expectError({"render", demo_, "--out", path("c.png"), "--camera", "Sun"}, 1, {"Sun"});  // not a camera
    QVERIFY(!fs::exists(path("c.png").toStdString()));
  }

  // What the renderer refuses or clamps reaches the user: 140 point lights
  // in one place overflow the light clusters' cap of 128, and `render`
  // says so (render/render_problems.h) and still renders: a still on
  // stderr, a sequence with its notes on stdout.
  void renderPrintsTheRenderersProblems() {
    scene::SceneState s;
    s.settings.showGrid = false;
    for (int i = 0; i < 140; ++i) {
      scene::Entity lamp;
      lamp.id = scene::EntityId(100 + i);
      lamp.name = "Lamp " + std::to_string(i);
      lamp.light = scene::Light{};
      lamp.light->type = scene::Light::Type::Point;
      lamp.transform.translation = {0.01 * i, 0.0, 1.0};
      s.entities.emplace(lamp.id, lamp);
      s.roots.push_back(lamp.id);
    }
    scene::Entity cam;  // sequences render through a camera
    cam.id = 1;
    cam.name = "Camera";
    cam.camera = scene::Camera{};
    cam.transform = test::lookFrom({0.0, -8.0, 1.0}, {0.0, 0.0, 1.0});
    s.entities.emplace(cam.id, cam);
    s.roots.push_back(cam.id);
    const QString file = path("lamps.hscene");
    std::string error;
    QVERIFY2(scene::saveScene(s, file.toStdString(), error), error.c_str());
    const Run r = cli({"render", file, "--out", path("lamps.png"), "--size", "64x36"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("warning: lights:") && r.err.contains("more than 128"), qPrintable(r.err));
    // A sequence says it too (with its other notes, on stdout).
    const Run seq = cli({"render", file, "--frames", "0-1", "--out", path("lamps_%03d.png"), "--size", "64x36"});
    QVERIFY2(seq.code == 0, qPrintable(seq.err));
    QVERIFY2(seq.out.contains("warning: lights:") && seq.out.contains("more than 128"), qPrintable(seq.out));
  }

  // --mix-camera: two shots in one frame (the renderer's view groups),
  // mixed in linear light. --mix 0 is the first camera's frame and --mix 1
  // the second's, pixel for pixel (EXR, linear); 0.5 is their mean.
  void renderMixesTwoCameras() {
    auto pixels = [](const QString& file) {
      std::vector<float> px;
      auto in = OIIO::ImageInput::open(file.toStdString());
      if (!in) return px;
      const OIIO::ImageSpec spec = in->spec();
      px.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
      in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data());
      return px;
    };
    auto render = [&](const QString& name, const QStringList& extra) {
      const QString out = path(name);
      const Run r = cli(QStringList{"render", demo_, "--out", out, "--size", "64x36", "--no-grid", "--aa", "none"} + extra);
      return std::make_pair(r, pixels(out));
    };
    const auto [ra, a] = render("a.exr", {"--camera", "Main Camera"});
    const auto [rb, b] = render("b.exr", {"--camera", "Flight Camera"});
    QVERIFY2(ra.code == 0 && rb.code == 0, qPrintable(ra.err + rb.err));
    const auto [r0, m0] = render("m0.exr", {"--camera", "Main Camera", "--mix-camera", "Flight Camera", "--mix", "0"});
    const auto [r1, m1] = render("m1.exr", {"--camera", "Main Camera", "--mix-camera", "Flight Camera", "--mix", "1"});
    const auto [rh, mh] = render("mh.exr", {"--camera", "Main Camera", "--mix-camera", "Flight Camera"});
    QVERIFY2(r0.code == 0 && r1.code == 0 && rh.code == 0, qPrintable(r0.err + r1.err + rh.err));
    QVERIFY2(rh.out.contains("mixed with camera 'Flight Camera'"), qPrintable(rh.out));
    QVERIFY(!a.empty() && a.size() == b.size() && a.size() == m0.size() && a.size() == mh.size());
    double d0 = 0, d1 = 0, dh = 0, ab = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      d0 = std::max(d0, std::abs(double(m0[i]) - double(a[i])));
      d1 = std::max(d1, std::abs(double(m1[i]) - double(b[i])));
      // Half floats: the mean within their rounding.
      dh = std::max(dh, std::abs(double(mh[i]) - 0.5 * (double(a[i]) + double(b[i]))) / std::max(1.0, std::abs(double(mh[i]))));
      ab = std::max(ab, std::abs(double(a[i]) - double(b[i])));
    }
    QCOMPARE(d0, 0.0);
    QCOMPARE(d1, 0.0);
    QVERIFY2(dh < 2e-3, qPrintable(QString::number(dh)));
    QVERIFY(ab > 0.05);  // two different shots
    // A camera that is not there, and a sequence, are refused with the reason.
    const Run bad = cli({"render", demo_, "--out", path("x.png"), "--mix-camera", "Nobody"});
    QCOMPARE(bad.code, 1);
    QVERIFY2(bad.err.contains("no camera named 'Nobody'") && bad.err.contains("Main Camera"), qPrintable(bad.err));
    const Run seq = cli({"render", demo_, "--out", path("f_%05d.png"), "--frames", "0-1", "--mix-camera", "Flight Camera"});
    QCOMPARE(seq.code, 2);
    QVERIFY2(seq.err.contains("--mix-camera and --transition apply to one frame"), qPrintable(seq.err));
  }

  // post.auto_exposure (render/auto_exposure.h) through the CLI: a still
  // says the exposure it metered; a sequence's frame rendered alone is the
  // same file as after the frames before it (a pure function of the time).
  void renderWithAutomaticExposure() {
    const QString file = path("auto_exposure.hscene");
    QFile::remove(file);
    QVERIFY(QFile::copy(demo_, file));
    const Run set = cli({"set", "settings.post.auto_exposure.enabled", "true", file});
    QVERIFY2(set.code == 0, qPrintable(set.err));
    const Run still = cli({"render", file, "--out", path("auto.png"), "--size", "64x36", "--at", "2",
                           "--camera", "Main Camera"});
    QVERIFY2(still.code == 0, qPrintable(still.err));
    QVERIFY2(still.out.contains("automatic exposure EV100") && still.out.contains("(9 probes)"), qPrintable(still.out));
    QDir().mkpath(path("auto_run"));
    QDir().mkpath(path("auto_alone"));
    const QStringList common = {"--size", "64x36", "--camera", "Main Camera", "--layout", "mono"};
    const Run run = cli(QStringList{"render", file, "--frames", "117-120", "--out", path("auto_run/f_%05d.png")} + common);
    const Run alone = cli(QStringList{"render", file, "--frames", "120-120", "--out", path("auto_alone/f_%05d.png")} + common);
    QVERIFY2(run.code == 0 && alone.code == 0, qPrintable(run.err + alone.err));
    const std::string a = test::readFile(path("auto_run/f_00120.png").toStdString());
    const std::string b = test::readFile(path("auto_alone/f_00120.png").toStdString());
    QVERIFY(!a.empty());
    QVERIFY(a == b);
  }

  // A camera's own post settings (scene/camera_post.h): set, keyed and
  // given back to the scene with `inherit`; a still through the camera is
  // the still of a scene whose own settings hold those values (the same
  // PNG), a view of another camera is not changed.
  void cameraPostSettings() {
    const QString file = path("camera_post.hscene");
    QFile::remove(file);
    QVERIFY(QFile::copy(demo_, file));
    Run r = cli({"set", "Main Camera", "camera.post.tonemap", "none", file});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"set", "Main Camera", "camera.post.vignette.enabled", "true", file});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"set", "Main Camera", "camera.post.bloom.intensity", "0.3", file});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli({"key", "Main Camera", "camera.post.vignette.intensity", "0", "0.7", file});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    auto s = load(file);
    QVERIFY(s);
    const scene::EntityId cam = s->findByName("Main Camera");
    const auto& post = s->find(cam)->camera->post;
    QCOMPARE(post.size(), size_t(3));
    QCOMPARE(std::get<int64_t>(post.at("tonemap")), int64_t(scene::Tonemap::None));
    QCOMPARE(sequencer::keyTimes(s->sequence, cam, "camera.post.vignette.intensity"), std::vector<double>{0.0});
    // `info` lists them per camera (the demo's crane shot is graded apart too).
    r = cli({"info", file, "--json"});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const QJsonObject cameraPost = parseJson(r.out.toUtf8())["camera_post"].toObject();
    QCOMPARE(cameraPost["Main Camera"].toObject()["tonemap"].toString(), QString("None"));
    QCOMPARE(cameraPost["Crane Camera"].toObject()["vignette.enabled"].toString(), QString("true"));
    r = cli({"info", file});
    QVERIFY2(r.out.contains("camera post settings") && r.out.contains("Main Camera: ") &&
                 r.out.contains("tonemap None"),
             qPrintable(r.out));
    // Removed: the scene's value shows again; a second time says so.
    r = cli({"set", "Main Camera", "camera.post.bloom.intensity", "inherit", file});
    QVERIFY2(r.code == 0 && r.out.contains("removed"), qPrintable(r.out + r.err));
    r = cli({"set", "Main Camera", "camera.post.bloom.intensity", "inherit", file});
    QVERIFY2(r.code == 0 && r.out.contains("unchanged"), qPrintable(r.out + r.err));
    QCOMPARE(load(file)->find(cam)->camera->post.count("bloom.intensity"), size_t(0));
    const std::string before = readFile(file.toStdString());
    expectError({"set", "Sun", "camera.post.tonemap", "agx", file}, 1, {"Sun", "camera"});
    expectError({"set", "Main Camera", "camera.post.shadows", "true", file}, 1, {"camera.post.shadows"});
    expectError({"set", "Main Camera", "camera.post.bloom.intensity", "-1", file}, 1, {"camera.post.bloom.intensity"});
    expectError({"set", "Main Camera", "camera.post.tonemap", "sepia", file}, 1, {"sepia"});
    QCOMPARE(readFile(file.toStdString()), before);

    // The same picture as the scene's own settings with those values.
    const QString scene = path("camera_post_scene.hscene");
    QFile::remove(scene);
    QVERIFY(QFile::copy(demo_, scene));
    for (const QStringList& set : {QStringList{"settings.tonemap", "none"}, QStringList{"settings.post.vignette.enabled", "true"},
                                   QStringList{"settings.post.vignette.intensity", "0.7"}}) {
      r = cli({"set", set[0], set[1], scene});
      QVERIFY2(r.code == 0, qPrintable(r.err));
    }
    // At t = 0, where the key holds the vignette's intensity.
    const QStringList still = {"--size", "96x54", "--camera", "Main Camera", "--at", "0"};
    r = cli(QStringList{"render", file, "--out", path("through_camera.png")} + still);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli(QStringList{"render", scene, "--out", path("scene_settings.png")} + still);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = cli(QStringList{"render", demo_, "--out", path("demo_settings.png")} + still);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const std::string through = test::readFile(path("through_camera.png").toStdString());
    QVERIFY(!through.empty());
    QVERIFY(through == test::readFile(path("scene_settings.png").toStdString()));
    QVERIFY(through != test::readFile(path("demo_settings.png").toStdString()));
  }

  void renderToUnknownExtension() {
    expectError({"render", demo_, "--out", path("frame.bmp")}, 1, {"frame.bmp", ".png"});
    expectError({"render", demo_, "--out", path("frame")}, 1, {"frame"});
    QVERIFY(!fs::exists(path("frame.bmp").toStdString()));
  }

  void renderIntoAMissingFolder() {
    const QString out = path("no/such/folder/frame.png");
    expectError({"render", demo_, "--out", out, "--size", "32x32"}, 1, {out, "does not exist"});
    QVERIFY(!fs::exists(path("no").toStdString()));
  }

  void badSceneFile() {
    QFile f(path("text.hscene"));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("not a scene\n");
    f.close();
    expectError({"info", path("text.hscene")}, 1, {"text.hscene", "not an SQLite database"});
    expectError({"render", path("text.hscene"), "--out", path("t.png")}, 1, {"text.hscene"});
  }
};

QTEST_GUILESS_MAIN(TestCli)
#include "test_cli.moc"
