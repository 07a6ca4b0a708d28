// Renderer tests through the headless EGL backend on llvmpipe: golden images
// (compared with an explicit tolerance), camera-relative precision at UTM
// coordinates, sRGB correctness, texturing, picking, culling.
#include <QtTest>

#include <cmath>

#include "image_compare.h"
#include "render_golden.h"
#include "look_from.h"
#include "mesh/mesh_import.h"
#include "render/offscreen_renderer.h"
#include "scene/demo_scene.h"
#include "scene/particle_world.h"
#include "scene/light_units.h"
#include "scene/world_bounds.h"

using namespace hs;
using hs::test::lookFrom;

namespace {


std::shared_ptr<const mesh::MeshData> bunnyMesh() {
  static std::shared_ptr<const mesh::MeshData> mesh = [] {
    mesh::ImportResult r = mesh::importMesh(HS_SOURCE_DIR "/resources/demo/stanford-bunny.obj");
    if (!r.ok()) qFatal("cannot load the bunny: %s", r.error.c_str());
    return std::make_shared<const mesh::MeshData>(std::move(*r.mesh));
  }();
  return mesh;
}

// A 2 x 2 m quad in the XZ plane facing -Y (towards a camera on -Y), with
// UVs (0,0) at its top-left corner and an optional texture.
mesh::MeshData quadMesh(const mesh::Texture* texture) {
  mesh::MeshData m;
  m.positions = {{-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}};
  m.normals.assign(4, glm::vec3(0, -1, 0));
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 2, 1, 0, 3, 2};
  mesh::Material mat;
  mat.baseColor = glm::vec4(1.0f);
  if (texture) {
    m.textures.push_back(*texture);
    mat.diffuseTexture = 0;
  }
  m.materials.push_back(mat);
  m.submeshes.push_back({0, 6, 0});
  return m;
}

scene::EntityId addEntity(scene::SceneState& s, scene::Entity e) {
  e.id = s.maxEntityId() + 1;
  s.roots.push_back(e.id);
  const scene::EntityId id = e.id;
  s.entities.emplace(id, std::move(e));
  return id;
}

scene::AssetId addAsset(scene::SceneState& s, std::shared_ptr<const mesh::MeshData> data) {
  scene::MeshAsset a;
  a.id = s.maxAssetId() + 1;
  a.name = "asset";
  a.contentHash = mesh::contentHash(*data);
  a.data = std::move(data);
  s.assets.emplace(a.id, a);
  return a.id;
}

// The bunny on the ground at `offset`, a sun, a camera 1 m in front at the same offset.
scene::SceneState bunnyScene(glm::dvec3 offset) {
  scene::SceneState s;
  s.settings.showGrid = false;
  const scene::AssetId a = addAsset(s, bunnyMesh());
  scene::Entity b;
  b.name = "Bunny";
  b.mesh = scene::MeshInstance{a};
  b.transform.translation = offset;
  addEntity(s, b);
  scene::Entity sun;
  sun.name = "Sun";
  sun.light = scene::Light{};
  sun.transform.rotation = scene::fromEulerDegrees({40, 0, -35});
  addEntity(s, sun);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 30.0;
  cam.camera->nearClip = 0.01;
  cam.transform = lookFrom(offset + glm::dvec3(0.05, -0.45, 0.12), offset + glm::dvec3(0, 0, 0.0));
  addEntity(s, cam);
  return s;
}

render::RenderView cameraView(const scene::SceneState& s, int w, int h) {
  return render::viewFromCamera(s, s.cameras().front(), w, h);
}

}  // namespace

class TestRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;


 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
    qInfo("GL: %s (EGL platform: %s)", r_.glDescription().c_str(), r_.eglPlatform().c_str());
  }

  void demoSceneGoldens_data() {
    QTest::addColumn<int>("aa");
    QTest::newRow("msaa4") << int(scene::Antialiasing::Msaa4);
    QTest::newRow("fxaa") << int(scene::Antialiasing::Fxaa);
    QTest::newRow("none") << int(scene::Antialiasing::None);
  }
  void demoSceneGoldens() {
    QFETCH(int, aa);
    std::string error;
    auto s = scene::buildDemoScene(error);
    QVERIFY2(s, error.c_str());
    s->settings.antialiasing = scene::Antialiasing(aa);
    // The goldens are at full resolution (LOD bound 0).
    s->settings.meshLodErrorPixels = 0.0;
    render::FrameStats stats;
    const hs::Image img = r_.render(*s, cameraView(*s, 640, 360), false, &stats);
    QCOMPARE(img.width, 640);
    QCOMPARE(img.height, 360);
    // Three instances of the 69,451-triangle bunny and the four translucent
    // samples (three glass spheres and the pond, scene/demo_glass.cpp), all
    // in view, two triangles per sprite particle in view (the snow, the
    // fog, the dust) and the rockfall's stones at full detail (mesh
    // particles: instances too); the detail samples are behind the camera.
    const scene::EntityId glass = s->findByName("Translucent samples");
    QVERIFY(glass != scene::kNoEntity);
    size_t glassTriangles = 0;
    for (scene::EntityId c : s->find(glass)->children)
      glassTriangles += s->findAsset(s->find(c)->mesh->mesh)->data->triangleCount();
    QCOMPARE(s->find(glass)->children.size(), size_t(4));
    const scene::EntityId stone = s->findByName("Rockfall stone");
    QVERIFY(stone != scene::kNoEntity);
    const size_t stoneTriangles = s->findAsset(s->find(stone)->mesh->mesh)->data->triangleCount();
    QVERIFY(stats.instancesDrawn > size_t(3 + 4));  // some stones in view
    const size_t stones = stats.instancesDrawn - (3 + 4);
    // particlesDrawn counts every live stone (handed to the instanced
    // source, which culls them), the sprites in view: the live stones from
    // the emitter's own evaluation.
    scene::ParticleWorld world(*s);
    const std::optional<scene::PlacedEmitter> rockfall = scene::placedEmitter(*s, s->findByName("Rockfall"));
    QVERIFY(rockfall);
    std::string evalError;
    const std::optional<particles::Evaluator> ev = world.evaluator(*rockfall, evalError);
    QVERIFY2(ev, evalError.c_str());
    const size_t liveStones = ev->frame(s->time.seconds).particles.size();
    QVERIFY(liveStones >= stones);
    QVERIFY(stats.particlesDrawn > 100 + liveStones);
    QCOMPARE(stats.trianglesDrawn - stats.terrainTriangles,
             size_t(3 * 69451) + glassTriangles + 2 * (stats.particlesDrawn - liveStones) + stones * stoneTriangles);
    QVERIFY(stats.oit.active);  // drawn through the transparency path
    QCOMPARE(stats.instancesAtCoarserLod, size_t(0));
    QVERIFY(stats.terrainTriangles > 0);  // and the valley they stand in
    test::verifyGolden(std::string("demo_") + QTest::currentDataTag(), img);

    // With the default 1-pixel bound the distant bunnies draw coarser
    // levels, and the picture stays the full-resolution one up to edge pixels.
    s->settings.meshLodErrorPixels = 1.0;
    render::FrameStats lodStats;
    const hs::Image lod = r_.render(*s, cameraView(*s, 640, 360), false, &lodStats);
    QVERIFY(lodStats.instancesAtCoarserLod > 0);
    QVERIFY(lodStats.trianglesDrawn < stats.trianglesDrawn);
    const test::CompareResult cmp = test::compareImages(test::toTest(lod), test::toTest(img), 16);
    qInfo("demo at the 1-pixel LOD bound: %zu vs %zu mesh triangles, %s", lodStats.trianglesDrawn - lodStats.terrainTriangles,
          stats.trianglesDrawn - stats.terrainTriangles, cmp.summary().c_str());
    QVERIFY2(cmp.differingShare <= 0.01, cmp.summary().c_str());
  }

  // DESIGN.md: a scan at UTM coordinates renders as it does at the origin.
  void largeCoordinatesMatchOrigin() {
    const auto atOrigin = bunnyScene({0, 0, 0});
    const auto atUtm = bunnyScene({500000.0, 4400000.0, 300.0});
    const hs::Image a = r_.render(atOrigin, cameraView(atOrigin, 480, 360));
    const hs::Image b = r_.render(atUtm, cameraView(atUtm, 480, 360));
    const test::CompareResult cmp = test::compareImages(test::toTest(a), test::toTest(b), 2);
    QVERIFY(cmp.sizeMatches);
    // Allow a grey level at a handful of edge pixels; no visible shift.
    QVERIFY2(cmp.maxChannelDiff <= 8 && cmp.differingShare <= 0.001, cmp.summary().c_str());
    test::verifyGolden("bunny_origin", a);
  }

  // The same with shadows on (docs/rendering.md "Shadows"): the sun's
  // cascades are formed in double around the camera, so the bunny shadowing
  // itself at UTM coordinates matches the bunny at the origin. The
  // shadowed picture must differ from the unshadowed one (or this would
  // test nothing).
  void largeCoordinatesMatchOriginWithShadows() {
    auto withShadows = [](scene::SceneState s) {
      s.settings.shadows = true;
      for (auto& [id, e] : s.entities)
        if (e.light) e.light->castsShadows = true;  // the sun casts (settings.shadows alone is the master switch)
      s.settings.shadowQuality = scene::ShadowQuality::High;
      s.settings.shadowDistance = 3.0;
      return s;
    };
    const auto atOrigin = withShadows(bunnyScene({0, 0, 0}));
    const auto atUtm = withShadows(bunnyScene({500000.0, 4400000.0, 300.0}));
    render::FrameStats stats;
    const hs::Image a = r_.render(atOrigin, cameraView(atOrigin, 480, 360), false, &stats);
    const hs::Image b = r_.render(atUtm, cameraView(atUtm, 480, 360));
    bool shadowPass = false;
    for (const render::PassStats& p : stats.passes) shadowPass |= p.name == "shadow_sun";
    QVERIFY(shadowPass);
    const test::CompareResult cmp = test::compareImages(test::toTest(a), test::toTest(b), 2);
    QVERIFY(cmp.sizeMatches);
    QVERIFY2(cmp.maxChannelDiff <= 8 && cmp.differingShare <= 0.001, cmp.summary().c_str());
    const hs::Image unshadowed = r_.render(bunnyScene({0, 0, 0}), cameraView(atOrigin, 480, 360));
    const test::CompareResult self = test::compareImages(test::toTest(a), test::toTest(unshadowed), 2);
    qInfo("shadows change %s", self.summary().c_str());
    QVERIFY(self.differingShare > 0.01);
    test::verifyGolden("bunny_origin_shadows", a);
  }

  // Without camera-relative maths the same scene would jitter: check that the
  // test above can fail, by rendering the UTM scene from a camera 5 cm off.
  void largeCoordinatesTestIsSensitive() {
    auto atUtm = bunnyScene({500000.0, 4400000.0, 300.0});
    const auto atOrigin = bunnyScene({0, 0, 0});
    atUtm.entities.at(atUtm.cameras().front()).transform.translation.x += 0.005;
    const hs::Image a = r_.render(atOrigin, cameraView(atOrigin, 480, 360));
    const hs::Image b = r_.render(atUtm, cameraView(atUtm, 480, 360));
    const test::CompareResult cmp = test::compareImages(test::toTest(a), test::toTest(b), 2);
    QVERIFY2(cmp.differingShare > 0.001, cmp.summary().c_str());
  }

  // A constant sky of linear 0.2140 must come out as sRGB 128 (0.2140 is the
  // linear value of sRGB 128/255), with no tone curve.
  void srgbEncodingIsExact() {
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.tonemap = scene::Tonemap::None;
    s.settings.antialiasing = scene::Antialiasing::None;
    const glm::vec3 c(0.21404114f);
    s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = c;
    render::RenderView v;
    v.width = 64;
    v.height = 64;
    const hs::Image img = r_.render(s, v);
    for (size_t i = 0; i < img.rgba8.size(); i += 4)
      for (int ch = 0; ch < 3; ++ch) QVERIFY(std::abs(int(img.rgba8[i + size_t(ch)]) - 128) <= 1);
    // The HDR readback holds the linear value itself.
    const hs::Image hdr = r_.render(s, v, true);
    QVERIFY(hdr.isFloat());
    QVERIFY(std::abs(hdr.rgbaF[0] - 0.21404114f) < 1e-3f);
    // Exposure scales linear light before encoding: one EV100 lower is x2,
    // linear 0.428 -> sRGB 174.
    s.settings.exposureEv100 -= 1.0f;
    const hs::Image bright = r_.render(s, v);
    QVERIFY(std::abs(int(bright.rgba8[0]) - 174) <= 1);
  }

  // Texture orientation and colour: a texture whose quadrants are red
  // (top-left), green (top-right), blue (bottom-left) and white on a quad
  // seen head-on.
  void texturedQuad() {
    mesh::Texture tex;
    tex.name = "quadrants";
    tex.width = tex.height = 64;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool right = x >= 32, bottom = y >= 32;
        const glm::u8vec4 c = !bottom ? (right ? glm::u8vec4(0, 255, 0, 255) : glm::u8vec4(255, 0, 0, 255))
                                      : (right ? glm::u8vec4(255) : glm::u8vec4(0, 0, 255, 255));
        tex.rgba.insert(tex.rgba.end(), {c.r, c.g, c.b, c.a});
      }
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.tonemap = scene::Tonemap::None;
    s.settings.antialiasing = scene::Antialiasing::None;
    s.settings.ambientIntensity = 1.0f;
    s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = glm::vec3(1.0f);  // white sky and ambient
    const scene::AssetId a = addAsset(s, std::make_shared<const mesh::MeshData>(quadMesh(&tex)));
    scene::Entity q;
    q.name = "Quad";
    q.mesh = scene::MeshInstance{a};
    addEntity(s, q);
    render::RenderView v;
    v.width = v.height = 200;
    v.fovY = glm::radians(60.0);
    v.eye = {0, -3, 0};
    v.orientation = lookFrom(v.eye, {0, 0, 0}).rotation;
    const hs::Image img = r_.render(s, v);
    auto px = [&](int x, int y) {
      const uint8_t* p = &img.rgba8[(size_t(y) * 200 + size_t(x)) * 4];
      return glm::ivec3(p[0], p[1], p[2]);
    };
    // The quad spans about 58% of the view: sample inside each quadrant.
    const glm::ivec3 tl = px(55, 55), tr = px(145, 55), bl = px(55, 145), br = px(145, 145);
    QVERIFY2(tl.r > 200 && tl.g < 60 && tl.b < 60, "top-left should be red");
    QVERIFY2(tr.g > 200 && tr.r < 60 && tr.b < 60, "top-right should be green");
    QVERIFY2(bl.b > 200 && bl.r < 60 && bl.g < 60, "bottom-left should be blue");
    QVERIFY2(br.r > 200 && br.g > 200 && br.b > 200, "bottom-right should be white");
    // Corners of the view are the (white) sky.
    QVERIFY(px(2, 2).r > 240);
  }

  void pickingFindsTheMesh() {
    const auto s = bunnyScene({500000.0, 4400000.0, 300.0});
    const render::RenderView v = cameraView(s, 320, 240);
    const scene::EntityId bunny = s.findByName("Bunny");
    // Project the bunny's centre to find a pixel on it.
    const scene::WorldBox box = scene::worldBounds(s, {bunny});
    glm::dvec2 px;
    QVERIFY(v.project(box.centre(), px));
    QCOMPARE(r_.renderer().pick(s, v, int(px.x), int(px.y)), bunny);
    QCOMPARE(r_.renderer().pick(s, v, 2, 2), scene::kNoEntity);   // sky
    QCOMPARE(r_.renderer().pick(s, v, -1, 5), scene::kNoEntity);  // outside
  }

  void culledWhenBehindTheCamera() {
    auto s = bunnyScene({0, 0, 0});
    render::RenderView v = cameraView(s, 160, 120);
    render::FrameStats stats;
    r_.render(s, v, false, &stats);
    QCOMPARE(stats.instancesDrawn, size_t(1));
    v.orientation = v.orientation * glm::angleAxis(glm::pi<double>(), glm::dvec3(0, 1, 0));  // turn around
    r_.render(s, v, false, &stats);
    QCOMPARE(stats.instancesDrawn, size_t(0));
    QCOMPARE(stats.instancesCulled, size_t(1));
    QCOMPARE(stats.trianglesDrawn, size_t(0));
  }

  void hiddenEntitiesAreNotDrawn() {
    auto s = bunnyScene({0, 0, 0});
    s.entities.at(s.findByName("Bunny")).visible = false;
    render::FrameStats stats;
    r_.render(s, cameraView(s, 160, 120), false, &stats);
    QCOMPARE(stats.trianglesDrawn, size_t(0));
  }

  void oddSizesAndResizes() {
    const auto s = bunnyScene({0, 0, 0});
    for (auto [w, h] : {std::pair{333, 177}, {1, 1}, {1024, 64}, {64, 1024}}) {
      const hs::Image img = r_.render(s, cameraView(s, w, h));
      QCOMPARE(img.width, w);
      QCOMPARE(img.height, h);
      QCOMPARE(img.rgba8.size(), size_t(w) * size_t(h) * 4);
    }
  }

  // A point light close to a wall lights its centre more than its edge.
  void pointLightFallsOff() {
    scene::SceneState s;
    s.settings.showGrid = false;
    s.settings.ambientIntensity = 0.0f;
    s.settings.antialiasing = scene::Antialiasing::None;
    auto wall = quadMesh(nullptr);
    for (auto& p : wall.positions) p *= 5.0f;
    const scene::AssetId a = addAsset(s, std::make_shared<const mesh::MeshData>(std::move(wall)));
    scene::Entity q;
    q.name = "Wall";
    q.mesh = scene::MeshInstance{a};
    addEntity(s, q);
    scene::Entity l;
    l.name = "Lamp";
    // 2 at 1 m in scene units (scene/light_units.h), as before physical units.
    l.light = scene::Light{scene::Light::Type::Point, glm::vec3(1.0f),
                           float(scene::legacyLightIntensity(scene::Light::Type::Point, 2.0)), 20.0f};
    l.transform.translation = {0, -1, 0};
    addEntity(s, l);
    render::RenderView v;
    v.width = v.height = 128;
    v.eye = {0, -6, 0};
    v.orientation = lookFrom(v.eye, {0, 0, 0}).rotation;
    const hs::Image img = r_.render(s, v);
    const int centre = img.rgba8[(64 * 128 + 64) * 4];
    const int edge = img.rgba8[(64 * 128 + 20) * 4];
    QVERIFY2(centre > edge + 40, qPrintable(QString("centre %1 edge %2").arg(centre).arg(edge)));
  }

  void cleanupTestCase() {}
};

QTEST_GUILESS_MAIN(TestRender)
#include "test_render.moc"
