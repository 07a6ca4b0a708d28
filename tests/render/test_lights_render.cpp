// Point and spot lights on screen (headless EGL, llvmpipe): a Lambert floor
// lit by one light, each pixel against the light's formula computed here in
// double (candela from lumens, inverse square, the range window, the spot's
// cone), goldens per light type, the window reaching 0 at the range, and
// degenerate values that still render; the clustered light list against
// the brute-force loop, its registry entries and more lights than a
// cluster holds.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/gtc/constants.hpp>

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
// spot's smooth step between the cones, and the floor's luminance
// albedo/π · E, in scene units.
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
  // A Lambert surface's luminance is albedo/π times its illuminance (cd/m²),
  // in scene units through the lights' unit.
  return kAlbedo / pi * glm::dvec3(l.color) * lux * ndl * scene::sceneUnitsPerNit();
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

// Adds point or spot light `id` to a floor scene.
void addLight(scene::SceneState& s, scene::EntityId id, const Light& light, glm::dvec3 at, glm::dvec3 euler = {0, 0, 0}) {
  scene::Entity l;
  l.id = id;
  l.name = "Lamp " + std::to_string(id);
  l.light = light;
  l.transform.translation = at;
  l.transform.rotation = scene::fromEulerDegrees(euler);
  s.entities.emplace(l.id, l);
  s.roots.push_back(l.id);
}

// 48 lights scattered over the floor and above it with ranges from 1 to
// 9 m, so their spheres straddle many tile and slice borders, some spots,
// and a light at the eye whose range holds the camera.
FloorScene manyLightsScene(int size) {
  FloorScene fs = floorScene(pointLight(), {0.0, -9.0, 12.0}, {0, 0, 0}, size);
  fs.state.entities.at(2).light->range = 30.0f;  // the camera is inside this one's range
  fs.state.entities.at(2).light->intensity = 2e5f;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> xy(-18.0, 18.0), z(0.2, 3.0), range(1.0, 9.0), yaw(-60.0, 60.0);
  for (int i = 0; i < 48; ++i) {
    Light l = i % 3 == 2 ? spotLight() : pointLight();
    l.range = float(range(rng));
    l.intensity = 4e5f;
    l.color = {float(0.3 + 0.7 * (i % 5) / 4.0), float(0.3 + 0.7 * (i % 7) / 6.0), 1.0f};
    addLight(fs.state, scene::EntityId(100 + i), l, {xy(rng), xy(rng), z(rng)}, {yaw(rng), 0.0, 0.0});
  }
  return fs;
}

bool hasAllocation(const std::vector<render::GpuAllocation>& reg, const std::string& name) {
  return std::any_of(reg.begin(), reg.end(), [&](const render::GpuAllocation& a) { return a.name == name; });
}

bool ranPass(const render::FrameStats& stats, const std::string& name) {
  return std::any_of(stats.passes.begin(), stats.passes.end(), [&](const render::PassStats& p) { return p.name == name; });
}

