// Point and spot lights on screen (headless EGL, llvmpipe): a Lambert floor
// lit by one light, each pixel against the light's formula computed here in
// double (candela from lumens, inverse square, the range window, the spot's
// cone), goldens per light type, the window reaching 0 at the range, and
// degenerate values that still render.
#include <QtTest>

#include <cmath>

#include "image_compare.h"
#include "render_golden.h"
#include "look_from.h"
#include "material_scenes.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "scene/light_units.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

using namespace hs;
using scene::Light;

namespace {


glm::dvec3 hdrAt(const hs::Image& img, int x, int y) {
  const float* p = &img.rgbaF[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return {p[0], p[1], p[2]};
}

constexpr glm::dvec3 kAlbedo{0.8, 0.8, 0.8};

// A 40 x 40 m Lambert floor at z = 0, seen from above and in front, no sun,
// no sky, no ambient light, no tone mapping: a pixel is the light's alone.
struct FloorScene {
  scene::SceneState state;
  render::RenderView view;
};

FloorScene floorScene(const Light& light, glm::dvec3 at, glm::dvec3 euler = {0, 0, 0}, int size = 128) {
  FloorScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.0f;
  s.settings.skyZenith = s.settings.skyHorizon = s.settings.groundColor = glm::vec3(0.0f);
  mesh::MeshData plane = mesh::gridPlane(40.0f, 1);
  scene::Material m;
  m.baseColor = glm::vec3(kAlbedo);
  m.model = scene::LightingModel::Lambert;
  test::addMeshEntity(s, std::move(plane), m, "Floor");
  scene::Entity l;
  l.id = 2;
  l.name = "Lamp";
  l.light = light;
  l.transform.translation = at;
  l.transform.rotation = scene::fromEulerDegrees(euler);
  s.entities.emplace(l.id, l);
  s.roots.push_back(l.id);
  out.view.width = out.view.height = size;
  out.view.fovY = glm::radians(60.0);
  out.view.eye = {0.0, -9.0, 12.0};
  out.view.orientation = test::lookFrom(out.view.eye, {0, 1, 0}).rotation;
  return out;
}

// Where the ray through pixel (x, y) meets the floor (z = 0).
bool floorHit(const render::RenderView& v, int x, int y, glm::dvec3& hit) {
  const double t = std::tan(v.fovY * 0.5);
  const double ndcX = (2.0 * (x + 0.5) / v.width - 1.0) * t * v.aspect();
  const double ndcY = (1.0 - 2.0 * (y + 0.5) / v.height) * t;
  const glm::dvec3 d = glm::normalize(v.forward() + ndcX * v.right() + ndcY * v.up());
  if (d.z >= -1e-6) return false;
  hit = v.eye + (-v.eye.z / d.z) * d;
  return std::abs(hit.x) < 19.5 && std::abs(hit.y) < 19.5;
}

// The light's value at floor point p, from the definitions in
// scene/components.h, written again here: I = Φ/4π (point) or
// Φ/(2π(1 − cos(outer/2))) (spot), E = I cosθ / d² · (1 − (d/r)⁴)², the
// spot's smooth step between the cones, in scene units.
glm::dvec3 expected(const Light& l, glm::dvec3 pos, glm::dvec3 dir, glm::dvec3 p) {
  const double pi = 3.14159265358979;
  double candela = double(l.intensity) / (4.0 * pi);
  if (l.type == Light::Type::Spot)
    candela = double(l.intensity) / (2.0 * pi * (1.0 - std::cos(glm::radians(double(l.outerConeDeg)) / 2.0)));
  const glm::dvec3 toLight = pos - p;
  const double d = glm::length(toLight);
  const glm::dvec3 dl = toLight / d;
  const double ndl = std::max(dl.z, 0.0);
  const double x = d / double(l.range);
  const double window = std::pow(std::clamp(1.0 - x * x * x * x, 0.0, 1.0), 2.0);
  double cone = 1.0;
  if (l.type == Light::Type::Spot) {
    const double ci = std::cos(glm::radians(double(l.innerConeDeg)) / 2.0);
    const double co = std::cos(glm::radians(double(l.outerConeDeg)) / 2.0);
    const double t = std::clamp((glm::dot(-dl, dir) - co) / std::max(ci - co, 1e-4), 0.0, 1.0);
    cone = t * t;
  }
  const double lux = candela * window * cone / (d * d);
  return kAlbedo * glm::dvec3(l.color) * lux * ndl / (1.2 * std::pow(2.0, 15.2));
}

Light pointLight() {
  Light l;
  l.type = Light::Type::Point;
  l.color = {1.0f, 0.8f, 0.6f};
  l.intensity = 2.5e6f;  // lumens: about 2 in scene units at 2 m
  l.range = 12.0f;
  return l;
}

Light spotLight() {
  Light l = pointLight();
  l.type = Light::Type::Spot;
  l.color = {0.6f, 0.8f, 1.0f};
  l.intensity = 1.5e6f;
  l.range = 25.0f;
  l.innerConeDeg = 40.0f;
  l.outerConeDeg = 70.0f;
  return l;
}

}  // namespace

class TestLightsRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;


