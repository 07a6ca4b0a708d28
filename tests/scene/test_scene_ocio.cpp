// OpenColorIO configs in the document (scene/ocio_config.h): a studio
// config read with the LUT files under its search paths into one bundle,
// its displays and views listed, its view transform matching what
// OpenColorIO makes of the original config in its folder; stored in the
// .hscene (the studio's folder can go), saved once, loaded back byte for
// byte; refused with a message naming the file when malformed, missing a
// LUT, without a scene-linear role, or not a file; a damaged blob or a
// display the config lacks costs the config (or the choice) with a warning,
// never the scene; the display and view fields refuse names the config
// lacks; Import is one undo step; the ACES path converts linear Rec.709 to
// ACES2065-1 as the primaries and the Bradford adaptation say; a part a
// killed writer left in the cache folder is swept by the next writer.
#include <QtTest>

#include <filesystem>

#include <glm/gtc/matrix_inverse.hpp>

#include "core/scratch_files.h"
#include "dead_scratch.h"
#include "scene/demo_post.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/hscene_file.h"
#include "scene/lut_processor.h"
#include "scene/ocio_config.h"
#include "scene/operations.h"
#include "scene/scene_json.h"
#include "hscene_sql.h"
#include "ocio_files.h"

using namespace hs;
namespace OCIO = OCIO_NAMESPACE;

