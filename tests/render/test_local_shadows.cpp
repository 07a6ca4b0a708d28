// Spot and point light shadows (docs/rendering.md "Shadows", "Spot and point
// lights") through the headless EGL backend: the faces' maths, goldens,
// the shadowed share against a CPU ray cast towards the light (meshproc's
// BVH, the independent reference), both eyes reading one set of maps, every
// light's casts_shadows read (the sun's too), nothing allocated without a
// casting light in reach, bad resolutions.
#include <QtTest>

#include <cmath>
#include <limits>

#include "image_compare.h"
#include "meshproc/closest_point_bvh.h"
#include "render/local_shadows.h"
#include "render/offscreen_renderer.h"
#include "render_golden.h"
#include "scene/fields.h"
#include "shadow_probe.h"
#include "shadow_scene.h"

using namespace hs;

namespace {

render::RenderView cameraView(const scene::SceneState& s, int w, int h) {
  return render::viewFromCamera(s, s.cameras().front(), w, h);
}

scene::Entity& theLight(scene::SceneState& s) {
  for (auto& [id, e] : s.entities)
    if (e.light && e.light->type != scene::Light::Type::Sun) return e;
  throw std::runtime_error("no local light");
}

glm::dvec3 lightPosition(const scene::SceneState& s) {
  for (const auto& [id, e] : s.entities)
    if (e.light && e.light->type != scene::Light::Type::Sun) return glm::dvec3(s.worldMatrix(id)[3]);
  return {};
}

// Bytes the renderer holds for shadows (the registry), and whether a frame
// ran a shadow pass.
size_t shadowBytes(render::OffscreenRenderer& r) {
  size_t b = 0;
  for (const render::GpuAllocation& a : r.renderer().resourceRegistry())
    if (a.name.find("shadow") != std::string::npos) b += a.bytes;
  return b;
}
size_t allocated(render::OffscreenRenderer& r, const std::string& name) {
  for (const render::GpuAllocation& a : r.renderer().resourceRegistry())
    if (a.name == name) return a.bytes;
  return 0;
}
int shadowPasses(const render::FrameStats& s) {
  int n = 0;
  for (const render::PassStats& p : s.passes) n += p.name.rfind("shadow", 0) == 0;
  return n;
}

render::WorldLight worldLight(scene::Light::Type type, glm::dvec3 at, glm::dvec3 dir, double outerDeg) {
  render::WorldLight l;
  l.type = type;
  l.position = at;
  l.direction = glm::normalize(dir);
  l.range = 50.0f;
  l.cosOuterHalf = float(std::cos(glm::radians(outerDeg) * 0.5));
  l.cosInnerHalf = l.cosOuterHalf;
  l.castsShadows = true;
  return l;
}

glm::dvec3 toMap(const render::LocalShadowFace& f, const glm::dvec3& p) {
  const glm::dvec4 c = f.frameToMap * glm::dvec4(p, 1.0);
  return glm::dvec3(c) / c.w;
}

}  // namespace

