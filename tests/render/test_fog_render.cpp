// Fog on screen (headless EGL, llvmpipe; shaders/fog.glsl): depth cueing and
// exponential height fog against their formulas computed here (the height
// fog's optical depth by summing the density along the ray, not from the
// closed form the shader uses), the horizontal-ray limit, extreme values
// that must stay finite, goldens per mode, and nothing for it without fog.
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "image_compare.h"
#include "render_golden.h"
#include "look_from.h"
#include "material_scenes.h"
#include "mesh/primitives.h"
#include "render/offscreen_renderer.h"
#include "scene/mesh_materials.h"
#include "scene/scene_state.h"

using namespace hs;

namespace {


glm::dvec3 hdrAt(const hs::Image& img, int x, int y) {
  const float* p = &img.rgbaF[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
  return {p[0], p[1], p[2]};
}

// A 2 km unlit grey floor at z = 0 (its colour is exactly its base colour,
// so fog is all that changes it), a sky, seen from `eye` towards `target`.
struct FogScene {
  scene::SceneState state;
  render::RenderView view;
};

FogScene fogScene(glm::dvec3 eye, glm::dvec3 target, bool wall = false) {
  FogScene out;
  scene::SceneState& s = out.state;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.fogColour = {0.5f, 0.6f, 0.7f};
  mesh::MeshData plane = mesh::gridPlane(2000.0f, 1);
  scene::Material m;
  m.baseColor = {0.2f, 0.3f, 0.1f};
  m.unlit = true;
  m.twoSided = true;
  scene::Entity& floor = test::addMeshEntity(s, std::move(plane), m, "Floor");
  if (wall) {  // stood up: the plane y = 0, facing the eye on -Y
    floor.transform.rotation = scene::fromEulerDegrees({90, 0, 0});
  }
  out.view.width = out.view.height = 96;
  out.view.fovY = glm::radians(50.0);
  out.view.eye = eye;
  out.view.orientation = test::lookFrom(eye, target).rotation;
  return out;
}

glm::dvec3 rayDir(const render::RenderView& v, int x, int y) {
  const double t = std::tan(v.fovY * 0.5);
  const double ndcX = (2.0 * (x + 0.5) / v.width - 1.0) * t * v.aspect();
  const double ndcY = (1.0 - 2.0 * (y + 0.5) / v.height) * t;
  return glm::normalize(v.forward() + ndcX * v.right() + ndcY * v.up());
}

// Distance along the ray to the floor (z = 0) or the wall (y = 0); < 0: none.
double hitDistance(const render::RenderView& v, glm::dvec3 d, bool wall) {
  const double t = wall ? (d.y > 1e-9 ? -v.eye.y / d.y : -1.0) : (d.z < -1e-9 ? -v.eye.z / d.z : -1.0);
  if (t < 0.0) return -1.0;
  const glm::dvec3 p = v.eye + t * d;
  return std::abs(p.x) < 990.0 && std::abs(wall ? p.z : p.y) < 990.0 ? t : -1.0;
}

// Height fog transmittance by a midpoint sum of ρ(z) = ρ0 e^(−b(z − h)).
double heightFogTransmittance(const scene::SceneSettings& s, glm::dvec3 eye, glm::dvec3 d, double dist) {
  const int n = 4000;
  double tau = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = eye.z + d.z * dist * (i + 0.5) / n;
    tau += double(s.fogDensity) * std::exp(-double(s.fogHeightFalloff) * (z - double(s.fogHeight))) * dist / n;
  }
  return std::exp(-tau);
}

glm::dvec3 fogged(const scene::SceneSettings& s, glm::dvec3 c, double t) {
  return glm::mix(glm::dvec3(s.fogColour), c, t);
}

}  // namespace

class TestFogRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

  static bool hasFogBlock(const std::vector<render::GpuAllocation>& reg) {
    return std::any_of(reg.begin(), reg.end(), [](const render::GpuAllocation& a) { return a.name == "fog_block"; });
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // First, on a fresh renderer: without fog there is no fog block in the
  // registry (and the image is the unfogged colour); the first frame with
  // fog makes one.
  void noFogCostsNothing() {
    FogScene fs = fogScene({0, -50, 20}, {0, 0, 0});
    const hs::Image clear = r_.render(fs.state, fs.view, true);
    QVERIFY(!hasFogBlock(r_.renderer().resourceRegistry()));
    QVERIFY(std::abs(hdrAt(clear, 48, 80).x - 0.2) < 2e-3);
    fs.state.settings.fogMode = scene::FogMode::DepthCue;
    r_.render(fs.state, fs.view, true);
    QVERIFY(hasFogBlock(r_.renderer().resourceRegistry()));
  }

  void depthCueMatchesFormula() {
    FogScene fs = fogScene({0, -50, 20}, {0, 200, 0});
    scene::SceneSettings& s = fs.state.settings;
    s.fogMode = scene::FogMode::DepthCue;
    s.fogK1 = 0.8f;  // below 1: the nearest surfaces keep all their colour (the min)
    s.fogK2 = 0.004f;
    const hs::Image img = r_.render(fs.state, fs.view, true);
    int checked = 0;
    for (int y = 0; y < fs.view.height; y += 2)
      for (int x = 0; x < fs.view.width; x += 2) {
        const glm::dvec3 d = rayDir(fs.view, x, y);
        const double dist = hitDistance(fs.view, d, false);
        if (dist < 0.0) continue;
        const double f = std::min(1.0, 1.0 / (double(s.fogK1) + double(s.fogK2) * dist));
        const glm::dvec3 want = fogged(s, glm::dvec3(0.2, 0.3, 0.1), f), got = hdrAt(img, x, y);
        for (int c = 0; c < 3; ++c)
          QVERIFY2(std::abs(got[c] - want[c]) < 2e-3 + 0.01 * want[c],
                   qPrintable(QString("(%1,%2) at %3 m: %4, want %5").arg(x).arg(y).arg(dist).arg(got[c]).arg(want[c])));
        ++checked;
      }
    QVERIFY(checked > 600);
    s.tonemap = scene::Tonemap::Aces;
    test::verifyGolden("fog_depth_cue", r_.render(fs.state, fs.view));
  }

  void heightFogMatchesFormula() {
    FogScene fs = fogScene({0, -50, 30}, {0, 200, 0});
    scene::SceneSettings& s = fs.state.settings;
    s.fogMode = scene::FogMode::ExponentialHeight;
    s.fogDensity = 0.01f;
    s.fogHeightFalloff = 0.08f;
    s.fogHeight = 5.0f;
    const hs::Image img = r_.render(fs.state, fs.view, true);
    int checked = 0;
    for (int y = 0; y < fs.view.height; y += 2)
      for (int x = 0; x < fs.view.width; x += 2) {
        const glm::dvec3 d = rayDir(fs.view, x, y);
        const double dist = hitDistance(fs.view, d, false);
        if (dist < 0.0) continue;
        const glm::dvec3 want = fogged(s, glm::dvec3(0.2, 0.3, 0.1), heightFogTransmittance(s, fs.view.eye, d, dist));
        const glm::dvec3 got = hdrAt(img, x, y);
        for (int c = 0; c < 3; ++c)
          QVERIFY2(std::abs(got[c] - want[c]) < 2e-3 + 0.01 * want[c],
                   qPrintable(QString("(%1,%2) at %3 m: %4, want %5").arg(x).arg(y).arg(dist).arg(got[c]).arg(want[c])));
        ++checked;
      }
    QVERIFY(checked > 600);
    s.tonemap = scene::Tonemap::Aces;
    test::verifyGolden("fog_height", r_.render(fs.state, fs.view));
  }

  // A wall seen straight ahead: the middle rows' rays are (nearly)
  // horizontal, where the closed form's (1 − e^(−bΔz))/(bΔz) is 0/0.
  void heightFogHorizontalRays() {
    FogScene fs = fogScene({0, -300, 40}, {0, 0, 40}, true);
    scene::SceneSettings& s = fs.state.settings;
    s.fogMode = scene::FogMode::ExponentialHeight;
    s.fogDensity = 0.004f;
    s.fogHeightFalloff = 0.05f;
    s.fogHeight = 30.0f;
    const hs::Image img = r_.render(fs.state, fs.view, true);
    for (int y = 44; y <= 51; ++y)
      for (int x = 20; x < 76; x += 5) {
        const glm::dvec3 d = rayDir(fs.view, x, y);
        const double dist = hitDistance(fs.view, d, true);
        QVERIFY(dist > 0.0);
        const glm::dvec3 want = fogged(s, glm::dvec3(0.2, 0.3, 0.1), heightFogTransmittance(s, fs.view.eye, d, dist));
        const glm::dvec3 got = hdrAt(img, x, y);
        for (int c = 0; c < 3; ++c)
          QVERIFY2(std::isfinite(got[c]) && std::abs(got[c] - want[c]) < 2e-3 + 0.01 * want[c],
                   qPrintable(QString("(%1,%2): %3, want %4").arg(x).arg(y).arg(got[c]).arg(want[c])));
      }
  }

  // Densities, falloffs and heights at the ends of their ranges: every
  // pixel, sky included, stays finite, and between the floor's colour and
  // the fog's.
  void extremesStayFinite() {
    FogScene fs = fogScene({0, -50, 20}, {0, 200, 10});
    scene::SceneSettings& s = fs.state.settings;
    s.fogMode = scene::FogMode::ExponentialHeight;
    for (float density : {0.0f, 1e-6f, 10.0f})
      for (float falloff : {0.0f, 1e-6f, 10.0f})
        for (float height : {-1e5f, 0.0f, 1e5f}) {
          s.fogDensity = density;
          s.fogHeightFalloff = falloff;
          s.fogHeight = height;
          const hs::Image img = r_.render(fs.state, fs.view, true);
          for (size_t i = 0; i < img.rgbaF.size(); ++i)
            QVERIFY2(std::isfinite(img.rgbaF[i]) && img.rgbaF[i] >= 0.0f && img.rgbaF[i] < 10.0f,
                     qPrintable(QString("density %1 falloff %2 height %3: %4").arg(density).arg(falloff).arg(height).arg(img.rgbaF[i])));
        }
  }
};

QTEST_GUILESS_MAIN(TestFogRender)
#include "test_fog_render.moc"