namespace {

glm::dvec3 apply(const OCIO::ConstProcessorRcPtr& p, glm::dvec3 c) {
  float rgb[3] = {float(c.r), float(c.g), float(c.b)};
  p->getDefaultCPUProcessor()->applyRGB(rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

// RGB -> XYZ of a space from its primaries' and white's xy.
glm::dmat3 rgbToXyz(glm::dvec2 r, glm::dvec2 g, glm::dvec2 b, glm::dvec2 w) {
  const auto xyz = [](glm::dvec2 c) { return glm::dvec3(c.x / c.y, 1.0, (1.0 - c.x - c.y) / c.y); };
  const glm::dmat3 p(xyz(r), xyz(g), xyz(b));  // columns
  const glm::dvec3 s = glm::inverse(p) * xyz(w);
  return glm::dmat3(p[0] * s.x, p[1] * s.y, p[2] * s.z);
}

}  // namespace

class TestSceneOcio : public QObject {
  Q_OBJECT
  std::filesystem::path dir_;

  scene::SceneState sceneWith(const scene::OcioConfigData& config) {
    scene::SceneState s;
    scene::Entity e;
    e.id = 1;
    e.name = "Anchor";
    s.entities[1] = e;
    s.roots = {1};
    s.settings.post.ocioConfig = config;
    s.settings.post.viewTransform = true;
    s.settings.post.display = "Projector";
    return s;
  }
  std::optional<scene::OcioConfigData> studio(std::string& error) {
    return scene::readOcioConfig(test::writeStudioConfig(dir_ / "studio"), error);
  }
  // The message readOcioConfig gives for config `text` written as `name` in
  // a folder with the film LUT under luts/.
  std::string refusal(const std::string& name, const std::string& text) {
    const std::filesystem::path folder = dir_ / ("bad_" + name);
    std::filesystem::create_directories(folder / "luts");
    test::writeText((folder / "luts" / "film.spi1d").string(), test::filmSpi1d(64));
    const std::string path = (folder / name).string();
    test::writeText(path, text);
    std::string error;
    if (scene::readOcioConfig(path, error)) return "";
    qInfo("%s: %s", name.c_str(), error.c_str());
    return error;
  }

 private slots:
  void initTestCase() {
    dir_ = std::filesystem::temp_directory_path() / ("hs_test_scene_ocio_" + std::to_string(QCoreApplication::applicationPid()));
    std::filesystem::create_directories(dir_);
  }
  void cleanupTestCase() { std::filesystem::remove_all(dir_); }

  void readsTheConfigWithItsLuts() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY2(c, error.c_str());
    QCOMPARE(c->fileName, std::string("studio.ocio"));
    QCOMPARE(c->files.size(), size_t(2));
    QCOMPARE(c->files[0].path, std::string(scene::kOcioConfigEntry));
    QCOMPARE(c->files[1].path, std::string("search0/film.spi1d"));
    QVERIFY(*c->files[1].bytes == test::filmSpi1d());
    QCOMPARE(c->contentHash, scene::ocioBundleHash(c->files));
    const scene::OcioConfigSummary s = scene::ocioSummary(*c);
    QVERIFY2(s.error.empty(), s.error.c_str());
    QCOMPARE(s.defaultDisplay, std::string("Studio sRGB"));
    QCOMPARE(s.sourceRole, std::string("scene_linear"));
    QCOMPARE(s.displays.size(), size_t(2));
    QCOMPARE(s.displays[0].views, (std::vector<std::string>{"Film", "Raw"}));
    QCOMPARE(s.displays[0].defaultView, std::string("Film"));
    QCOMPARE(s.displays[1].name, std::string("Projector"));
    // Empty names are the defaults; unknown ones are named with what there is.
    std::string e;
    const scene::DisplayView dv = scene::resolveDisplayView(*c, "", "", e);
    QVERIFY(e.empty() && dv.display == "Studio sRGB" && dv.view == "Film");
    scene::resolveDisplayView(*c, "Cinema", "", e);
    QVERIFY2(e.find("no display 'Cinema' (it has 'Studio sRGB', 'Projector')") != std::string::npos, e.c_str());
    scene::resolveDisplayView(*c, "Projector", "Raw", e);
    QVERIFY2(e.find("display 'Projector' has no view 'Raw' (it has 'Film')") != std::string::npos, e.c_str());
  }

  void theViewTransformIsOpenColorIosOwn() {
    // The bundle's processor against OpenColorIO reading the original
    // config in its folder, and against the curve the LUT was written from.
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY2(c, error.c_str());
    const OCIO::ConstProcessorRcPtr bundled = scene::viewTransformProcessor(*c, "", "", error);
    QVERIFY2(bundled, error.c_str());
    const OCIO::ConstConfigRcPtr original = OCIO::Config::CreateFromFile((dir_ / "studio" / "studio.ocio").c_str());
    const OCIO::ConstProcessorRcPtr direct =
        original->getProcessor(OCIO::ROLE_SCENE_LINEAR, "Studio sRGB", "Film", OCIO::TRANSFORM_DIR_FORWARD);
    double worstCurve = 0.0;
    for (double x : {0.0, 0.01, 0.18, 0.5, 1.0, 2.5, 8.0, 15.9}) {
      const glm::dvec3 a = apply(bundled, glm::dvec3(x, x * 0.5, x * 0.25));
      const glm::dvec3 b = apply(direct, glm::dvec3(x, x * 0.5, x * 0.25));
      QCOMPARE(a, b);
      worstCurve = std::max(worstCurve, std::abs(a.r - test::filmCurve(x)));
    }
    qInfo("film view against its curve: largest difference %.2e (the 4096-entry table's interpolation)", worstCurve);
    QVERIFY(worstCurve < 1e-3);
    // The raw view is data: left as it is.
    const OCIO::ConstProcessorRcPtr raw = scene::viewTransformProcessor(*c, "", "Raw", error);
    QVERIFY(raw);
    QCOMPARE(apply(raw, glm::dvec3(0.25, 3.0, 0.5)), glm::dvec3(0.25, 3.0, 0.5));
    QVERIFY(!scene::viewTransformProcessor(*c, "Nowhere", "", error));
    QVERIFY(error.find("no display 'Nowhere'") != std::string::npos);
  }

  void theAcesPathConvertsRec709ToAp0() {
    // Independently: sRGB primaries (D65) to XYZ, Bradford to D60, XYZ to
    // AP0 (ACES2065-1's primaries and white).
    const glm::dmat3 srgb = rgbToXyz({0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290});
    const glm::dmat3 ap0 = rgbToXyz({0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770}, {0.32168, 0.33767});
    const glm::dmat3 bradford = glm::transpose(glm::dmat3(0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389,
                                                          -0.0685, 1.0296));
    const auto xyz = [](glm::dvec2 c) { return glm::dvec3(c.x / c.y, 1.0, (1.0 - c.x - c.y) / c.y); };
    const glm::dvec3 from = bradford * xyz({0.3127, 0.3290}), to = bradford * xyz({0.32168, 0.33767});
    const glm::dmat3 adapt = glm::inverse(bradford) * glm::dmat3(to.x / from.x, 0, 0, 0, to.y / from.y, 0, 0, 0,
                                                                 to.z / from.z) * bradford;
    const glm::dmat3 expected = glm::inverse(ap0) * adapt * srgb;
    const std::filesystem::path folder = dir_ / "aces";
    std::filesystem::create_directories(folder);
    test::writeText((folder / "aces.ocio").string(), test::acesConfigText());
    std::string error;
    const std::optional<scene::OcioConfigData> c = scene::readOcioConfig((folder / "aces.ocio").string(), error);
    QVERIFY2(c, error.c_str());
    QCOMPARE(scene::ocioSummary(*c).sourceRole, std::string("aces_interchange"));
    const OCIO::ConstProcessorRcPtr p = scene::viewTransformProcessor(*c, "", "", error);
    QVERIFY2(p, error.c_str());
    const glm::dmat3 unadapted = glm::inverse(ap0) * srgb;  // what forgetting the white's change gives
    double worst = 0.0, worstUnadapted = 0.0;
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 unit(0.0);
      unit[k] = 1.0;
      const glm::dvec3 got = apply(p, unit);
      for (int i = 0; i < 3; ++i) {
        worst = std::max(worst, std::abs(got[i] - expected[k][i]));
        worstUnadapted = std::max(worstUnadapted, std::abs(got[i] - unadapted[k][i]));
      }
    }
    qInfo("linear Rec.709 to ACES2065-1: largest difference to the derived matrix %.2e (to one without the "
          "white's adaptation %.2e)",
          worst, worstUnadapted);
    // The published matrix and this derivation (four-digit white points,
    // float processing) agree to about 2e-4; a missing adaptation is far off.
    QVERIFY(worst < 5e-4);
    QVERIFY(worstUnadapted > 20 * worst);
  }

