// The grading LUT on the GPU (render/color_lut.h: OpenColorIO's shader
// generator and its tables in the tone map pass) against OpenColorIO's CPU
// processor on the renderer's own HDR image (tests/common/post_reference.h
// runs the rest of the chain): an identity .cube leaves the image as it was
// within 1/255; a 3D look, a 1D table and a half-mixed look match the CPU
// within 1/255. A stored LUT that is off costs nothing (no program with it,
// the same image as no LUT); a LUT OpenColorIO cannot make a shader for is
// left out of the frame, not a stop. A config's view transform (the same
// shader generator, in the tone map's place) matches OpenColorIO's CPU
// processor within 1/255, alone and with a LUT in the same program; a raw
// (data) view passes linear values out as code values; one stored but off
// costs nothing; a
// display the config lacks is reported once and the tone map used.
#include <QtTest>

#include <filesystem>

#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/color_lut.h"
#include "scene/lut_processor.h"
#include "scene/ocio_config.h"
#include "look_from.h"
#include "lut_files.h"
#include "ocio_files.h"
#include "pass_stats.h"
#include "post_reference.h"
#include "scene_parts.h"

using namespace hs;

namespace {

// Colours across the range: a lit ground, saturated balls, an HDR sky.
scene::SceneState colourScene() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::AgX;
  s.settings.skyZenith = {2.0f, 3.5f, 6.0f};
  s.settings.skyHorizon = {0.6f, 0.7f, 0.8f};
  test::addMeshAsset(s, 1, "Ground", mesh::gridPlane(60.0f, 1), {0.4f, 0.35f, 0.3f});
  test::addMeshEntity(s, 1, "Ground", 1);
  const glm::vec3 colours[] = {{0.8f, 0.1f, 0.1f}, {0.1f, 0.7f, 0.2f}, {0.1f, 0.2f, 0.9f}, {0.9f, 0.9f, 0.9f}};
  for (int i = 0; i < 4; ++i) {
    test::addMeshAsset(s, 10 + i, "Ball " + std::to_string(i), mesh::uvSphere(0.8f, 24, 12), colours[i]);
    test::addMeshEntity(s, 10 + i, "Ball " + std::to_string(i), 10 + i, {-3.0 + 2.0 * i, 0.0, 0.8});
  }
  test::addSun(s, 100, {50, 0, -30});
  return s;
}

render::RenderView view() {
  render::RenderView v;
  v.width = 192;
  v.height = 108;
  v.fovY = glm::radians(55.0);
  v.eye = {0.0, -9.0, 2.5};
  v.orientation = test::lookFrom(v.eye, {0.0, 0.0, 1.2}).rotation;
  return v;
}

std::pair<int, double> compare8(const Image& a, const Image& b) {
  int worst = 0;
  size_t over = 0, n = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) {
    if (i % 4 == 3) continue;
    const int d = std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
    worst = std::max(worst, d);
    over += d > 0;
    ++n;
  }
  return {worst, double(over) / double(std::max<size_t>(n, 1))};
}

}  // namespace

