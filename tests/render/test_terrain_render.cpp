// The CDLOD terrain renderer through the headless EGL backend on llvmpipe:
// no cracks where levels meet (no sky through a continuous surface), the
// UTM-coordinate equality (camera-relative: a terrain at 500 km / 4400 km
// renders as at the origin), the measured screen-space error against the
// full-resolution mesh within the bound, a brush dab uploading exactly its
// region, the paint weights on the GPU as the document's (four layers to a
// texel), holes drawn as holes and not pickable, and scenes without terrain
// not running the pass.
#include <QTemporaryDir>
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "image_compare.h"
#include "look_from.h"
#include "terrain_screen_error.h"
#include "render/gpu_terrain.h"
#include "render/offscreen_renderer.h"
#include "scene/document.h"
#include "scene/fields.h"
#include "scene/operations.h"
#include "scene/terrain_edits.h"
#include "scene/terrain_ops.h"
#include "scene/terrain_pick.h"
#include "terrain/noise.h"
#include "terrain/stroke.h"

using namespace hs;
using hs::test::lookFrom;

namespace {

const glm::vec3 kSky(1.0f, 0.0f, 1.0f);  // magenta: no terrain colour is anywhere near it

test::Rgba8Image toTest(const hs::Image& img) { return {img.width, img.height, img.rgba8}; }

// A rough terrain (ridged noise, 60 m of relief) with a sun and a camera;
// the sky, horizon and ground colours all magenta, no grid, no tone curve.
struct TerrainScene {
  scene::Document doc;
  scene::EntityId terrain = scene::kNoEntity;
  scene::EntityId camera = scene::kNoEntity;
  explicit TerrainScene(int samples, double size, glm::dvec3 at = glm::dvec3(0.0), double lodError = 1.0) {
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.tonemap = scene::Tonemap::None;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = kSky;
    s.settings.ambientIntensity = 0.0f;  // the ambient light is magenta too: keep it off the terrain
    doc.reset(std::move(s), {});
    scene::ops::addLight(doc, "Sun", lookFrom({0, 0, 0}, {0.4, 0.3, -1.0}), scene::Light{});
    scene::ops::NewTerrain spec;
    spec.samplesX = spec.samplesY = samples;
    spec.sizeMetres = glm::dvec2(size);
    spec.centre = at;
    spec.lodErrorPixels = lodError;
    std::string error;
    terrain = scene::ops::addTerrain(doc, spec, error);
    if (!terrain) qFatal("%s", error.c_str());
    terrain::Heightfield& hf = data().terrain().height;
    terrain::FractalNoise n;
    n.seed = 5;
    n.scale = size / 6.0;
    n.octaves = 8;
    std::vector<float> h(size_t(samples) * size_t(samples));
    for (int y = 0; y < samples; ++y)
      for (int x = 0; x < samples; ++x)
        h[size_t(y) * size_t(samples) + size_t(x)] =
            60.0f * (1.0f - std::abs(n.at(x * hf.spacing().x, y * hf.spacing().y)));
    hf.write(hf.bounds(), h);
    data().noteChanged(hf.bounds(), scene::kTerrainAll);
    scene::Camera c;
    c.verticalFovDeg = 40.0;
    c.nearClip = 0.5;
    camera = scene::ops::addCamera(doc, "Camera", scene::Transform{}, c);
  }
  scene::TerrainData& data() { return *scene::terrainOf(doc.state(), terrain)->data; }
  const scene::SceneState& state() const { return doc.state(); }
  glm::dvec3 origin() const { return scene::terrainWorldOrigin(doc.state(), terrain); }
  void look(glm::dvec3 eye, glm::dvec3 target) { scene::ops::setTransforms(doc, {{camera, lookFrom(eye, target)}}, "look"); }
  render::RenderView view(int w, int h) const { return render::viewFromCamera(doc.state(), camera, w, h); }
};

bool isSky(const hs::Image& img, int x, int y) {
  const uint8_t* p = &img.rgba8[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return p[0] > 250 && p[1] < 5 && p[2] > 250;
}

size_t skyPixels(const hs::Image& img) {
  size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += isSky(img, x, y);
  return n;
}

using ErrorStats = test::TerrainScreenError;

ErrorStats measureError(render::OffscreenRenderer& r, const TerrainScene& s, const render::RenderView& v) {
  std::vector<float> depth(size_t(v.width) * size_t(v.height));
  r.renderer().readDepth(depth.data());
  return test::terrainScreenError(depth, v, scene::terrainOf(s.state(), s.terrain)->data->heights(), s.origin());
}

}  // namespace

class TestTerrainRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // Looking down at a rough terrain that fills the whole view: every pixel
  // is terrain, so one sky pixel is a crack. The view spans several levels
  // (checked), with their morph zones in view.
  void noCracksWhereLevelsMeet_data() {
    QTest::addColumn<double>("lodError");
    QTest::newRow("1 px") << 1.0;
    QTest::newRow("4 px") << 4.0;
    QTest::newRow("16 px") << 16.0;
  }
  void noCracksWhereLevelsMeet() {
    QFETCH(double, lodError);
    TerrainScene s(2049, 4096.0, glm::dvec3(0.0), lodError);
    s.look({0.0, -300.0, 320.0}, {0.0, 200.0, 0.0});  // the view's top edge meets the ground 1.4 km away
    const render::RenderView v = s.view(640, 360);
    render::FrameStats stats;
    const hs::Image img = r_.render(s.state(), v, false, &stats);
    const render::LodSelection lod = r_.renderer().terrainLod(s.state(), s.terrain, v);
    int minLevel = 99, maxLevel = -1;
    for (const auto& p : lod.patches) {
      minLevel = std::min(minLevel, p.level);
      maxLevel = std::max(maxLevel, p.level);
    }
    qInfo("error bound %.0f px: %zu quadrants, levels %d..%d, %zu triangles (full resolution: %d)", lodError,
          lod.patches.size(), minLevel, maxLevel, stats.terrainTriangles, 2 * 2048 * 2048);
    QVERIFY(maxLevel > minLevel);  // level boundaries in view (where cracks would be)
    QCOMPARE(stats.terrainTriangles, lod.triangles());
    const size_t sky = skyPixels(img);
    if (sky) {
      QDir().mkpath(HS_TEST_OUT_DIR);
      test::writePng(HS_TEST_OUT_DIR "/terrain_cracks.png", toTest(img));
    }
    QVERIFY2(sky == 0, qPrintable(QString("%1 sky pixels through the terrain").arg(sky)));

    // The check can fail: cut a hole, and the sky shows through it.
    terrain::BrushSettings b;
    b.tool = terrain::BrushTool::Holes;
    b.radius = 40.0;
    b.strength = 1.0f;
    terrain::Stroke st(s.data().terrain(), b);
    const terrain::StrokeUpdate u = st.dabAt(glm::dvec2(2048.0, 2048.0 + 500.0));
    scene::noteTerrainChange(s.doc, scene::terrainOf(s.state(), s.terrain)->id, s.data(), u.changed, scene::kTerrainHoles);
    const hs::Image holed = r_.render(s.state(), v);
    QVERIFY(skyPixels(holed) > 100);
  }