// The largest difference between two HDR images relative to 1e-4 + 1e-4 of
// the brighter value (half floats hold 11 bits: 5e-4 relative).
double worstRelativeDifference(const hs::Image& a, const hs::Image& b, int* lit = nullptr) {
  double worst = 0.0;
  if (lit) *lit = 0;
  for (size_t i = 0; i < a.rgbaF.size(); ++i) {
    if (i % 4 == 3) continue;
    const double x = a.rgbaF[i], y = b.rgbaF[i];
    worst = std::max(worst, std::abs(x - y) / (1e-4 + 1e-4 * std::max(std::abs(x), std::abs(y))));
    if (lit && x > 1e-3) ++*lit;
  }
  return worst;
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
    // A sun: the same value everywhere on the flat floor, albedo/π · E cosθ.
    const glm::dvec3 toSun = -glm::normalize(scene::fromEulerDegrees({40, 0, -35}) * glm::dvec3(0, 0, -1));
    const double want = kAlbedo.x / glm::pi<double>() * 60000.0 * toSun.z * scene::sceneUnitsPerNit() * double(sun.color.r);
    QVERIFY2(std::abs(hdrAt(hdr, 64, 100).x / want - 1.0) < 0.01, qPrintable(QString::number(hdrAt(hdr, 64, 100).x)));
    test::verifyGolden("light_sun", r_.render(fs.state, fs.view));
  }

  // Physical units: a white Lambert plane facing a 100 000 lux sun is a
  // white diffuser of luminance E/π = 31 831 cd/m² (not E: the shaders
  // apply the BRDF's 1/π), read back in linear scene units before tone
  // mapping and converted through the lights' unit.
  void whitePlaneUnderTheSunIsEOverPi() {
    Light sun;
    sun.intensity = 100000.0f;
    sun.color = {1.0f, 1.0f, 1.0f};
    FloorScene fs = floorScene(sun, {0, 0, 10});  // no rotation: shining straight down
    scene::Material& floor = fs.state.materials.begin()->second;
    floor.baseColor = glm::vec3(1.0f);
    const hs::Image hdr = r_.render(fs.state, fs.view, true);
    QVERIFY(hdr.isFloat());
    const double want = 100000.0 / glm::pi<double>();
    double worst = 0.0, centre = 0.0;
    for (int y = 8; y < fs.view.height; y += 16)
      for (int x = 8; x < fs.view.width; x += 16) {
        glm::dvec3 p;
        if (!floorHit(fs.view, x, y, p)) continue;
        const glm::dvec3 nits = hdrAt(hdr, x, y) / scene::sceneUnitsPerNit();
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(nits[c] / want - 1.0));
        if (x == 72 && y == 72) centre = nits.g;
      }
    qInfo("white Lambert plane, 100000 lux at normal incidence: %.1f cd/m2 (E/pi = %.1f), worst %.3f%%", centre, want,
          worst * 100.0);
    // Half floats hold 11 bits (0.05%).
    QVERIFY2(worst < 0.002, qPrintable(QString("worst %1% off E/pi").arg(worst * 100.0)));
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

  // The clustered image is the brute-force loop's: the window is 0 at the
  // range, so a light a cluster leaves out adds nothing there, and the
  // cluster sums its lights in the buffer's order.
  void clusteredEqualsBruteForce() {
    for (int size : {160, 97}) {
      const FloorScene fs = manyLightsScene(size);
      render::FrameStats clusteredStats, bruteStats;
      const hs::Image clustered = r_.render(fs.state, fs.view, true, &clusteredStats);
      render::RenderOptions brute;
      brute.bruteForceLights = true;
      const hs::Image reference = r_.render(fs.state, fs.view, true, &bruteStats, brute);
      QVERIFY(clustered.isFloat() && reference.isFloat());
      QVERIFY(ranPass(clusteredStats, "light_culling"));
      QVERIFY(!ranPass(bruteStats, "light_culling"));
      QVERIFY2(clusteredStats.lightsInView > 20, qPrintable(QString::number(clusteredStats.lightsInView)));
      int lit = 0;
      const double worst = worstRelativeDifference(clustered, reference, &lit);
      QVERIFY2(lit > size * size / 2, qPrintable(QString("only %1 channels lit").arg(lit)));
      qInfo("%d px, %zu lights in view: worst difference %.3g of the tolerance", size, clusteredStats.lightsInView, worst);
      QVERIFY2(worst <= 1.0, qPrintable(QString("%1 px: worst difference %2 of the tolerance").arg(size).arg(worst)));
    }
  }

  // The grid exists only in frames with a point or spot light in view
  // (the renderer's registry, not the pass's own counters); a light behind
  // the camera, out of reach of the view, adds no pass and no buffer.
  void noLightInViewHasNoGrid() {
    Light l = pointLight();
    FloorScene fs = floorScene(l, {0.0, 2.0, 2.0});
    render::FrameStats stats;
    r_.render(fs.state, fs.view, true, &stats);
    auto reg = r_.renderer().resourceRegistry();
    QVERIFY(ranPass(stats, "light_culling"));
    QVERIFY(hasAllocation(reg, "light_grid") && hasAllocation(reg, "light_indices"));
    fs.state.entities.at(2).transform.translation = {0.0, -40.0, 30.0};  // behind the eye, range 12 m
    r_.render(fs.state, fs.view, true, &stats);
    reg = r_.renderer().resourceRegistry();
    QVERIFY(!ranPass(stats, "light_culling"));
    QCOMPARE(stats.lightsInView, size_t(0));
    QVERIFY(!hasAllocation(reg, "light_grid") && !hasAllocation(reg, "light_indices") &&
            !hasAllocation(reg, "light_cull_stats"));
  }

  // More lights in one cluster than it holds (128): the first 128 in
  // outliner order light it, the frame says how many clusters overflowed,
  // and the problem is reported once. The image is the brute-force image
  // of the first 128 lights (all 140 share one place, so every cluster
  // they reach overflows).
  void moreLightsThanAClusterHolds() {
    FloorScene fs = floorScene(pointLight(), {0.0, 2.0, 2.0}, {0, 0, 0}, 96);
    FloorScene first128 = fs;
    for (int i = 1; i < 140; ++i) {
      Light l = pointLight();
      l.intensity = 1e4f * float(i);
      addLight(fs.state, scene::EntityId(100 + i), l, {0.0, 2.0, 2.0});
      if (i < 128) addLight(first128.state, scene::EntityId(100 + i), l, {0.0, 2.0, 2.0});
    }
    r_.renderer().takeLightProblems();
    render::FrameStats stats;
    const hs::Image clamped = r_.render(fs.state, fs.view, true, &stats);
    QCOMPARE(stats.lightsInView, size_t(140));
    QVERIFY2(stats.lightClustersOverCap > 10, qPrintable(QString::number(stats.lightClustersOverCap)));
    QCOMPARE(stats.lightsMaxPerCluster, size_t(140));
    const std::vector<std::string> problems = r_.renderer().takeLightProblems();
    QCOMPARE(problems.size(), size_t(1));
    QVERIFY2(problems[0].find("more than 128") != std::string::npos, problems[0].c_str());
    r_.render(fs.state, fs.view, true, &stats);
    QVERIFY(r_.renderer().takeLightProblems().empty());  // once, not every frame
    render::RenderOptions brute;
    brute.bruteForceLights = true;
    const hs::Image reference = r_.render(first128.state, first128.view, true, nullptr, brute);
    int lit = 0;
    const double worst = worstRelativeDifference(clamped, reference, &lit);
    QVERIFY(lit > 1000);
    QVERIFY2(worst <= 1.0, qPrintable(QString("worst difference %1 of the tolerance").arg(worst)));
    // With all 140 the brute-force image is brighter: the cap did drop lights.
    const hs::Image all = r_.render(fs.state, fs.view, true, nullptr, brute);
    QVERIFY(worstRelativeDifference(all, clamped) > 100.0);
  }
};

QTEST_GUILESS_MAIN(TestLightsRender)
#include "test_lights_render.moc"