class TestPostLut : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;
  std::filesystem::path dir_;

  scene::LutData lutFrom(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    if (!test::writeText(path, text)) return {};
    std::string error;
    std::optional<scene::LutData> lut = scene::readLutFile(path, error);
    if (!lut) qWarning("%s", error.c_str());
    return lut ? *lut : scene::LutData{};
  }

  scene::OcioConfigData studio() {
    std::string error;
    std::optional<scene::OcioConfigData> c = scene::readOcioConfig(test::writeStudioConfig(dir_ / "studio"), error);
    if (!c) qWarning("%s", error.c_str());
    return c ? *c : scene::OcioConfigData{};
  }

  // The renderer's output with the view transform `s` asks for against
  // OpenColorIO's CPU processors (the view's, and the LUT's when one is on)
  // in the CPU reference; the largest difference in 1/255.
  int viewDifferenceToOcioCpu(const scene::SceneState& s, const char* what) {
    const scene::PostSettings& post = s.settings.post;
    std::string error;
    const OCIO_NAMESPACE::ConstProcessorRcPtr transform =
        scene::viewTransformProcessor(post.ocioConfig, post.display, post.view, error);
    OCIO_NAMESPACE::ConstProcessorRcPtr lut;
    if (post.lutEnabled) lut = scene::lutProcessor(post.lut, error);
    if (!transform || (post.lutEnabled && !lut)) {
      qWarning("%s", error.c_str());
      return 1000;
    }
    const auto cpuOf = [](const OCIO_NAMESPACE::ConstProcessorRcPtr& p) -> test::LutRef {
      if (!p) return {};
      return [cpu = p->getDefaultCPUProcessor()](glm::dvec3 c) {
        float rgb[3] = {float(c.r), float(c.g), float(c.b)};
        cpu->applyRGB(rgb);
        return glm::dvec3(rgb[0], rgb[1], rgb[2]);
      };
    };
    const Image hdr = r_.render(s, view(), true);
    const Image out = r_.render(s, view(), false);
    const auto [worst, share] =
        compare8(out, test::postReference(hdr, s.settings, s.time.frame, cpuOf(lut), cpuOf(transform)));
    qInfo("%s: largest difference to OpenColorIO's CPU processor %d/255 (%.3f%% of the channels differ)", what,
          worst, 100.0 * share);
    return worst;
  }

  // The renderer's output with `lut` against OpenColorIO's CPU processor
  // applied in the CPU reference; the largest difference in 1/255.
  int differenceToOcioCpu(scene::SceneState s, const scene::LutData& lut, const char* what) {
    s.settings.post.lut = lut;
    s.settings.post.lutEnabled = true;
    std::string error;
    const OCIO_NAMESPACE::ConstProcessorRcPtr processor = scene::lutProcessor(lut, error);
    if (!processor) {
      qWarning("%s", error.c_str());
      return 1000;
    }
    const OCIO_NAMESPACE::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();
    const test::LutRef ocio = [&](glm::dvec3 c) {
      float rgb[3] = {float(c.r), float(c.g), float(c.b)};
      cpu->applyRGB(rgb);
      return glm::dvec3(rgb[0], rgb[1], rgb[2]);
    };
    const Image hdr = r_.render(s, view(), true);
    const Image out = r_.render(s, view(), false);
    const auto [worst, share] = compare8(out, test::postReference(hdr, s.settings, s.time.frame, ocio));
    qInfo("%s: largest difference to OpenColorIO's CPU processor %d/255 (%.3f%% of the channels differ)", what,
          worst, 100.0 * share);
    return worst;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    dir_ = std::filesystem::temp_directory_path() / ("hs_test_post_lut_" + std::to_string(QCoreApplication::applicationPid()));
    std::filesystem::create_directories(dir_);
  }
  void cleanupTestCase() { std::filesystem::remove_all(dir_); }

  void identityLutLeavesTheImageUnchanged() {
    const scene::LutData identity = lutFrom("identity.cube", test::cube3dText(33, test::identityLook));
    QVERIFY(!identity.empty());
    scene::SceneState s = colourScene();
    const Image plain = r_.render(s, view());
    s.settings.post.lut = identity;
    s.settings.post.lutEnabled = true;
    render::FrameStats stats;
    const Image graded = r_.render(s, view(), false, &stats);
    const auto [worst, share] = compare8(graded, plain);
    qInfo("identity LUT: largest difference %d/255, %.3f%% of the channels differ", worst, 100.0 * share);
    QVERIFY(worst <= 1);
    // It was applied: the program with OpenColorIO's function was built.
    bool withLut = false;
    for (const render::BuiltProgram& p : r_.renderer().builtPrograms())
      withLut |= std::find(p.defines.begin(), p.defines.end(), "HS_LUT") != p.defines.end();
    QVERIFY(withLut);
  }

  void cubeLutMatchesOpenColorIoOnTheCpu() {
    // 17 points per axis: most pixels fall between entries, so the GPU's
    // interpolation is what is compared.
    const scene::LutData look = lutFrom("teal_orange.cube", test::cube3dText(17, test::tealOrangeLook));
    QVERIFY(!look.empty());
    const int worst = differenceToOcioCpu(colourScene(), look, "3D .cube");
    QVERIFY(worst <= 1);
    // And it changes the image well beyond that.
    scene::SceneState s = colourScene();
    const Image plain = r_.render(s, view());
    s.settings.post.lut = look;
    s.settings.post.lutEnabled = true;
    QVERIFY(compare8(r_.render(s, view()), plain).first > 10);
  }

  void oneDimensionalLutAndIntensity() {
    // A 1D table (OpenColorIO makes it a 1D or 2D texture, not a 3D one).
    const scene::LutData curve =
        lutFrom("curve.cube", test::cube1dText(1024, [](glm::dvec3 c) {
                  return glm::dvec3(std::pow(c.r, 0.8), std::pow(c.g, 1.1), 0.1 + 0.85 * c.b);
                }));
    QVERIFY(!curve.empty());
    QVERIFY(differenceToOcioCpu(colourScene(), curve, "1D .cube") <= 1);
    // Half mixed in, together with the grade before it and the vignette after it.
    scene::SceneState s = colourScene();
    s.settings.post.lutIntensity = 0.5f;
    s.settings.post.grade = true;
    s.settings.post.saturation = 1.2f;
    s.settings.post.vignette = true;
    const scene::LutData look = lutFrom("look.cube", test::cube3dText(33, test::tealOrangeLook));
    QVERIFY(differenceToOcioCpu(s, look, "3D .cube at intensity 0.5 with grade and vignette") <= 1);
  }

  // Off (even with a LUT stored): the same image as no LUT, no program with it.
  void storedButOffCostsNothing() {
    render::OffscreenRenderer fresh;  // a renderer that has never built a LUT program
    std::string error;
    QVERIFY2(fresh.initialize(error), error.c_str());
    scene::SceneState s = colourScene();
    const Image plain = fresh.render(s, view());
    s.settings.post.lut = lutFrom("off.cube", test::cube3dText(9, test::tealOrangeLook));
    s.settings.post.lutEnabled = false;
    QVERIFY(fresh.render(s, view()).rgba8 == plain.rgba8);
    for (const render::BuiltProgram& p : fresh.renderer().builtPrograms())
      QVERIFY(std::find(p.defines.begin(), p.defines.end(), "HS_LUT") == p.defines.end());
    // On without its bytes (a description whose blob was not loaded): left out, no stop.
    s.settings.post.lutEnabled = true;
    s.settings.post.lut.bytes.reset();
    QVERIFY(fresh.render(s, view()).rgba8 == plain.rgba8);
  }

  // A LUT the renderer cannot make (bytes OpenColorIO refuses, as a damaged
  // blob would hold): the frame is drawn without it and the problem,
  // naming the file, reaches the user once (Renderer::takeLutProblems, the
  // CLI's warnings and the editor's Messages through render_problems.h).
  void aLutThatCannotBeDrawnIsReportedOnce() {
    scene::SceneState s = colourScene();
    const Image plain = r_.render(s, view());
    (void)r_.renderer().takeLutProblems();
    const std::string bytes = "LUT_3D_SIZE 2\n0 0 0\n";  // four entries short
    s.settings.post.lut = scene::LutData{"damaged.cube", std::make_shared<const std::string>(bytes), 0x5eed};
    s.settings.post.lutEnabled = true;
    QVERIFY(r_.render(s, view()).rgba8 == plain.rgba8);
    const std::vector<std::string> problems = r_.renderer().takeLutProblems();
    QCOMPARE(problems.size(), size_t(1));
    QVERIFY2(problems[0].find("damaged.cube") != std::string::npos, problems[0].c_str());
    QVERIFY(r_.render(s, view()).rgba8 == plain.rgba8);
    QVERIFY(r_.renderer().takeLutProblems().empty());  // once, not every frame
    s.settings.post.lut = {};
    s.settings.post.lutEnabled = false;
    r_.render(s, view());
  }

  // Stored but off: the same image as none and no program with it; the
  // registry holds no view transform table.
  void viewTransformStoredButOffCostsNothing() {
    render::OffscreenRenderer fresh;
    std::string error;
    QVERIFY2(fresh.initialize(error), error.c_str());
    scene::SceneState s = colourScene();
    const Image plain = fresh.render(s, view());
    s.settings.post.ocioConfig = studio();
    QVERIFY(!s.settings.post.ocioConfig.empty());
    s.settings.post.viewTransform = false;
    QVERIFY(fresh.render(s, view()).rgba8 == plain.rgba8);
    for (const render::BuiltProgram& p : fresh.renderer().builtPrograms())
      QVERIFY(std::find(p.defines.begin(), p.defines.end(), "HS_VIEW_TRANSFORM") == p.defines.end());
    QVERIFY(test::allocationNamed(fresh.renderer(), "view_transform_tables").empty());
  }

  void viewTransformMatchesOpenColorIoOnTheCpu() {
    scene::SceneState s = colourScene();
    s.settings.exposureEv100 = 9.0f;  // a bright frame: the film curve's shoulder is used
    const Image toneMapped = r_.render(s, view());
    s.settings.post.ocioConfig = studio();
    s.settings.post.viewTransform = true;
    QVERIFY(viewDifferenceToOcioCpu(s, "film view (1D LUT under the config's search path)") <= 1);
    // It replaced the tone map: the image is another.
    QVERIFY(compare8(r_.render(s, view()), toneMapped).first > 10);
    QVERIFY(!test::allocationNamed(r_.renderer(), "view_transform_tables").empty());
    // With the grade and a 3D LUT in the same program (both OpenColorIO
    // functions side by side), on the other display.
    s.settings.post.display = "Projector";
    s.settings.post.grade = true;
    s.settings.post.saturation = 0.7f;
    s.settings.post.lut = lutFrom("with_view.cube", test::cube3dText(17, test::tealOrangeLook));
    s.settings.post.lutEnabled = true;
    QVERIFY(viewDifferenceToOcioCpu(s, "film view with a grade and a 3D LUT") <= 1);
    const Image withLut = r_.render(s, view());
    bool both = false;  // one program holds both of OpenColorIO's functions
    for (const render::BuiltProgram& p : r_.renderer().builtPrograms())
      both |= std::count(p.defines.begin(), p.defines.end(), "HS_LUT") &&
              std::count(p.defines.begin(), p.defines.end(), "HS_VIEW_TRANSFORM");
    QVERIFY(both);
    s.settings.post.lutEnabled = false;
    QVERIFY(compare8(r_.render(s, view()), withLut).first > 10);  // the LUT did change it
  }

  void rawViewShowsLinearValuesAsCodeValues() {
    // The raw view is data: scene light goes out as the display's code
    // values unchanged (clamped), as Blender's "Raw" view shows it: the
    // CPU reference with an identity transform, darker than no tone map
    // (which encodes to sRGB).
    scene::SceneState s = colourScene();
    s.settings.post.ocioConfig = studio();
    s.settings.post.viewTransform = true;
    s.settings.post.view = "Raw";
    const Image hdr = r_.render(s, view(), true);
    const Image raw = r_.render(s, view());
    const auto identity = [](glm::dvec3 c) { return c; };
    const auto [worst, share] = compare8(raw, test::postReference(hdr, s.settings, s.time.frame, {}, identity));
    qInfo("raw view against its CPU reference: largest difference %d/255 (%.3f%% of the channels)", worst,
          100.0 * share);
    QVERIFY(worst <= 1);
    s.settings.post.viewTransform = false;
    s.settings.tonemap = scene::Tonemap::None;
    QVERIFY(compare8(raw, r_.render(s, view())).first > 10);
  }

  void anUnknownDisplayIsReportedOnce() {
    // A camera's override can name a display the config lacks (the field
    // check knows no config there): the frame uses its tone map, the
    // problem reaches the user once.
    scene::SceneState s = colourScene();
    const Image toneMapped = r_.render(s, view());
    (void)r_.renderer().takeLutProblems();
    s.settings.post.ocioConfig = studio();
    s.settings.post.viewTransform = true;
    s.settings.post.display = "Cinema";
    QVERIFY(r_.render(s, view()).rgba8 == toneMapped.rgba8);
    std::vector<std::string> problems = r_.renderer().takeLutProblems();
    QCOMPARE(problems.size(), size_t(1));
    qInfo("%s", problems[0].c_str());
    QVERIFY(problems[0].find("no display 'Cinema'") != std::string::npos);
    QVERIFY(r_.render(s, view()).rgba8 == toneMapped.rgba8);
    QVERIFY(r_.renderer().takeLutProblems().empty());
    // On with no config stored: said once too.
    s.settings.post.ocioConfig = {};
    QVERIFY(r_.render(s, view()).rgba8 == toneMapped.rgba8);
    problems = r_.renderer().takeLutProblems();
    QCOMPARE(problems.size(), size_t(1));
    QVERIFY(problems[0].find("stores no OpenColorIO config") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestPostLut)
#include "test_post_lut.moc"