  void badConfigsAreRefusedByName() {
    // Malformed YAML.
    std::string e = refusal("malformed.ocio", "ocio_profile_version: 2\nroles: [unclosed\n");
    QVERIFY(e.find("malformed.ocio: OpenColorIO cannot read it") != std::string::npos);
    QVERIFY(e.find('\n') == std::string::npos);
    // Truncated: the colour spaces cut off (the view names one that is gone).
    const std::string full = test::studioConfigText();
    e = refusal("truncated.ocio", full.substr(0, full.find("  - !<ColorSpace>\n    name: film")));
    QVERIFY2(e.find("truncated.ocio") != std::string::npos && e.find("film") != std::string::npos, e.c_str());
    // A LUT that is not under the search path.
    e = refusal("missing_lut.ocio", test::studioConfigText("luts", "gone.spi1d"));
    QVERIFY2(e.find("missing_lut.ocio") != std::string::npos && e.find("gone.spi1d") != std::string::npos,
             e.c_str());
    // No colour space for the renderer's light to enter as.
    e = refusal("no_role.ocio", test::studioConfigText("luts", "film.spi1d", "texture_paint"));
    QVERIFY2(e.find("neither a 'scene_linear' nor an 'aces_interchange' role") != std::string::npos, e.c_str());
    // Empty, a folder, a missing file, a LUT passed as a config.
    QVERIFY(refusal("empty.ocio", "").find("empty.ocio: the file is empty") != std::string::npos);
    std::string error;
    QVERIFY(!scene::readOcioConfig(dir_.string(), error));
    QVERIFY(error.find("a folder") != std::string::npos);
    QVERIFY(!scene::readOcioConfig((dir_ / "nothing.ocio").string(), error));
    QVERIFY(error.find("nothing.ocio: cannot open it") != std::string::npos);
    QVERIFY(!refusal("lut.ocio", test::filmSpi1d(16)).empty());
  }

  void aCancelledImportReadsNothing() {
    hs::Progress progress;
    std::vector<double> fractions;
    hs::Progress watched([&](double f, std::string_view) { fractions.push_back(f); });
    std::string error;
    QVERIFY(scene::readOcioConfig(test::writeStudioConfig(dir_ / "progress"), error, &watched));
    QVERIFY(fractions.size() >= 2 && std::is_sorted(fractions.begin(), fractions.end()));
    progress.cancel();
    QVERIFY(!scene::readOcioConfig(test::writeStudioConfig(dir_ / "cancelled"), error, &progress));
    QVERIFY2(error.find("the import was cancelled") != std::string::npos, error.c_str());
  }