  // DESIGN.md: a terrain at UTM coordinates renders as it does at the origin.
  void largeCoordinatesMatchOrigin() {
    TerrainScene a(513, 512.0), b(513, 512.0, glm::dvec3(500000.0, 4400000.0, 300.0));
    const glm::dvec3 eye(20.0, -30.0, 0.0), target(40.0, 5.0, 0.0);
    auto place = [&](TerrainScene& s, glm::dvec3 shift) {
      // A 4 m checkerboard painted on (sharp edges: shifts show), seen
      // from 25 m above the ground under the eye.
      terrain::PaintLayers& paint = s.data().terrain().paint;
      for (int y = 0; y < paint.samplesY(); ++y)
        for (int x = 0; x < paint.samplesX(); ++x)
          if (((x / 4) + (y / 4)) % 2) paint.blend(x, y, 7, 1.0f);
      s.data().noteChanged(s.data().heights().bounds(), scene::kTerrainPaint);
      const double ground = *scene::terrainSurfaceAt(s.state(), s.terrain, glm::dvec2(eye + shift));
      s.look(glm::dvec3(eye.x, eye.y, ground + 25.0) + glm::dvec3(shift.x, shift.y, 0.0),
             glm::dvec3(target.x, target.y, ground - 10.0) + glm::dvec3(shift.x, shift.y, 0.0));
    };
    place(a, glm::dvec3(0.0));
    place(b, glm::dvec3(500000.0, 4400000.0, 300.0));
    const hs::Image ia = r_.render(a.state(), a.view(480, 360));
    const hs::Image ib = r_.render(b.state(), b.view(480, 360));
    const test::CompareResult cmp = test::compareImages(toTest(ia), toTest(ib), 2);
    qInfo("origin vs UTM: %s", cmp.summary().c_str());
    QVERIFY(cmp.sizeMatches);
    QVERIFY2(cmp.maxChannelDiff <= 8 && cmp.differingShare <= 0.001, cmp.summary().c_str());
    QVERIFY(skyPixels(ia) < size_t(480 * 360) / 2);  // mostly terrain: the comparison means something
    // And it could fail: the camera 5 mm off.
    scene::Transform t = b.state().find(b.camera)->transform;
    t.translation.x += 0.005;
    scene::ops::setTransforms(b.doc, {{b.camera, t}}, "nudge");
    const hs::Image ic = r_.render(b.state(), b.view(480, 360));
    QDir().mkpath(HS_TEST_OUT_DIR);
    test::writePng(HS_TEST_OUT_DIR "/terrain_utm.png", toTest(ib));
    test::writePng(HS_TEST_OUT_DIR "/terrain_utm_shifted.png", toTest(ic));
    QVERIFY2(test::compareImages(toTest(ia), toTest(ic), 2).differingShare > 0.001, "a 5 mm shift should show");
  }