class TestLocalShadows : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // GL-free: a spot's axis lands at the map's centre with depth near / d;
  // its outer cone inside the map, within the guard band; a cube's six
  // faces each hold their axis; the matrices are relative to the frame
  // origin (a light at UTM coordinates gives the numbers of one at the
  // origin); a frustum volume holds what the face sees and not what lies
  // beyond the range.
  void faceMaths() {
    const glm::dvec3 utm(500000.0, 4400000.0, 300.0);
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.2, 0.4, -1.0));
    for (const glm::dvec3& origin : {glm::dvec3(0.0), utm}) {
      const render::WorldLight spot = worldLight(scene::Light::Type::Spot, origin + glm::dvec3(1, 2, 8), dir, 60.0);
      const render::LocalShadow s = render::computeLocalShadow(spot, 3, 1024, 1, origin);
      QCOMPARE(s.faces.size(), size_t(1));
      QCOMPARE(s.light, size_t(3));
      const glm::dvec3 onAxis = toMap(s.faces[0], glm::dvec3(1, 2, 8) + dir * 10.0);
      QVERIFY(std::abs(onAxis.x - 0.5) < 1e-9 && std::abs(onAxis.y - 0.5) < 1e-9);
      QVERIFY(std::abs(onAxis.z - s.nearPlane / 10.0) < 1e-9);
      // A point on the outer cone: inside the map, at least the guard band (3 texels) from its edge.
      const glm::dvec3 side = glm::normalize(glm::cross(dir, glm::dvec3(0, 0, 1)));
      const glm::dvec3 edge = glm::dvec3(1, 2, 8) + 10.0 * (glm::cos(glm::radians(30.0)) * dir + glm::sin(glm::radians(30.0)) * side);
      const glm::dvec3 e = toMap(s.faces[0], edge);
      const double fromEdge = std::min({e.x, e.y, 1.0 - e.x, 1.0 - e.y}) * 1024.0;
      qInfo("outer cone edge %.2f texels from the map's edge", fromEdge);
      QVERIFY(fromEdge > 2.9 && fromEdge < 4.0);
      const render::Frustum v = render::localShadowVolume(s, s.faces[0]);
      QVERIFY(v.intersectsSphere(glm::dvec3(1, 2, 8) + dir * 40.0, 0.1));
      QVERIFY(!v.intersectsSphere(glm::dvec3(1, 2, 8) + dir * 51.0, 0.5));   // past the range
      QVERIFY(!v.intersectsSphere(glm::dvec3(1, 2, 8) - dir * 5.0, 0.5));    // behind the spot
    }
    const render::LocalShadow a = render::computeLocalShadow(
        worldLight(scene::Light::Type::Spot, glm::dvec3(1, 2, 8), dir, 60.0), 0, 1024, 1, glm::dvec3(0.0));
    const render::LocalShadow b = render::computeLocalShadow(
        worldLight(scene::Light::Type::Spot, utm + glm::dvec3(1, 2, 8), dir, 60.0), 0, 1024, 1, utm);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) QVERIFY(std::abs(a.faces[0].frameToMap[c][r] - b.faces[0].frameToMap[c][r]) < 1e-9);

    for (auto [type, outer] : {std::pair{scene::Light::Type::Point, 45.0}, std::pair{scene::Light::Type::Spot, 150.0}}) {
      const render::LocalShadow cube =
          render::computeLocalShadow(worldLight(type, glm::dvec3(0.0), dir, outer), 0, 512, 1, glm::dvec3(0.0));
      QCOMPARE(cube.faces.size(), size_t(6));
      for (size_t f = 0; f < 6; ++f) {
        glm::dvec3 axis(0.0);
        axis[int(f / 2)] = f % 2 ? -1.0 : 1.0;
        QVERIFY(cube.faces[f].axis == axis);
        const glm::dvec3 m = toMap(cube.faces[f], axis * 3.0);
        QVERIFY(std::abs(m.x - 0.5) < 1e-9 && std::abs(m.y - 0.5) < 1e-9);
        // The face's 45-degree edge stays inside its map (the guard band).
        const glm::dvec3 across = f / 2 == 2 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
        const glm::dvec3 c = toMap(cube.faces[f], axis * 3.0 + across * 3.0);
        QVERIFY(c.x > 0.0 && c.x < 1.0 && c.y > 0.0 && c.y < 1.0);
        QVERIFY(std::min({c.x, c.y, 1.0 - c.x, 1.0 - c.y}) * 512.0 > 2.9);
      }
    }
  }

  // The map size of a light: its own, or the settings' (a cube's faces half
  // of it); out of range clamped with a message naming the light and field.
  void resolutionRules() {
    render::ShadowConfig config;
    config.resolution = 2048;
    render::WorldLight spot = worldLight(scene::Light::Type::Spot, {}, {0, 0, -1}, 60.0);
    render::WorldLight point = worldLight(scene::Light::Type::Point, {}, {0, 0, -1}, 60.0);
    std::string problem;
    QCOMPARE(render::localShadowResolution(spot, "Lamp", config, 16384, &problem), 2048);
    QCOMPARE(render::localShadowResolution(point, "Lamp", config, 16384, &problem), 1024);
    spot.shadowResolution = 512;
    QCOMPARE(render::localShadowResolution(spot, "Lamp", config, 16384, &problem), 512);
    QVERIFY(problem.empty());
    for (auto [bad, expect] : {std::pair{-5, 256}, std::pair{1000000, 8192}, std::pair{100, 256}}) {
      problem.clear();
      spot.shadowResolution = bad;
      QCOMPARE(render::localShadowResolution(spot, "Lamp", config, 16384, &problem), expect);
      qInfo("%s", problem.c_str());
      QVERIFY(problem.find("light 'Lamp'") != std::string::npos);
      QVERIFY(problem.find("shadow_resolution") != std::string::npos);
      QVERIFY(problem.find(std::to_string(bad)) != std::string::npos);
    }
    problem.clear();
    spot.shadowResolution = 8192;
    QCOMPARE(render::localShadowResolution(spot, "Lamp", config, 4096, &problem), 4096);
    QVERIFY(problem.find("larger than this GPU allows") != std::string::npos);
  }

  void goldens_data() {
    QTest::addColumn<int>("type");
    QTest::newRow("spot") << int(scene::Light::Type::Spot);
    QTest::newRow("point") << int(scene::Light::Type::Point);
  }
  // The pictures, against goldens (8-bit, explicit tolerance: at most 0.5%
  // of pixels more than 6 levels off, none more than 40).
  void goldens() {
    QFETCH(int, type);
    test::ShadowScene sc = test::localLightScene(scene::Light::Type(type));
    sc.state.settings.tonemap = scene::Tonemap::Aces;
    render::FrameStats stats;
    const hs::Image img = r_.render(sc.state, cameraView(sc.state, 480, 320), false, &stats);
    test::verifyGolden(type == int(scene::Light::Type::Spot) ? "shadows_spot" : "shadows_point", img,
                       test::GoldenTolerance{40, 6, 0.005});
    bool ran = false;
    for (const render::PassStats& p : stats.passes) ran |= p.name == "shadow_local";
    QVERIFY(ran);
  }

  // The independent reference: from each pixel's world position (depth
  // buffer) a ray towards the light's position through the scene's
  // triangles. The maps must agree but for a thin band at shadow edges.
  void shadowedShareAgainstRayCast_data() {
    QTest::addColumn<int>("type");
    QTest::addColumn<int>("resolution");
    QTest::newRow("spot 1024") << int(scene::Light::Type::Spot) << 1024;
    QTest::newRow("spot 2048") << int(scene::Light::Type::Spot) << 2048;
    QTest::newRow("point 512") << int(scene::Light::Type::Point) << 512;
    QTest::newRow("point 1024") << int(scene::Light::Type::Point) << 1024;
  }
  void shadowedShareAgainstRayCast() {
    QFETCH(int, type);
    QFETCH(int, resolution);
    test::ShadowScene sc = test::localLightScene(scene::Light::Type(type));
    theLight(sc.state).light->shadowResolution = resolution;
    const render::RenderView view = cameraView(sc.state, 400, 300);
    const test::ShadowProbe p = test::probeShadows(r_, sc.state, view);
    const mesh::ClosestPointBvh bvh(sc.world);
    const glm::dvec3 light = lightPosition(sc.state) - sc.offset;
    size_t counted = 0, shadowed = 0, refShadowed = 0, differ = 0;
    for (size_t i = 0; i < p.visibility.size(); ++i) {
      if (p.visibility[i] < 0.0f) continue;
      ++counted;
      const glm::dvec3 at = p.world[i] - sc.offset;
      const double d = glm::length(light - at);
      const bool s = p.visibility[i] < 0.5f;
      const bool ref = bvh.occluded(at, (light - at) / d, 0.03, d - 0.03);
      shadowed += s;
      refShadowed += ref;
      differ += s != ref;
    }
    const double share = double(differ) / double(counted);
    qInfo("%zu lit-facing pixels: %zu shadowed (ray cast: %zu), %.2f%% differ", counted, shadowed, refShadowed,
          100.0 * share);
    QVERIFY(counted > 30000);
    QVERIFY(refShadowed > counted / 50);  // the scene does have shadows in view (2-5% of the pixels)
    QVERIFY2(share < 0.01, qPrintable(QString::number(100.0 * share) + "% of pixels differ from the ray cast"));
  }

  // Both eyes of a stereo pair: one shadow pass in the frame, and each eye's
  // picture is the one it gets alone with the same maps.
  void stereoEyesShareMaps() {
    test::ShadowScene sc = test::localLightScene(scene::Light::Type::Point);
    const render::RenderView centre = cameraView(sc.state, 240, 160);
    render::RenderView left = centre, right = centre;
    left.eye -= centre.right() * 0.3;
    right.eye += centre.right() * 0.3;
    render::RenderOptions o;
    o.lodView = &centre;
    o.keepHdr = true;
    const render::FrameStats stats = r_.renderViewsOnly(sc.state, {left, right}, o);
    QCOMPARE(shadowPasses(stats), 1);
    const hs::Image leftInPair = r_.renderer().readHdr(0);
    const hs::Image rightInPair = r_.renderer().readHdr(1);
    const hs::Image leftAlone = r_.render(sc.state, left, true, nullptr, o);
    QVERIFY(leftInPair.rgbaF == leftAlone.rgbaF);
    QVERIFY(rightInPair.rgbaF != leftInPair.rgbaF);
    // And the shadows are there: without them the left eye is brighter somewhere.
    scene::SceneState off = sc.state;
    theLight(off).light->castsShadows = false;
    const hs::Image leftUnshadowed = r_.render(off, left, true, nullptr, o);
    QVERIFY(leftUnshadowed.rgbaF != leftAlone.rgbaF);
  }

  // Costs nothing: each light's casts_shadows is read (the sun's too), with
  // settings.shadows the master switch; a light whose range reaches no view
  // gets no map. From the renderer's registry, not from the passes' counts.
  void nothingAllocatedWithoutCastingLights() {
    test::ShadowScene sc = test::localLightScene(scene::Light::Type::Spot);
    const render::RenderView view = cameraView(sc.state, 160, 120);
    render::FrameStats stats;
    r_.render(sc.state, view, false, &stats);
    QCOMPARE(shadowPasses(stats), 1);
    QCOMPARE(allocated(r_, "local_shadow_maps"), size_t(1024) * 1024 * 4);  // settings: custom 1024
    QVERIFY(allocated(r_, "local_shadow_data") > 0);
    QCOMPARE(allocated(r_, "sun_shadow_map"), size_t(0));  // the sun is hidden

    auto expectNone = [&](const scene::SceneState& s, const char* what) {
      render::FrameStats st;
      r_.render(s, view, false, &st);
      if (shadowPasses(st) != 0 || shadowBytes(r_) != 0) qWarning("%s: a shadow pass ran or holds bytes", what);
      QCOMPARE(shadowPasses(st), 0);
      QCOMPARE(shadowBytes(r_), size_t(0));
    };
    scene::SceneState off = sc.state;
    off.settings.shadows = false;
    expectNone(off, "settings.shadows off");
    scene::SceneState notCasting = sc.state;
    theLight(notCasting).light->castsShadows = false;
    expectNone(notCasting, "casts_shadows false");
    // The sun visible again, but not casting: still nothing.
    for (auto& [id, e] : notCasting.entities)
      if (e.light) {
        e.visible = true;
        if (e.light->type == scene::Light::Type::Sun) e.light->castsShadows = false;
      }
    expectNone(notCasting, "a sun with casts_shadows false");
    QVERIFY(r_.renderer().sunCascades().empty());
    // The same sun casting: its maps are there.
    for (auto& [id, e] : notCasting.entities)
      if (e.light && e.light->type == scene::Light::Type::Sun) e.light->castsShadows = true;
    r_.render(notCasting, view, false, &stats);
    QVERIFY(allocated(r_, "sun_shadow_map") > 0);
    QCOMPARE(allocated(r_, "local_shadow_maps"), size_t(0));
    // A casting light whose range ends before anything the view sees: 200 m
    // behind the camera, range 60 m.
    scene::SceneState far = sc.state;
    theLight(far).transform.translation = glm::dvec3(0, -214, 7);
    expectNone(far, "a light beyond its range from the view");
    // Its range reaching into the view again: a map.
    theLight(far).light->range = 300.0f;
    r_.render(far, view, false, &stats);
    QVERIFY(allocated(r_, "local_shadow_maps") > 0);
  }

  // Bad shadow_resolution values on a light: 0 uses the settings (no
  // message); negative and 1e6 (set in code: the field refuses them) are
  // clamped with a message naming the light and the field, once, and the
  // frame renders with the clamped map. NaN never reaches the document.
  void badResolutions() {
    test::ShadowScene sc = test::localLightScene(scene::Light::Type::Spot);
    const render::RenderView view = cameraView(sc.state, 160, 120);
    r_.renderer().takeShadowProblems();
    theLight(sc.state).light->shadowResolution = 0;
    hs::Image img = r_.render(sc.state, view);
    QCOMPARE(img.width, 160);
    QVERIFY(r_.renderer().takeShadowProblems().empty());
    QCOMPARE(allocated(r_, "local_shadow_maps"), size_t(1024) * 1024 * 4);
    for (auto [bad, side] : {std::pair{-5, 256}, std::pair{1000000, 8192}}) {
      theLight(sc.state).light->shadowResolution = bad;
      img = r_.render(sc.state, view);
      QCOMPARE(img.width, 160);
      const std::vector<std::string> problems = r_.renderer().takeShadowProblems();
      QCOMPARE(problems.size(), size_t(1));
      qInfo("%s", problems[0].c_str());
      QVERIFY(problems[0].find("light 'Test spot'") != std::string::npos);
      QVERIFY(problems[0].find("shadow_resolution") != std::string::npos);
      QVERIFY(problems[0].find(std::to_string(bad)) != std::string::npos);
      QCOMPARE(allocated(r_, "local_shadow_maps"), size_t(side) * size_t(side) * 4);
      r_.render(sc.state, view);
      QVERIFY(r_.renderer().takeShadowProblems().empty());  // once, not every frame
    }
    const scene::EntityField* f = scene::findEntityField("light.shadow_resolution");
    QVERIFY(f);
    for (const char* text : {"nan", "-5", "1e6"}) {
      std::string error;
      const std::optional<scene::FieldValue> v = scene::parseFieldValue(*f, text, error);
      if (v) error = scene::fieldValueProblem(*f, *v, static_cast<const scene::Entity*>(nullptr));
      qInfo("set light.shadow_resolution %s: %s", text, error.c_str());
      QVERIFY(!error.empty());
    }
    scene::Entity& e = theLight(sc.state);
    e.light->shadowResolution = 512;
    f->set(e, scene::FieldValue(std::numeric_limits<double>::quiet_NaN()));
    QCOMPARE(e.light->shadowResolution, 512);
  }
};

QTEST_GUILESS_MAIN(TestLocalShadows)
#include "test_local_shadows.moc"