  void theStudioFolderCanGo() {
    // Stored in the scene: the config and its LUT are not needed again,
    // and the bundle's hash is the same wherever it is read.
    const std::filesystem::path folder = dir_ / "moving";
    std::string error;
    const std::optional<scene::OcioConfigData> c = scene::readOcioConfig(test::writeStudioConfig(folder), error);
    QVERIFY2(c, error.c_str());
    const std::string path = (dir_ / "stored.hscene").string();
    scene::SaveReport report;
    QVERIFY2(scene::saveScene(sceneWith(*c), path, error, &report), error.c_str());
    QCOMPARE(report.blobsWritten, size_t(2));
    std::filesystem::remove_all(folder);
    scene::LoadReport load;
    std::optional<scene::SceneState> back = scene::loadScene(path, error, nullptr, &load);
    QVERIFY2(back, error.c_str());
    QVERIFY(load.warnings.empty());
    const scene::OcioConfigData& got = back->settings.post.ocioConfig;
    QVERIFY(got == *c && got.loaded());
    for (size_t i = 0; i < got.files.size(); ++i) QVERIFY(*got.files[i].bytes == *c->files[i].bytes);
    QVERIFY(back->settings.post.viewTransform);
    QCOMPARE(back->settings.post.display, std::string("Projector"));
    QVERIFY(scene::canonicalJson(*back) == scene::canonicalJson(sceneWith(*c)));
    QCOMPARE(scene::sceneFileVersion(path), scene::kSceneFormatVersion);
    QVERIFY(scene::viewTransformProcessor(got, "Projector", "Film", error));
    // Saved again: nothing rewritten; without the config its blobs go.
    scene::SaveReport again;
    QVERIFY(scene::saveScene(*back, path, error, &again));
    QCOMPARE(again.blobsWritten, size_t(0));
    scene::SceneState none = *back;
    none.settings.post.ocioConfig = {};
    QVERIFY(scene::saveScene(none, path, error));
    back = scene::loadScene(path, error, nullptr, &load);
    QVERIFY(back && back->settings.post.ocioConfig.empty() && load.warnings.empty());
  }