  // The measured screen-space error of the LOD against the full-resolution
  // mesh, from the depth buffer, per pixel: within the bound.
  void screenSpaceErrorWithinBound() {
    TerrainScene s(2049, 4096.0, glm::dvec3(0.0), 1.0);
    s.look({0.0, -1500.0, 260.0}, {0.0, 900.0, 0.0});
    const render::RenderView v = s.view(960, 540);
    render::FrameStats lodStats;
    render::RenderOptions keepDepth;
    keepDepth.keepDepth = true;
    r_.render(s.state(), v, false, &lodStats, keepDepth);
    const ErrorStats lod = measureError(r_, s, v);
    scene::ops::setField(s.doc, s.terrain, *scene::findEntityField("terrain.lod_error_px"), scene::FieldValue(0.1));
    render::FrameStats fineStats;
    r_.render(s.state(), v, false, &fineStats, keepDepth);
    const ErrorStats fine = measureError(r_, s, v);
    qInfo("bound 1 px: %zu triangles, error max %.3f px, 99%% %.3f px, mean %.4f px over %zu pixels; "
          "bound 0.1 px: %zu triangles, max %.3f px",
          lodStats.terrainTriangles, lod.maxPx, lod.p99, lod.mean, lod.pixels, fineStats.terrainTriangles, fine.maxPx);
    QVERIFY(lod.pixels > 100000);
    QVERIFY2(lod.p99 <= 1.0, qPrintable(QString::number(lod.p99)));
    QVERIFY2(lod.maxPx <= 1.5, qPrintable(QString::number(lod.maxPx)));  // depth-buffer and rasterisation noise above 1
    QVERIFY(fine.maxPx < lod.maxPx + 0.25);
    QVERIFY(fineStats.terrainTriangles > lodStats.terrainTriangles);
    QVERIFY(lodStats.terrainTriangles < size_t(2) * 2048 * 2048 / 4);  // far fewer than the full mesh
  }

  // A brush dab uploads its region (4 bytes per height sample), nothing more.
  void dabUploadsOnlyItsRegion() {
    TerrainScene s(1025, 1024.0);
    s.look({0.0, -600.0, 400.0}, {0.0, 0.0, 0.0});
    render::FrameStats first;
    const hs::Image before = r_.render(s.state(), s.view(320, 180), false, &first);
    QVERIFY(first.terrainUploadBytes >= size_t(1025) * 1025 * 4);  // the first frame uploads it all
    terrain::BrushSettings b;
    b.tool = terrain::BrushTool::Raise;
    b.radius = 128.0;
    b.strength = 30.0f;
    terrain::Stroke st(s.data().terrain(), b);
    const terrain::StrokeUpdate u = st.dabAt(glm::dvec2(512.0, 512.0));
    scene::noteTerrainChange(s.doc, scene::terrainOf(s.state(), s.terrain)->id, s.data(), u.changed, scene::kTerrainHeights);
    r_.makeCurrent();
    const render::TerrainUpload up = r_.renderer().syncTerrain(s.data());
    qInfo("radius-128 dab: changed %dx%d samples, uploaded %zu bytes in %zu sub-images (%.3f ms CPU incl. LOD bookkeeping)",
          u.changed.width(), u.changed.height(), up.bytes, up.regions, up.cpuMs);
    QCOMPARE(up.bytes, u.changed.samples() * 4);
    QVERIFY(!up.full);
    QVERIFY(up.regions <= 9);
    render::FrameStats after;
    const hs::Image img = r_.render(s.state(), s.view(320, 180), false, &after);
    QCOMPARE(after.terrainUploadBytes, size_t(0));  // already up to date
    QVERIFY(img.rgba8 != before.rgba8);             // and it shows
  }

