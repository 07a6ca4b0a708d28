// Shadows (docs/rendering.md "Shadows") through the headless EGL backend:
// the cascade maths, a golden of the sun's shadows, the shadowed share
// against a CPU ray cast (the independent reference: meshproc's BVH), no
// shimmer when the camera moves by less than a texel, one set of cascades
// for both eyes, cut-out casters (sun and spot), nothing allocated without
// a caster, bad resolutions.
#include <QtTest>

#include <cmath>

#include "image_compare.h"
#include "render_golden.h"
#include "meshproc/closest_point_bvh.h"
#include "render/offscreen_renderer.h"
#include "render/shadow_cascades.h"
#include "scene/fields.h"
#include "scene/mesh_materials.h"
#include "shadow_probe.h"
#include "shadow_scene.h"

using namespace hs;

namespace {


render::RenderView cameraView(const scene::SceneState& s, int w, int h) {
  return render::viewFromCamera(s, s.cameras().front(), w, h);
}

// A 2 x 2 m card 2 m over a ground plane, its material cutting out a 1 x 1
// m hole in its middle (base colour alpha 0 there), lit by a sun or a spot
// light along (0.6, 0, -1) through the card's centre (the spot 3 units
// of that back from it); a camera on +X that sees the card's shadow on the
// ground beside it, not through the card.
struct CardScene {
  scene::SceneState state;
  glm::dvec3 light{0.0};  // the spot's position (unused for the sun)
};

CardScene cardScene(bool spot, bool cutout, float opacity = 1.0f) {
  CardScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.shadows = true;
  s.settings.shadowQuality = scene::ShadowQuality::Custom;
  s.settings.shadowResolution = 2048;
  s.settings.shadowCascades = 1;
  s.settings.shadowDistance = 30.0;
  auto addShape = [&](mesh::MeshData m, glm::dvec3 at, const scene::Material* material) {
    test::addShadowMesh(s, std::move(m), at, glm::dvec3(1.0), material);
  };
  addShape(mesh::gridPlane(30.0f, 4), {0, 0, 0}, nullptr);
  // The card's texture: white, alpha 0 over its middle half (UV 0.25..0.75).
  auto hole = std::make_shared<mesh::Texture>();
  hole->name = "card with a hole";
  hole->width = hole->height = 16;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      hole->rgba.insert(hole->rgba.end(), {255, 255, 255, uint8_t(x >= 4 && x < 12 && y >= 4 && y < 12 ? 0 : 255)});
  scene::TextureAsset tex;
  tex.id = 1;
  tex.name = hole->name;
  tex.srgb = true;
  tex.contentHash = 1;
  tex.image = hole;
  s.textures.emplace(tex.id, tex);
  scene::Material card;
  card.name = "Card";
  card.baseColorTexture = tex.id;
  card.alphaCutout = cutout;
  card.alphaThreshold = 0.5f;
  card.opacity = opacity;
  addShape(mesh::gridPlane(2.0f, 1), {0, 0, 2}, &card);

  const glm::dvec3 along = glm::normalize(glm::dvec3(0.6, 0, -1));
  scene::Entity light;
  light.name = spot ? "Card spot" : "Sun";
  light.light = scene::Light{};
  light.light->castsShadows = true;
  if (spot) {
    light.light->type = scene::Light::Type::Spot;
    light.light->intensity = 3.0e6f;
    light.light->range = 40.0f;
    light.light->innerConeDeg = 100.0f;
    light.light->outerConeDeg = 110.0f;
    out.light = glm::dvec3(0, 0, 2) - along * (3.0 / -along.z);  // 3 m above the card
  }
  light.transform = test::lookFrom(out.light, out.light + along);
  test::addShadowEntity(s, light);
  scene::Entity cam;
  cam.name = "Camera";
  cam.camera = scene::Camera{};
  cam.camera->verticalFovDeg = 50.0;
  cam.transform = test::lookFrom({8, 0, 5}, {1.2, 0.5, 0});
  test::addShadowEntity(s, cam);
  return out;
}

glm::dvec3 towardSun(const scene::SceneState& s) {
  for (const auto& [id, e] : s.entities)
    if (e.light) return glm::dvec3(s.worldMatrix(id) * glm::dvec4(0, 0, 1, 0));
  return {0, 0, 1};
}

}  // namespace