  // The cache folder OpenColorIO reads from is written through parts
  // renamed into place; a writer killed in between leaves its part, and the
  // next writer of that file removes it (a live writer's stays).
  void aKilledWritersPartIsSwept() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY2(c, error.c_str());
    const std::filesystem::path folder = scene::ocioCacheFolder(*c, error);
    QVERIFY2(!folder.empty(), error.c_str());
    const std::string prefix = std::string(scene::kOcioConfigEntry) + ".part-";
    const std::string live = scratchName(prefix);
    const test::DeadScratch dead = test::asDeadProcess(scratchName(prefix));
    QVERIFY(!dead.name.empty());
    test::writeText((folder / live).string(), "half a config");
    test::writeText((folder / dead.name).string(), "half a config");
    std::filesystem::remove(folder / scene::kOcioConfigEntry);  // so it is written again
    QVERIFY2(!scene::ocioCacheFolder(*c, error).empty(), error.c_str());
    QVERIFY(std::filesystem::exists(folder / scene::kOcioConfigEntry));
    QVERIFY2(!std::filesystem::exists(folder / dead.name), dead.name.c_str());
    QVERIFY(std::filesystem::exists(folder / live));
    std::filesystem::remove(folder / live);
    for (const auto& e : std::filesystem::directory_iterator(folder))
      QVERIFY2(e.path().filename().string().find(".part") == std::string::npos, e.path().c_str());
    QVERIFY(scene::viewTransformProcessor(*c, "Projector", "Film", error));
  }

  void aDamagedBlobCostsTheConfigNotTheScene() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY(c);
    const std::string key = scene::ocioBlobKey(c->files[1].contentHash);  // the LUT
    for (const char* damage : {"UPDATE blobs SET data = X'00112233' WHERE key = '%1'",
                               "DELETE FROM blobs WHERE key = '%1'"}) {
      const std::string path = (dir_ / "damaged.hscene").string();
      QVERIFY(scene::saveScene(sceneWith(*c), path, error));
      test::sql(path, QString(damage).arg(QString::fromStdString(key)).toStdString());
      scene::LoadReport report;
      const std::optional<scene::SceneState> s = scene::loadScene(path, error, nullptr, &report);
      QVERIFY2(s, error.c_str());
      QCOMPARE(s->entities.size(), size_t(1));
      QVERIFY(s->settings.post.ocioConfig.empty());
      QVERIFY(!s->settings.post.viewTransform);
      QCOMPARE(report.warnings.size(), size_t(1));
      qInfo("%s", report.warnings[0].c_str());
      QVERIFY(report.warnings[0].find("OpenColorIO config 'studio.ocio', file 'search0/film.spi1d'") !=
              std::string::npos);
      QVERIFY(report.warnings[0].find("renders with its tone map") != std::string::npos);
    }
  }

  void anUnknownDisplayFallsBackWithAWarning() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY(c);
    scene::SceneState s = sceneWith(*c);
    s.settings.post.display = "Cinema";  // as a hand-edited file could say
    const std::string path = (dir_ / "unknown_display.hscene").string();
    QVERIFY(scene::saveScene(s, path, error));
    scene::LoadReport report;
    const std::optional<scene::SceneState> back = scene::loadScene(path, error, nullptr, &report);
    QVERIFY2(back, error.c_str());
    QCOMPARE(report.warnings.size(), size_t(1));
    QVERIFY(report.warnings[0].find("no display 'Cinema'") != std::string::npos);
    QVERIFY(back->settings.post.display.empty() && back->settings.post.ocioConfig == *c);
  }

  void theFieldsRefuseNamesTheConfigLacks() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY(c);
    scene::Document doc;
    QVERIFY(scene::ops::setOcioConfig(doc, *c));
    const scene::SettingsField* display = nullptr;
    const scene::SettingsField* view = nullptr;
    for (const auto& f : scene::settingsFields()) {
      if (f.key == "post.view_transform.display") display = &f;
      if (f.key == "post.view_transform.view") view = &f;
    }
    QVERIFY(display && view);
    scene::ops::FieldChange change;
    scene::ops::setSettingsField(doc, *display, scene::FieldValue(std::string("Cinema")), {}, &change);
    QVERIFY2(change.message.find("no display 'Cinema' (it has 'Studio sRGB', 'Projector'); unchanged") !=
                 std::string::npos,
             change.message.c_str());
    QVERIFY(doc.state().settings.post.display.empty());
    QVERIFY(scene::ops::setSettingsField(doc, *display, scene::FieldValue(std::string("Projector"))));
    QCOMPARE(doc.state().settings.post.display, std::string("Projector"));
    scene::ops::setSettingsField(doc, *view, scene::FieldValue(std::string("Raw")), {}, &change);
    QVERIFY2(change.message.find("has no view 'Raw'") != std::string::npos &&
                 change.message.find("unchanged") != std::string::npos,
             change.message.c_str());
    QVERIFY(doc.state().settings.post.view.empty());
    // Without a config there is nothing to check against.
    scene::Document empty;
    QVERIFY(scene::ops::setSettingsField(empty, *display, scene::FieldValue(std::string("Anything"))));
  }

  void theDemosConfigIsSound() {
    // Made in code, checked as an import would be; stored off, so the demo
    // keeps its tone map until the Post dock turns the view on.
    const scene::OcioConfigData demo = scene::demoOcioConfig();
    const std::string problem = scene::ocioConfigProblem("demo", demo);
    QVERIFY2(problem.empty(), problem.c_str());
    std::string error;
    const OCIO::ConstProcessorRcPtr film = scene::viewTransformProcessor(demo, "", "", error);
    QVERIFY2(film, error.c_str());
    // Black stays black, 18 % grey lands in the mid-tones, 32 is white.
    QVERIFY(apply(film, glm::dvec3(0.0)).g < 1e-3);
    const double mid = apply(film, glm::dvec3(0.18)).g;
    QVERIFY2(mid > 0.3 && mid < 0.6, std::to_string(mid).c_str());
    QVERIFY(apply(film, glm::dvec3(32.0)).g > 0.999);
    scene::SceneState s;
    scene::addDemoPost(s);
    QVERIFY(s.settings.post.ocioConfig == demo && !s.settings.post.viewTransform);
  }

  void importIsOneUndoStep() {
    std::string error;
    const std::optional<scene::OcioConfigData> c = studio(error);
    QVERIFY(c);
    scene::Document doc;
    QVERIFY(scene::ops::setOcioConfig(doc, *c));
    QVERIFY(doc.state().settings.post.viewTransform);
    QCOMPARE(doc.state().settings.post.ocioConfig.fileName, std::string("studio.ocio"));
    doc.undoStack()->undo();
    QVERIFY(doc.state().settings.post.ocioConfig.empty() && !doc.state().settings.post.viewTransform);
    doc.undoStack()->redo();
    QVERIFY(doc.state().settings.post.ocioConfig.loaded());
    QVERIFY(scene::ops::setOcioConfig(doc, {}));
    QVERIFY(doc.state().settings.post.ocioConfig.empty() && !doc.state().settings.post.viewTransform);
    QVERIFY(!scene::ops::setOcioConfig(doc, {}));  // nothing to remove: no step
  }
};

QTEST_GUILESS_MAIN(TestSceneOcio)
#include "test_scene_ocio.moc"