  // The weight texture holds every painted layer's 16-bit weights rounded
  // to 8 bits, four layers to a texel (gpu_terrain.h), read back and
  // compared sample by sample with the document's; after a dab on one layer
  // only its region is uploaded again, and the texture still matches.
  void paintWeightsPackFourLayersToATexel() {
    TerrainScene s(257, 256.0);
    terrain::PaintLayers& paint = s.data().terrain().paint;
    QVERIFY(paint.layerCount() >= 7);
    // Five layers painted in different patterns (with layer 0 reduced, six
    // have tiles: two groups); layer 4 and those above 6 never painted.
    const int painted[] = {1, 2, 3, 5, 6};
    for (int k = 0; k < 5; ++k)
      for (int y = 0; y < 257; ++y)
        for (int x = 0; x < 257; ++x)
          if ((x * (k + 3) + y * (7 - k)) % 11 < k + 2) paint.blend(x, y, painted[k], 0.15f + 0.1f * float(k));
    s.data().noteChanged(s.data().heights().bounds(), scene::kTerrainPaint);
    r_.makeCurrent();
    render::GpuTerrain gpu;
    gpu.sync(s.data());
    auto check = [&](const char* when) {
      int slices = 0;
      for (int l = 0; l < paint.layerCount(); ++l) slices += gpu.weightSlice(l) >= 0;
      QCOMPARE(gpu.weightSlice(4), -1);
      QCOMPARE(slices, 6);
      QCOMPARE(gpu.weightGroups(), 2);
      std::vector<uint8_t> texels(size_t(257) * 257 * 4 * 2);
      glGetTextureImage(gpu.weightTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(texels.size()), texels.data());
      std::vector<int> owner(8, -1);  // slice -> layer
      for (int l = 0; l < paint.layerCount(); ++l)
        if (gpu.weightSlice(l) >= 0) owner[size_t(gpu.weightSlice(l))] = l;
      size_t wrong = 0, nonzero = 0;
      for (int slice = 0; slice < 8; ++slice)
        for (int y = 0; y < 257; ++y)
          for (int x = 0; x < 257; ++x) {
            const size_t at = ((size_t(slice / 4) * 257 + size_t(y)) * 257 + size_t(x)) * 4 + size_t(slice % 4);
            const int layer = owner[size_t(slice)];
            const int want = layer < 0 ? 0 : int(std::lround(double(paint.weight(layer, x, y)) * 255.0));
            wrong += texels[at] != want;
            nonzero += texels[at] != 0;
          }
      qInfo("%s: %d slices in %d texel layers, %zu of %d weights wrong, %zu nonzero", when, slices,
            gpu.weightGroups(), wrong, 8 * 257 * 257, nonzero);
      QCOMPARE(wrong, size_t(0));
      QVERIFY(nonzero > size_t(257) * 257);
    };
    check("first upload");
    if (QTest::currentTestFailed()) return;
    // A dab on layer 6 over a 40 x 30 region.
    const terrain::Region dab{100, 50, 140, 80};
    for (int y = dab.y0; y < dab.y1; ++y)
      for (int x = dab.x0; x < dab.x1; ++x) paint.blend(x, y, 6, 0.5f);
    s.data().noteChanged(dab, scene::kTerrainPaint);
    const render::TerrainUploadStats up = gpu.sync(s.data());
    QVERIFY(!up.full);
    QCOMPARE(up.bytes, size_t(dab.samples()) * 4 * 2);  // both groups' texels of the region, once
    check("after a dab");
    gpu.release();
  }

  void holesAreNotDrawnAndNotPicked() {
    TerrainScene s(257, 256.0);
    s.look({0.0, 0.0, 300.0}, {0.0, 0.01, 0.0});  // straight down on the centre
    const render::RenderView v = s.view(200, 200);
    QCOMPARE(r_.renderer().pick(s.state(), v, 100, 100), s.terrain);
    terrain::BrushSettings b;
    b.tool = terrain::BrushTool::Holes;
    b.radius = 20.0;
    b.strength = 1.0f;
    terrain::Stroke st(s.data().terrain(), b);
    const terrain::StrokeUpdate u = st.dabAt(glm::dvec2(128.0, 128.0));
    scene::noteTerrainChange(s.doc, scene::terrainOf(s.state(), s.terrain)->id, s.data(), u.changed, scene::kTerrainHoles);
    const hs::Image img = r_.render(s.state(), v);
    QVERIFY(isSky(img, 100, 100));
    QVERIFY(!isSky(img, 10, 10));
    QCOMPARE(r_.renderer().pick(s.state(), v, 100, 100), scene::kNoEntity);
    QCOMPARE(r_.renderer().pick(s.state(), v, 10, 10), s.terrain);
  }