  // Every floor pixel against `expected`; returns how many were compared.
  int compareWithFormula(const FloorScene& fs, const Light& l, glm::dvec3 pos, glm::dvec3 dir, double& worst) {
    const hs::Image hdr = r_.render(fs.state, fs.view, true);
    if (!hdr.isFloat()) return 0;
    int checked = 0;
    worst = 0.0;
    for (int y = 1; y < fs.view.height; y += 3)
      for (int x = 1; x < fs.view.width; x += 3) {
        glm::dvec3 p;
        if (!floorHit(fs.view, x, y, p)) continue;
        const glm::dvec3 want = expected(l, pos, dir, p);
        const glm::dvec3 got = hdrAt(hdr, x, y);
        for (int c = 0; c < 3; ++c) {
          // Half floats, and the pixel's footprint where the light changes fast.
          const double err = std::abs(got[c] - want[c]) / (0.004 + 0.03 * want[c]);
          worst = std::max(worst, err);
        }
        ++checked;
      }
    return checked;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void pointLightMatchesItsFormula() {
    const Light l = pointLight();
    const glm::dvec3 pos{1.0, 2.0, 2.0};
    const FloorScene fs = floorScene(l, pos);
    double worst = 0.0;
    const int checked = compareWithFormula(fs, l, pos, {0, 0, -1}, worst);
    QVERIFY(checked > 1000);
    QVERIFY2(worst <= 1.0, qPrintable(QString("worst error %1 of the tolerance").arg(worst)));
    test::verifyGolden("light_point", r_.render(fs.state, fs.view));
  }

  void spotLightMatchesItsFormula() {
    const Light l = spotLight();
    // Tilted 30° about X: local -Z shines down and towards +Y.
    const glm::dvec3 pos{0.0, -1.0, 5.0};
    const FloorScene fs = floorScene(l, pos, {-30, 0, 0});
    const glm::dvec3 dir = glm::normalize(scene::fromEulerDegrees({-30, 0, 0}) * glm::dvec3(0, 0, -1));
    double worst = 0.0;
    const int checked = compareWithFormula(fs, l, pos, dir, worst);
    QVERIFY(checked > 1000);
    QVERIFY2(worst <= 1.0, qPrintable(QString("worst error %1 of the tolerance").arg(worst)));
    test::verifyGolden("light_spot", r_.render(fs.state, fs.view));
  }

  void sunGolden() {
    Light sun;
    sun.intensity = 60000.0f;
    FloorScene fs = floorScene(sun, {0, 0, 10}, {40, 0, -35});
    fs.state.settings.tonemap = scene::Tonemap::Aces;
    const hs::Image hdr = r_.render(fs.state, fs.view, true);
    // A sun: the same value everywhere on the flat floor, E cosθ.
    const glm::dvec3 toSun = -glm::normalize(scene::fromEulerDegrees({40, 0, -35}) * glm::dvec3(0, 0, -1));
    const double want = kAlbedo.x * 60000.0 * toSun.z / (1.2 * std::pow(2.0, 15.2)) * double(sun.color.r);
    QVERIFY2(std::abs(hdrAt(hdr, 64, 100).x / want - 1.0) < 0.01, qPrintable(QString::number(hdrAt(hdr, 64, 100).x)));
    test::verifyGolden("light_sun", r_.render(fs.state, fs.view));
  }

  // The window is exactly 0 from the range on, so a light list that drops a
  // light there loses nothing; just inside, the light still reaches.
  void windowReachesZeroAtTheRange() {
    Light l = pointLight();
    l.range = 6.0f;
    const glm::dvec3 pos{0.0, 2.0, 1.0};
    const FloorScene fs = floorScene(l, pos);
    const hs::Image hdr = r_.render(fs.state, fs.view, true);
    int beyond = 0, inside = 0;
    for (int y = 0; y < fs.view.height; ++y)
      for (int x = 0; x < fs.view.width; ++x) {
        glm::dvec3 p;
        if (!floorHit(fs.view, x, y, p)) continue;
        const double d = glm::length(p - pos);
        const glm::dvec3 got = hdrAt(hdr, x, y);
        if (d >= double(l.range) * 1.001) {
          QVERIFY2(got == glm::dvec3(0.0), qPrintable(QString("lit at %1 m, beyond the range").arg(d)));
          ++beyond;
        } else if (d < double(l.range) * 0.9 && got.x > 0.0) {
          ++inside;
        }
      }
    QVERIFY(beyond > 1000 && inside > 500);
  }

  // Values at the edges of their ranges render a finite frame: a spot whose
  // cones coincide (a hard edge), the narrowest and widest cones, zero power.
  void degenerateLightsStillRender() {
    for (auto [inner, outer, power] : {std::tuple{45.0f, 45.0f, 1e6f}, std::tuple{0.1f, 0.1f, 1e6f},
                                      std::tuple{179.9f, 179.9f, 1e6f}, std::tuple{30.0f, 60.0f, 0.0f}}) {
      Light l = spotLight();
      l.innerConeDeg = inner;
      l.outerConeDeg = outer;
      l.intensity = power;
      const FloorScene fs = floorScene(l, {0, 0, 3}, {0, 0, 0}, 48);
      const hs::Image hdr = r_.render(fs.state, fs.view, true);
      QVERIFY(hdr.isFloat());
      for (float v : hdr.rgbaF) QVERIFY2(std::isfinite(v), qPrintable(QString("cones %1/%2").arg(inner).arg(outer)));
    }
  }
};

QTEST_GUILESS_MAIN(TestLightsRender)
#include "test_lights_render.moc"