class TestShadows : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;


 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // GL-free: splits from near to far, nearest cascades finest; the map's
  // size does not change when the camera turns; snapped centres sit on
  // whole texels; a sub-texel move keeps or shifts a centre by whole texels.
  void cascadeMaths() {
    const std::vector<double> s = render::cascadeSplits(0.1, 30000.0, 4);
    QCOMPARE(s.size(), size_t(5));
    for (size_t i = 1; i < s.size(); ++i) QVERIFY(s[i] > s[i - 1]);
    QCOMPARE(s.back(), 30000.0);
    render::RenderView v;
    v.width = 1920;
    v.height = 1080;
    v.farClip = 50000.0;
    v.eye = {500000.25, 4400000.5, 300.0};
    render::ShadowConfig c;
    c.enabled = true;
    c.cascades = 4;
    c.resolution = 2048;
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, 0.8, -0.4));
    const render::SunCascades a = render::computeSunCascades(v, sun, c, v.eye);
    QCOMPARE(a.cascades.size(), size_t(4));
    QCOMPARE(a.cascades.back().splitFar, 30000.0);  // the 30 km the settings cover
    v.orientation = glm::angleAxis(0.7, glm::normalize(glm::dvec3(0.2, 1, 0.5)));
    const render::SunCascades b = render::computeSunCascades(v, sun, c, v.eye);
    for (size_t i = 0; i < 4; ++i) {
      QCOMPARE(a.cascades[i].radius, b.cascades[i].radius);
      if (i) QVERIFY(a.cascades[i].texelMetres > a.cascades[i - 1].texelMetres);
      const glm::dvec3 q = b.cascades[i].centreLight / b.cascades[i].texelMetres;
      for (int k = 0; k < 3; ++k) QCOMPARE(q[k], std::round(q[k]));
    }
    // Moved by a third of the finest texel: each centre stays or moves by whole texels.
    render::RenderView m = v;
    m.eye += glm::dvec3(1, 0.5, 0.2) * (b.cascades[0].texelMetres / 3.0);
    const render::SunCascades moved = render::computeSunCascades(m, sun, c, m.eye);
    for (size_t i = 0; i < 4; ++i) {
      const glm::dvec3 d = (moved.cascades[i].centreLight - b.cascades[i].centreLight) / b.cascades[i].texelMetres;
      for (int k = 0; k < 3; ++k) QVERIFY(std::abs(d[k] - std::round(d[k])) < 1e-6 && std::abs(d[k]) <= 1.0);
    }
  }

  // The picture, against a golden (8-bit, explicit tolerance).
  void sunShadowGolden() {
    test::ShadowScene sc = test::shadowScene();
    sc.state.settings.tonemap = scene::Tonemap::Aces;
    render::FrameStats stats;
    const hs::Image img = r_.render(sc.state, cameraView(sc.state, 480, 320), false, &stats);
    test::verifyGolden("shadows_sun", img);
    bool ran = false;
    for (const render::PassStats& p : stats.passes) ran |= p.name == "shadow_sun";
    QVERIFY(ran);
  }

  // The independent reference: for each pixel, a ray from its world position
  // (from the depth buffer) towards the sun through the scene's triangles
  // (meshproc's BVH). The shadow maps must agree but for a thin band at
  // shadow edges (the PCF kernel and the depth of each texel).
  void shadowedShareAgainstRayCast_data() {
    QTest::addColumn<int>("cascades");
    QTest::newRow("1 cascade") << 1;  // a one-layer array
    QTest::newRow("2 cascades") << 2;
    QTest::newRow("3 cascades") << 3;
    QTest::newRow("4 cascades") << 4;
  }
  void shadowedShareAgainstRayCast() {
    QFETCH(int, cascades);
    test::ShadowScene sc = test::shadowScene();
    sc.state.settings.shadowCascades = cascades;
    sc.state.settings.shadowResolution = 2048;
    sc.state.settings.shadowDistance = 30.0;
    const render::RenderView view = cameraView(sc.state, 400, 300);
    const test::ShadowProbe p = test::probeShadows(r_, sc.state, view);
    const mesh::ClosestPointBvh bvh(sc.world);
    const glm::dvec3 l = towardSun(sc.state);
    size_t counted = 0, shadowed = 0, refShadowed = 0, differ = 0;
    for (size_t i = 0; i < p.visibility.size(); ++i) {
      if (p.visibility[i] < 0.0f) continue;
      ++counted;
      const bool s = p.visibility[i] < 0.5f;
      const bool ref = bvh.occluded(p.world[i] - sc.offset, l, 0.03, 1e4);
      shadowed += s;
      refShadowed += ref;
      differ += s != ref;
    }
    const double share = double(differ) / double(counted);
    qInfo("%zu sunlit-facing pixels: %zu shadowed (ray cast: %zu), %.2f%% differ", counted, shadowed, refShadowed,
          100.0 * share);
    QVERIFY(counted > 30000);
    QVERIFY(refShadowed > counted / 20);  // the scene does have shadows in view
    QVERIFY2(share < 0.01, qPrintable(QString::number(100.0 * share) + "% of pixels differ from the ray cast"));
  }

  // No shimmer: the frame's camera (which the cascades follow) moves by a
  // fortieth of a texel per frame for 30 frames (three quarters of a texel
  // in all) while the picture is drawn from a fixed eye, so every change
  // would be the cascades'. No pixel may change between shadow and light.
  void stableUnderSubTexelMoves() {
    test::ShadowScene sc = test::shadowScene();
    const render::RenderView view = cameraView(sc.state, 320, 240);
    render::RenderView centre = view;
    render::RenderOptions o;
    o.lodView = &centre;
    const test::ShadowProbe first = test::probeShadows(r_, sc.state, view, o);
    const std::vector<render::SunCascadeInfo> cascades = r_.renderer().sunCascades();
    QVERIFY(!cascades.empty());
    const double texel = cascades.back().texelMetres;  // the scene is in the last cascade
    size_t changed = 0, shadowedPixels = 0;
    for (float v : first.visibility) shadowedPixels += v >= 0.0f && v < 0.5f;
    QVERIFY(shadowedPixels > 1000);
    for (int f = 1; f <= 30; ++f) {
      centre.eye = view.eye + glm::dvec3(0.8, 0.5, 0.3) * (texel * f / 40.0);
      const test::ShadowProbe p = test::probeShadows(r_, sc.state, view, o);
      for (size_t i = 0; i < p.visibility.size(); ++i)
        if (first.visibility[i] >= 0.0f && p.visibility[i] >= 0.0f)
          changed += (first.visibility[i] < 0.5f) != (p.visibility[i] < 0.5f);
    }
    qInfo("%zu shadowed pixels; %zu state changes over 30 frames", shadowedPixels, changed);
    QCOMPARE(changed, size_t(0));
  }

  // Both eyes of a stereo pair: one shadow pass in the frame, and each eye's
  // picture is the one it gets alone with the same (centre) cascades.
  void stereoEyesShareCascades() {
    test::ShadowScene sc = test::shadowScene();
    const render::RenderView centre = cameraView(sc.state, 240, 160);
    render::RenderView left = centre, right = centre;
    left.eye -= centre.right() * 0.3;
    right.eye += centre.right() * 0.3;
    render::RenderOptions o;
    o.lodView = &centre;
    o.keepHdr = true;
    const render::FrameStats stats = r_.renderViewsOnly(sc.state, {left, right}, o);
    int shadowPasses = 0;
    for (const render::PassStats& p : stats.passes) shadowPasses += p.name.rfind("shadow", 0) == 0;
    QCOMPARE(shadowPasses, 1);
    const std::vector<render::SunCascadeInfo> pair = r_.renderer().sunCascades();
    const hs::Image leftInPair = r_.renderer().readHdr(0);
    const hs::Image rightInPair = r_.renderer().readHdr(1);
    const hs::Image leftAlone = r_.render(sc.state, left, true, nullptr, o);
    const std::vector<render::SunCascadeInfo> alone = r_.renderer().sunCascades();
    QCOMPARE(pair.size(), alone.size());
    for (size_t i = 0; i < pair.size(); ++i) QVERIFY(pair[i].frameToMap == alone[i].frameToMap);
    QVERIFY(leftInPair.rgbaF == leftAlone.rgbaF);
    // The right eye sees the same shadows: they differ from the left only by parallax.
    QVERIFY(rightInPair.rgbaF != leftInPair.rgbaF);
  }

  // Cut-out casters: a card with a hole lets the light through in its
  // shadow where the hole is (sun and spot: the cascades and the spot's map
  // draw casters alike); without cut-out the same place is in shadow.
  // Probed on the ground where the light through the hole's centre, through
  // the card's solid ring and past the card's edge lands.
  void cutoutCastersLetLightThroughHoles_data() {
    QTest::addColumn<bool>("spot");
    QTest::newRow("sun") << false;
    QTest::newRow("spot") << true;
  }
  void cutoutCastersLetLightThroughHoles() {
    QFETCH(bool, spot);
    for (bool cutout : {true, false}) {
      const CardScene sc = cardScene(spot, cutout);
      const render::RenderView view = cameraView(sc.state, 320, 240);
      const test::ShadowProbe p = test::probeShadows(r_, sc.state, view);
      // Where the light through a point of the card lands on the ground.
      auto ground = [&](glm::dvec3 onCard) {
        const glm::dvec3 d = spot ? onCard - sc.light : glm::dvec3(0.6, 0, -1);
        return onCard + d * (onCard.z / -d.z);
      };
      auto visibilityAt = [&](glm::dvec3 world) {
        glm::dvec2 px;
        if (!view.project(world, px)) return -2.0f;
        return p.visibility[size_t(int(px.y)) * size_t(view.width) + size_t(int(px.x))];
      };
      const float inHole = visibilityAt(ground({0, 0, 2}));
      const float underCard = visibilityAt(ground({0, 0.75, 2}));
      const float beside = visibilityAt(ground({0, 1.4, 2}));
      qInfo("%s, cut-out %s: visibility %.2f through the hole, %.2f under the card, %.2f beside it",
            spot ? "spot" : "sun", cutout ? "on" : "off", double(inHole), double(underCard), double(beside));
      QVERIFY(beside > 0.9f);
      QVERIFY(underCard >= 0.0f && underCard < 0.1f);
      if (cutout) QVERIFY(inHole > 0.9f);
      else QVERIFY(inHole >= 0.0f && inHole < 0.1f);
    }
  }

  // A translucent card (opacity a, no cut-out) lets about 1 - a of the
  // light through: a hashed share a of its texels casts (shadow_depth.frag),
  // so the filtered visibility over a patch of its shadow is near 1 - a; its
  // hole (texture alpha 0) lets everything through.
  void translucentCastersLetTheirShareThrough() {
    for (float opacity : {0.3f, 0.6f}) {
      const CardScene sc = cardScene(false, false, opacity);
      const render::RenderView view = cameraView(sc.state, 320, 240);
      const test::ShadowProbe p = test::probeShadows(r_, sc.state, view);
      auto visibilityAt = [&](glm::dvec3 onCard) {
        const glm::dvec3 d(0.6, 0, -1);
        glm::dvec2 px;
        if (!view.project(onCard + d * (onCard.z / -d.z), px)) return -2.0f;
        return p.visibility[size_t(int(px.y)) * size_t(view.width) + size_t(int(px.x))];
      };
      double sum = 0.0;
      int n = 0;
      for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 3; ++j) {
          const float v = visibilityAt({-0.8 + 0.2 * i, 0.6 + 0.15 * j, 2.0});
          QVERIFY(v >= 0.0f);
          sum += double(v);
          ++n;
        }
      const double mean = sum / n;
      const float inHole = visibilityAt({0, 0, 2});
      qInfo("opacity %.1f: mean visibility %.3f under the card (1 - a = %.1f), %.2f through the hole", double(opacity),
            mean, 1.0 - double(opacity), double(inHole));
      QVERIFY(std::abs(mean - (1.0 - double(opacity))) < 0.1);
      QVERIFY(inHole > 0.9f);
    }
  }

  // Costs nothing: without a sun, or with shadows off, no shadow pass runs
  // and the renderer holds no shadow map or caster data (its registry);
  // with them, the map is there with its bytes, and it goes when they go.
  void nothingAllocatedWithoutCasters() {
    auto shadowBytes = [&] {
      size_t b = 0;
      for (const render::GpuAllocation& a : r_.renderer().resourceRegistry())
        if (a.name.rfind("sun_shadow", 0) == 0) b += a.bytes;
      return b;
    };
    auto ranShadow = [](const render::FrameStats& s) {
      for (const render::PassStats& p : s.passes)
        if (p.name.rfind("shadow", 0) == 0) return true;
      return false;
    };
    test::ShadowScene sc = test::shadowScene();
    const render::RenderView view = cameraView(sc.state, 160, 120);
    render::FrameStats stats;
    r_.render(sc.state, view, false, &stats);
    QVERIFY(ranShadow(stats));
    // 1024^2 x 2 cascades of 32-bit depth.
    const size_t mapBytes = size_t(1024) * 1024 * 2 * 4;
    QVERIFY(shadowBytes() >= mapBytes);
    size_t reported = 0;
    for (const render::PassStats& p : stats.passes)
      if (p.name == "shadow_sun") reported = p.gpuBytes;
    QVERIFY(reported >= mapBytes);

    scene::SceneState off = sc.state;
    off.settings.shadows = false;
    r_.render(off, view, false, &stats);
    QVERIFY(!ranShadow(stats));
    QCOMPARE(shadowBytes(), size_t(0));

    scene::SceneState noSun = sc.state;
    for (auto& [id, e] : noSun.entities)
      if (e.light) e.visible = false;
    r_.render(noSun, view, false, &stats);
    QVERIFY(!ranShadow(stats));
    QCOMPARE(shadowBytes(), size_t(0));
    QVERIFY(r_.renderer().sunCascades().empty());
  }

  // A resolution of 0 or 1e6 set in code (the CLI and the file loader
  // refuse or clamp it first): a message naming the field, the map made at
  // the clamped size, the frame still rendered. And the field's own refusal.
  void badResolutions() {
    test::ShadowScene sc = test::shadowScene();
    sc.state.settings.shadowCascades = 1;
    const render::RenderView view = cameraView(sc.state, 160, 120);
    r_.renderer().takeShadowProblems();
    for (int bad : {0, 1000000}) {
      sc.state.settings.shadowResolution = bad;
      render::FrameStats stats;
      const hs::Image img = r_.render(sc.state, view, false, &stats);
      QCOMPARE(img.width, 160);
      const std::vector<std::string> problems = r_.renderer().takeShadowProblems();
      QCOMPARE(problems.size(), size_t(1));
      qInfo("%s", problems[0].c_str());
      QVERIFY(problems[0].find("settings.shadow_resolution") != std::string::npos);
      QVERIFY(problems[0].find(std::to_string(bad)) != std::string::npos);
      size_t bytes = 0;
      for (const render::GpuAllocation& a : r_.renderer().resourceRegistry())
        if (a.name == "sun_shadow_map") bytes = a.bytes;
      const size_t side = bad == 0 ? 256 : 8192;
      QCOMPARE(bytes, side * side * 4);
      // Reported once, not every frame.
      r_.render(sc.state, view, false, &stats);
      QVERIFY(r_.renderer().takeShadowProblems().empty());
    }
    const scene::SettingsField* f = scene::findSettingsField("shadow_resolution");
    QVERIFY(f);
    for (const char* text : {"0", "1e6"}) {
      std::string error;
      QVERIFY(!scene::parseFieldValue(*f, text, error));
      qInfo("set shadow_resolution %s: %s", text, error.c_str());
      QVERIFY(error.find("Shadow map size") != std::string::npos && error.find("256") != std::string::npos);
    }
    scene::SceneSettings s;
    f->set(s, scene::FieldValue(1e6));
    QCOMPARE(s.shadowResolution, 8192);
    f->set(s, scene::FieldValue(0.0));
    QCOMPARE(s.shadowResolution, 256);
  }
};

QTEST_GUILESS_MAIN(TestShadows)
#include "test_shadows.moc"