  // A layer's normal map turns the shading normal like real geometry does:
  // a flat terrain whose layer holds a constant tangent-space normal tilted
  // by 30 degrees about the y axis must shade as a plane tilted by 30 degrees
  // without one (the tangent frame of terrain.frag: T along +x, B along +y
  // on flat ground). The flat terrain without the map is the check that the
  // comparison can fail.
  void layerNormalMapTurnsTheShading() {
    const double tilt = glm::radians(30.0);
    QTemporaryDir dir;
    const std::string mapPath = dir.filePath("tilt_normal.png").toStdString();
    test::Rgba8Image map{8, 8, {}};
    const glm::dvec3 tn(std::sin(tilt), 0.0, std::cos(tilt));
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < 4; ++c)
        map.rgba.push_back(c == 3 ? 255 : uint8_t(std::lround((tn[c] * 0.5 + 0.5) * 255.0)));
    QVERIFY(test::writePng(mapPath, map));
    // 65 x 65 samples over 64 m; heights along x given by `slope`.
    auto render = [&](double slope, const std::string& normalMap) {
      TerrainScene s(65, 64.0);
      terrain::Heightfield& hf = s.data().terrain().height;
      std::vector<float> h(65 * 65);
      for (int y = 0; y < 65; ++y)
        for (int x = 0; x < 65; ++x) h[size_t(y) * 65 + size_t(x)] = float(-(x - 32) * hf.spacing().x * slope);
      hf.write(hf.bounds(), h);
      s.data().noteChanged(hf.bounds(), scene::kTerrainAll);
      terrain::Material m = scene::terrainOf(s.state(), s.terrain)->materials[0];
      m.albedo = glm::vec3(0.3f);  // dark enough that the flat terrain does not clip at 255
      m.albedoTexture.clear();
      m.normalTexture = normalMap;
      if (!scene::ops::setTerrainMaterial(s.doc, scene::terrainOf(s.state(), s.terrain)->id, 0, m))
        qFatal("cannot set the terrain material");
      s.look(glm::dvec3(0.0, -20.0, 60.0), glm::dvec3(0.0));  // the terrain is centred on the origin
      return r_.render(s.state(), s.view(160, 120));
    };
    // The mean of a 16 x 16 window at the centre, where both surfaces pass
    // through the look target.
    auto centre = [](const hs::Image& img) {
      if (isSky(img, img.width / 2, img.height / 2)) qFatal("no terrain at the centre of the view");
      glm::dvec3 sum(0.0);
      for (int y = img.height / 2 - 8; y < img.height / 2 + 8; ++y)
        for (int x = img.width / 2 - 8; x < img.width / 2 + 8; ++x)
          for (int c = 0; c < 3; ++c) sum[c] += img.rgba8[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + size_t(c)];
      return sum / 256.0;
    };
    const glm::dvec3 mapped = centre(render(0.0, mapPath));
    const glm::dvec3 tilted = centre(render(std::tan(tilt), ""));
    const glm::dvec3 flat = centre(render(0.0, ""));
    qInfo("centre grey: normal-mapped %.1f, tilted geometry %.1f, flat %.1f", mapped.x, tilted.x, flat.x);
    for (int c = 0; c < 3; ++c) QVERIFY2(std::abs(mapped[c] - tilted[c]) <= 3.0, qPrintable(QString::number(c)));
    QVERIFY2(std::abs(flat.x - tilted.x) > 20.0, "the tilt should show against the flat terrain");
  }

  void noTerrainNoPass() {
    scene::SceneState s;
    render::RenderView v;
    v.width = v.height = 64;
    render::FrameStats stats;
    r_.render(s, v, false, &stats);
    QCOMPARE(stats.terrainPatches, size_t(0));
    QCOMPARE(stats.terrainTriangles, size_t(0));
    QCOMPARE(stats.terrainUploadBytes, size_t(0));
  }
};

QTEST_GUILESS_MAIN(TestTerrainRender)
#include "test_terrain_render.moc"
