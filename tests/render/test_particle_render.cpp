// Particle emitters drawn (render/particle_source.h): each preset against a
// golden and visibly there; soft particles fade where they meet the ground;
// alpha and additive particles in front of and behind a translucent pane
// composite as depth peeling does in the A-buffer, fixed array and
// K-buffer, additive ones past their layers too (the tail sums them); a frame is the same alone or after a run of frames (replay
// cache); no emitter, or one behind the camera, costs no pass, buffer or
// draw, nor one drawing meshes whose shadow cannot reach the view either;
// mesh particles (draw_mesh) draw as a mesh entity placed at the
// particle would, a missing draw_mesh is reported and loses nothing else,
// and particlesDrawn counts them. Scenes at UTM coordinates
// (camera-relative drawing).
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "look_from.h"
#include "mesh/primitives.h"
#include "particles/evaluate.h"
#include "particles/presets.h"
#include "particles/rng.h"
#include "pass_stats.h"
#include "render/offscreen_renderer.h"
#include "render/particle_mesh.h"
#include "render_golden.h"
#include "scene/animation.h"
#include "scene/scene_state.h"
#include "scene_parts.h"

using namespace hs;
using test::passRan;

namespace {

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);
constexpr scene::AssetId kGroundAsset = 1, kPaneAsset = 2, kRockAsset = 3;
constexpr scene::EntityId kFirstEmitter = 100;

// An opaque ground (dark, unlit: its colour is exact in every image) at the
// UTM origin's height, a sun, no grid, no tone mapping.
scene::SceneState ground() {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.3f;
  test::addMeshAsset(s, kGroundAsset, "Ground", mesh::gridPlane(200.0f, 1), {0.05f, 0.06f, 0.08f}, 1.0f, true);
  scene::Entity g;
  g.id = 1;
  g.name = "Ground";
  g.mesh = scene::MeshInstance{kGroundAsset};
  g.transform.translation = kUtm;
  s.entities.emplace(g.id, g);
  s.roots.push_back(g.id);
  test::addSun(s, 1000, {50, 0, -30});
  return s;
}

void addEmitters(scene::SceneState& s, const std::vector<particles::EmitterDesc>& descs) {
  scene::EntityId id = kFirstEmitter;
  while (s.entities.count(id)) ++id;
  for (const particles::EmitterDesc& d : descs) {
    scene::Entity e;
    e.id = id++;
    e.name = d.name;
    e.particles = scene::ParticleEmitter{d};  // desc.origin is the world position (entity at 0)
    s.entities.emplace(e.id, e);
    s.roots.push_back(e.id);
  }
}

void removeEmitters(scene::SceneState& s) {
  for (auto it = s.entities.begin(); it != s.entities.end();)
    if (it->second.particles) {
      s.roots.erase(std::remove(s.roots.begin(), s.roots.end(), it->first), s.roots.end());
      it = s.entities.erase(it);
    } else {
      ++it;
    }
}

render::RenderView camera(glm::dvec3 eyeRel, glm::dvec3 atRel, int w = 160, int h = 90, double fovDeg = 60.0) {
  render::RenderView v;
  v.width = w;
  v.height = h;
  v.fovY = glm::radians(fovDeg);
  v.eye = kUtm + eyeRel;
  v.orientation = test::lookFrom(v.eye, kUtm + atRel).rotation;
  return v;
}

// A still emitter: `count` particles born at t = 0 in a box around `at`
// (relative to kUtm), living long, not moving; unlit colour `rgba`.
particles::EmitterDesc still(const std::string& name, glm::dvec3 at, glm::dvec3 half, int count, double size,
                             glm::dvec4 rgba, particles::Sprite sprite = particles::Sprite::Spark,
                             particles::Blend blend = particles::Blend::Alpha, uint32_t seed = 7) {
  particles::EmitterDesc d;
  d.name = name;
  d.seed = seed;
  d.origin = kUtm + at;
  d.rate = 0.0;
  d.bursts = {{0.0, count}};
  d.shape = half == glm::dvec3(0.0) ? particles::Shape::Point : particles::Shape::Box;
  d.boxHalf = half == glm::dvec3(0.0) ? glm::dvec3(1.0) : half;
  d.speedMin = d.speedMax = 0.0;
  d.lifetimeMin = d.lifetimeMax = 1000.0;
  d.sizeMin = d.sizeMax = size;
  d.gravity = glm::dvec3(0.0);
  d.colourOverLife.keys = {{0.0, rgba}};
  d.sprite = sprite;
  d.blend = blend;
  d.softDistance = 0.0;
  d.lit = false;
  return d;
}

// An axis-aligned box from `lo` to `hi` with flat normals (24 vertices,
// 12 triangles): off the origin and longer along x than across, so a wrong
// centre, scale or turn of a mesh particle shows.
mesh::MeshData box(glm::vec3 lo, glm::vec3 hi) {
  mesh::MeshData m;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      glm::vec3 n(0.0f);
      n[axis] = side ? 1.0f : -1.0f;
      const uint32_t first = uint32_t(m.positions.size());
      for (int k = 0; k < 4; ++k) {
        glm::vec3 p;
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        p[v] = k >= 2 ? hi[v] : lo[v];
        m.positions.push_back(p);
        m.normals.push_back(n);
        m.uvs.emplace_back(float(k == 1 || k == 2), float(k >= 2));
      }
      // Counter-clockwise seen from outside (u x v is +axis): one-sided
      // materials cull the back faces.
      const uint32_t order[2][6] = {{0, 2, 1, 0, 3, 2}, {0, 1, 2, 0, 2, 3}};
      for (uint32_t i : order[side]) m.indices.push_back(first + i);
    }
  m.submeshes.push_back({0, uint32_t(m.indices.size()), -1});
  return m;
}

// The rock: a 1 x 0.5 x 0.3 m box whose centre is off its origin, lit,
// under entity `id` named "Rock", hidden (users hide a mesh particle's
// source so it is not drawn at its own place).
const glm::vec3 kRockLo(0.2f, -0.1f, 0.05f), kRockHi(1.2f, 0.4f, 0.35f);
void addHiddenRock(scene::SceneState& s, scene::EntityId id) {
  test::addMeshAsset(s, kRockAsset, "Rock", box(kRockLo, kRockHi), {0.7f, 0.45f, 0.25f});
  scene::Entity e;
  e.id = id;
  e.name = "Rock";
  e.mesh = scene::MeshInstance{kRockAsset};
  e.transform.translation = kUtm + glm::dvec3(30, 30, 0);
  e.visible = false;
  s.entities.emplace(e.id, e);
  s.roots.push_back(e.id);
}

// ground() lit (grey), the sun casting shadows, the hidden "Rock" for
// mesh particles, at 1.5 s.
scene::SceneState shadowedGroundWithRock() {
  scene::SceneState s = ground();
  s.materials[kGroundAsset].unlit = false;
  s.materials[kGroundAsset].baseColor = {0.5f, 0.5f, 0.5f};
  s.settings.shadows = true;
  s.entities[1000].light->castsShadows = true;
  s.time.seconds = 1.5;
  addHiddenRock(s, 3);
  return s;
}

double lum(const Image& img, int x, int y) {  // top row first; 0..255
  const uint8_t* p = &img.rgba8[(size_t(y) * img.width + x) * 4];
  return (double(p[0]) + p[1] + p[2]) / 3.0;
}

int maxDiff(const Image& a, const Image& b) {
  int m = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) m = std::max(m, std::abs(int(a.rgba8[i]) - int(b.rgba8[i])));
  return m;
}

double meanDiff(const Image& a, const Image& b) {
  double s = 0;
  for (size_t i = 0; i < a.rgba8.size(); ++i) s += std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
  return s / double(a.rgba8.size());
}

// Pixels whose largest channel difference is over `threshold`.
size_t pixelsApart(const Image& a, const Image& b, int threshold) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < a.rgba8.size(); i += 4) {
    int m = 0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a.rgba8[i + c]) - int(b.rgba8[i + c])));
    n += m > threshold;
  }
  return n;
}

// Leaves an image next to the goldens' failures (HS_TEST_OUT_DIR) for a look.
void keep(const std::string& name, const Image& img) {
  QDir().mkpath(HS_TEST_OUT_DIR);
  test::writePng(std::string(HS_TEST_OUT_DIR) + "/" + name + ".png", test::toTest(img));
}

size_t particleAllocations(const render::Renderer& r) {
  size_t n = 0;
  for (const render::GpuAllocation& a : r.resourceRegistry()) {
    bool mine = a.name.find("particles") != std::string::npos;
    for (const std::string& u : a.users) mine = mine || u.find("particles") != std::string::npos;
    n += mine ? 1 : 0;
  }
  return n;
}

}  // namespace

class TestParticleRender : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

  // `s` drawn in transparency mode `mode` against `reference` (depth
  // peeling): the largest channel difference; over 2, both images are kept
  // as `name` for a look.
  int fromPeeling(scene::SceneState& s, const render::RenderView& view, scene::Transparency mode,
                  const Image& reference, const std::string& name, render::FrameStats* stats = nullptr) {
    s.settings.transparency = mode;
    const Image img = r_.render(s, view, false, stats);
    const int m = maxDiff(img, reference);
    if (m > 2) {
      keep(name + "_reference", reference);
      keep(name + "_mode" + std::to_string(int(mode)), img);
    }
    return m;
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  // Each preset at a fixed time: its golden, and visibly more than the
  // ground alone (a preset that draws nothing fails here, not only on the
  // golden's first write).
  void presetsMatchGoldens() {
    // Snow: a small dense patch seen from close by, a few metres under the
    // box it is born in (30 m up; the wind carries it east as it falls):
    // flakes of 1-2.5 cm are under a pixel from farther away, and a cold
    // frame replays every flake's path, so the patch stays small.
    const struct {
      const char* name;
      double t;
      double halfArea;  // metres around the origin (snow, fog, dust)
      double rate;      // particles per second of the main emitter (0: the preset's)
      render::RenderView view;
      double minMeanDiff;  // 0..255 per channel over the image
    } presets[] = {
        {"snow", 2.0, 1.0, 150.0, camera({3, -2.5, 26.5}, {3, 0, 26.5}, 160, 90, 50.0), 0.03},
        {"fog", 40.0, 5.0, 3.0, camera({0, -9.0, 1.7}, {0, 0, 1.5}), 0.5},
        {"torch", 2.0, 0.0, 0.0, camera({0, -3.0, 1.2}, {0, 0, 0.8}), 0.05},
        {"campfire", 2.0, 0.0, 0.0, camera({0, -3.0, 1.2}, {0, 0, 0.8}), 0.1},
        {"dust", 8.0, 5.0, 20.0, camera({0, -9.0, 1.7}, {0, 0, 1.0}), 0.3}};
    for (const auto& p : presets) {
      scene::SceneState s = ground();
      s.time.seconds = p.t;
      const render::RenderView& view = p.view;
      const Image empty = r_.render(s, view);
      particles::PresetOptions o;
      o.at = kUtm;
      if (p.halfArea > 0)
        o.area = glm::dvec4(kUtm.x - p.halfArea, kUtm.y - p.halfArea, kUtm.x + p.halfArea, kUtm.y + p.halfArea);
      if (p.rate > 0) o.rate = p.rate;
      std::string error;
      const std::vector<particles::EmitterDesc> descs = particles::makePreset(p.name, o, error);
      QVERIFY2(!descs.empty(), error.c_str());
      addEmitters(s, descs);
      render::FrameStats stats;
      const Image img = r_.render(s, view, false, &stats);
      QVERIFY2(stats.particlesDrawn > 0, p.name);
      const double d = meanDiff(img, empty);
      if (d <= p.minMeanDiff) keep(std::string("particles_") + p.name + "_faint", img);
      QVERIFY2(d > p.minMeanDiff, (std::string(p.name) + ": mean difference " + std::to_string(d)).c_str());
      test::verifyGolden(std::string("particles_") + p.name, img, {12, 4, 0.01});
    }
  }

  // A white particle half sunk into the ground: with a soft distance the
  // pixels just above the line where it meets the ground are darker (more
  // transparent) than the hard particle's, and far above the line the same.
  void softParticlesFadeAtTheGround() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    const render::RenderView view = camera({0, -6.0, 1.0}, {0, 0, 0.5}, 160, 90, 40.0);
    particles::EmitterDesc d = still("Puff", {0, 0, 0}, glm::dvec3(0.0), 1, 2.0, {1, 1, 1, 0.9});
    addEmitters(s, {d});
    const Image hard = r_.render(s, view);
    removeEmitters(s);
    d.softDistance = 1.0;
    addEmitters(s, {d});
    const Image soft = r_.render(s, view);
    removeEmitters(s);
    const Image none = r_.render(s, view);
    // The column through the particle's centre: find the intersection line
    // (the lowest row the hard particle brightens) going up from the bottom.
    const int x = view.width / 2;
    int line = -1;
    for (int y = view.height - 1; y >= 0 && line < 0; --y)
      if (lum(hard, x, y) > lum(none, x, y) + 20.0) line = y;
    QVERIFY2(line > 0, "the particle is not in view");
    const int near = line - 1;  // just above the line
    QVERIFY2(lum(soft, x, near) < lum(hard, x, near) - 20.0,
             qPrintable(QString("soft %1 hard %2").arg(lum(soft, x, near)).arg(lum(hard, x, near))));
    QVERIFY(lum(soft, x, near) >= lum(none, x, near) - 1.0);  // fading, never darker than the ground
    // Well above the line the ground behind is over a soft distance away.
    int top = near;
    while (top > 0 && lum(hard, x, top - 1) > lum(none, x, top - 1) + 20.0) --top;
    const int above = (top + near) / 2 - (near - top) / 4;
    QVERIFY(near - above > 5);
    QVERIFY2(std::abs(lum(soft, x, above) - lum(hard, x, above)) <= 2.0,
             qPrintable(QString("row %1: soft %2 hard %3").arg(above).arg(lum(soft, x, above)).arg(lum(hard, x, above))));
  }

  // Alpha particles in front of and behind a translucent pane, and additive
  // sparks behind it: the A-buffer, fixed array and K-buffer composite them
  // as depth peeling does (within 2/255), and the order matters (the pane
  // in front of the particles differs from behind them).
  void sortingMatchesDepthPeeling() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    s.settings.ambientIntensity = 0.0f;
    test::addMeshAsset(s, kPaneAsset, "Pane", mesh::gridPlane(3.0f, 1), {0.9f, 0.2f, 0.1f}, 0.5f, true);
    scene::Entity pane;
    pane.id = 2;
    pane.name = "Pane";
    pane.mesh = scene::MeshInstance{kPaneAsset};
    pane.transform.translation = kUtm + glm::dvec3(0, 0, 1.2);
    pane.transform.rotation = glm::angleAxis(glm::radians(90.0), glm::dvec3(1, 0, 0));  // facing -Y (the camera)
    s.entities.emplace(pane.id, pane);
    s.roots.push_back(pane.id);
    const render::RenderView view = camera({0, -5.0, 1.2}, {0, 0, 1.2}, 120, 80, 45.0);
    // Seeds with no two particles at one depth: such a full tie is what
    // depth peeling cannot order (it keeps one of them; test_oit).
    addEmitters(s, {still("Front", {-0.4, -0.6, 1.2}, {0.5, 0.2, 0.4}, 12, 0.5, {0.2, 0.5, 1.0, 0.6},
                          particles::Sprite::Smoke, particles::Blend::Alpha, 11),
                    still("Behind", {0.4, 0.6, 1.2}, {0.5, 0.2, 0.4}, 12, 0.5, {0.3, 1.0, 0.3, 0.7},
                          particles::Sprite::Smoke, particles::Blend::Alpha, 4),
                    still("Sparks", {0.0, 0.5, 1.0}, {0.6, 0.2, 0.3}, 20, 0.3, {3.0, 1.2, 0.3, 1.0},
                          particles::Sprite::Spark, particles::Blend::Additive, 5)});
    // The K-buffer keeps every layer (K = 32: none in its tail).
    s.settings.kbufferK = 32;
    s.settings.transparency = scene::Transparency::Reference;
    render::FrameStats stats;
    const Image reference = r_.render(s, view, false, &stats);
    QCOMPARE(stats.particlesDrawn, size_t(44));
    QVERIFY(stats.oit.peels >= 3);
    for (auto mode : {scene::Transparency::ABuffer, scene::Transparency::ABufferFixed, scene::Transparency::KBuffer}) {
      const int m = fromPeeling(s, view, mode, reference, "particles_sort");
      QVERIFY2(m <= 2, qPrintable(QString("mode %1: max difference %2 from depth peeling").arg(int(mode)).arg(m)));
    }
    // The pane moved behind every particle: a different image, so the
    // comparison above saw an order that matters.
    s.entities[2].transform.translation = kUtm + glm::dvec3(0, 2.0, 1.2);
    s.settings.transparency = scene::Transparency::Reference;
    const Image moved = r_.render(s, view);
    QVERIFY(meanDiff(moved, reference) > 1.0);
    // Weighted OIT is approximate: it draws them (the image is not the pane's alone).
    s.settings.transparency = scene::Transparency::Weighted;
    const Image weighted = r_.render(s, view);
    removeEmitters(s);
    const Image paneOnly = r_.render(s, view);
    QVERIFY(meanDiff(weighted, paneOnly) > 1.0);
  }

  // Additive particles past the K-buffer's K and the fixed array's 16
  // layers go to the tail, which sums their light apart (light adds in any
  // order): 24 sparks stacked over one spot with K = 4 (and the fixed
  // array's 16 layers) draw what depth peeling draws, within 2/255
  // (measured 1/255, thousands of fragments in the tail, which dropped
  // them before).
  void additiveTailKeepsTheLight() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    s.settings.ambientIntensity = 0.0f;
    const render::RenderView view = camera({0, -4.0, 1.0}, {0, 0, 1.0}, 80, 60, 40.0);
    addEmitters(s, {still("Stack", {0.0, 0.0, 1.0}, {0.08, 0.6, 0.08}, 24, 0.9, {0.03, 0.02, 0.012, 1.0},
                          particles::Sprite::Spark, particles::Blend::Additive, 9)});
    s.settings.kbufferK = 4;
    s.settings.transparency = scene::Transparency::Reference;
    render::FrameStats stats;
    const Image reference = r_.render(s, view, false, &stats);
    QCOMPARE(stats.particlesDrawn, size_t(24));
    removeEmitters(s);
    const Image bare = r_.render(s, view);
    QVERIFY2(maxDiff(reference, bare) > 60, qPrintable(QString::number(maxDiff(reference, bare))));
    addEmitters(s, {still("Stack", {0.0, 0.0, 1.0}, {0.08, 0.6, 0.08}, 24, 0.9, {0.03, 0.02, 0.012, 1.0},
                          particles::Sprite::Spark, particles::Blend::Additive, 9)});
    for (auto mode : {scene::Transparency::KBuffer, scene::Transparency::ABufferFixed}) {
      const int m = fromPeeling(s, view, mode, reference, "particles_tail", &stats);
      qInfo("mode %d: %llu fragments in the tail, max difference %d from depth peeling", int(mode),
            static_cast<unsigned long long>(stats.oit.overflow), m);
      QVERIFY(stats.oit.overflow > 0);  // the tail was used
      QVERIFY2(m <= 2, qPrintable(QString("mode %1: max difference %2 from depth peeling").arg(int(mode)).arg(m)));
    }
  }

  // RenderOptions::gpuParticles: the emitters the compute pass takes (the
  // fog bank, alpha puffs, additive sparks, sparks with turbulence)
  // evaluated there draw what the CPU's records draw, within 2/255
  // (positions agree to micrometres: test_particle_gpu_eval); an emitter
  // that collides with the ground stays on the CPU in the same frame.
  void gpuEvaluationDrawsTheSame() {
    scene::SceneState s = ground();
    s.time.seconds = 30.0;
    const render::RenderView view = camera({0, -9.0, 1.7}, {0, 0, 1.5});
    particles::PresetOptions o;
    o.at = kUtm;
    o.area = glm::dvec4(kUtm.x - 5, kUtm.y - 5, kUtm.x + 5, kUtm.y + 5);
    o.rate = 3.0;
    std::string error;
    std::vector<particles::EmitterDesc> descs = particles::makePreset("fog", o, error);
    QVERIFY2(!descs.empty(), error.c_str());
    descs.push_back(still("Puffs", {-1.0, 0, 1.2}, {0.8, 0.5, 0.6}, 15, 0.6, {0.3, 0.6, 1.0, 0.7},
                          particles::Sprite::Smoke));
    descs.push_back(still("Sparks", {1.0, 0, 1.0}, {0.5, 0.5, 0.5}, 25, 0.2, {3.0, 1.2, 0.3, 1.0},
                          particles::Sprite::Spark, particles::Blend::Additive));
    particles::EmitterDesc turbulent = descs.back();
    turbulent.name = "Turbulent";
    turbulent.origin += glm::dvec3(0, 0, 0.8);
    turbulent.turbulence = 1.0;
    descs.push_back(turbulent);
    particles::EmitterDesc falling = still("Falling", {0.0, 0.5, 1.5}, {0.6, 0.3, 0.2}, 20, 0.15, {0.9, 0.9, 1.0, 0.9});
    falling.gravity = {0, 0, -9.81};
    falling.collision = particles::CollisionMode::Stick;
    descs.push_back(falling);
    addEmitters(s, descs);
    render::FrameStats cpuStats, gpuStats;
    const Image cpu = r_.render(s, view, false, &cpuStats);
    render::RenderOptions options;
    options.gpuParticles = true;
    const Image gpu = r_.render(s, view, false, &gpuStats, options);
    QVERIFY(!passRan(cpuStats, "particles_evaluate"));
    QVERIFY(passRan(gpuStats, "particles_evaluate"));
    QVERIFY(meanDiff(cpu, r_.render(ground(), view)) > 0.3);  // the particles are there
    const int m = maxDiff(gpu, cpu);
    if (m > 2) {
      keep("particles_gpu_cpu", cpu);
      keep("particles_gpu_gpu", gpu);
    }
    QVERIFY2(m <= 2, qPrintable(QString("max difference %1").arg(m)));
  }

  // Frame t = 2 rendered alone equals the same frame after t = 1.0 .. 1.95
  // (the replay cache carried across frames), byte for byte: embers with
  // turbulence, killed by the ground.
  void frameAloneEqualsFrameInARun() {
    scene::SceneState s = ground();
    const render::RenderView view = camera({0, -3.0, 1.2}, {0, 0, 0.8});
    particles::PresetOptions o;
    o.at = kUtm;
    std::string error;
    std::vector<particles::EmitterDesc> descs = particles::makePreset("campfire", o, error);
    QVERIFY2(!descs.empty(), error.c_str());
    bool replays = false;
    for (const particles::EmitterDesc& d : descs) replays = replays || d.needsReplay();
    QVERIFY(replays);
    addEmitters(s, descs);
    for (int k = 0; k < 20; ++k) {
      s.time.seconds = 1.0 + 0.05 * k;
      r_.render(s, view);
    }
    s.time.seconds = 2.0;
    const Image inRun = r_.render(s, view);
    // A frame without the emitters drops their caches; then t = 2 cold.
    removeEmitters(s);
    r_.render(s, view);
    addEmitters(s, descs);
    const Image alone = r_.render(s, view);
    QCOMPARE(alone.rgba8.size(), inRun.rgba8.size());
    QCOMPARE(maxDiff(alone, inRun), 0);
  }

  // No emitter: no particle pass, buffer or texture; one in view: its
  // upload pass and buffer; one behind the camera: nothing uploaded or
  // drawn (and no transparency pass: nothing else is translucent). Stereo:
  // both eyes draw the one buffer.
  void costsNothingWithoutParticlesInView() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    const render::RenderView view = camera({0, -6.0, 1.5}, {0, 0, 1.0});
    render::FrameStats stats;
    r_.render(s, view, false, &stats);
    QVERIFY(!passRan(stats, "particles"));
    QCOMPARE(particleAllocations(r_.renderer()), size_t(0));
    QCOMPARE(stats.particlesDrawn, size_t(0));

    addEmitters(s, {still("Ahead", {0, 0, 1.0}, {0.5, 0.5, 0.5}, 30, 0.3, {1, 1, 1, 0.8})});
    r_.render(s, view, false, &stats);
    QVERIFY(passRan(stats, "particles_upload"));
    QVERIFY(passRan(stats, "oit_"));
    QVERIFY(particleAllocations(r_.renderer()) > 0);
    QCOMPARE(stats.particlesDrawn, size_t(30));
    QCOMPARE(stats.emittersOutOfView, size_t(0));

    // The same emitter behind the camera: skipped by its bound (particles/
    // bounds.h) before any evaluation.
    const render::RenderView away = camera({0, -6.0, 1.5}, {0, -12.0, 1.5});
    const size_t drawCallsBefore = stats.drawCalls;
    r_.render(s, away, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));
    QVERIFY(!passRan(stats, "particles"));
    QVERIFY(!passRan(stats, "oit_"));
    QCOMPARE(particleAllocations(r_.renderer()), size_t(0));
    QVERIFY(stats.drawCalls < drawCallsBefore);

    // A stereo pair: one evaluation, one buffer of the particles either eye sees.
    render::RenderView left = view, right = view;
    left.eye -= view.orientation * glm::dvec3(0.03, 0, 0);
    right.eye += view.orientation * glm::dvec3(0.03, 0, 0);
    const render::FrameStats pair = r_.renderViewsOnly(s, {left, right});
    QCOMPARE(pair.particlesDrawn, size_t(30));

    // Beside the view, with particles moving towards it: the bound holds
    // the whole flight, so the emitter is evaluated (and its particles that
    // reached the view drawn) rather than skipped. Box shape at 12 m to the
    // side; speed 3 m/s towards the view's axis for 10 s reaches it.
    particles::EmitterDesc side = still("Side", {12.0, 0, 1.0}, {0.2, 0.2, 0.2}, 40, 0.3, {1, 1, 1, 0.8});
    side.direction = {-1, 0, 0};
    side.speedMin = side.speedMax = 3.0;
    side.lifetimeMin = side.lifetimeMax = 10.0;
    removeEmitters(s);
    addEmitters(s, {side});
    s.time.seconds = 4.0;  // 12 m travelled: at the view's axis
    r_.render(s, view, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(0));
    QCOMPARE(stats.particlesDrawn, size_t(40));
    // From 200 m off, looking away, the bound (the box plus 30 m of travel)
    // is in no view: skipped.
    const render::RenderView farAway = camera({0, -200.0, 1.5}, {0, -400.0, 1.5});
    r_.render(s, farAway, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));
  }

  // A world-space emitter on a moving entity and one with spawn values
  // keyed on the timeline have bounds too (scene::placedBound): while the
  // particles a moving emitter left behind are still in view it is drawn
  // although the emitter itself has flown out of it; once the whole live
  // window was born out of view it is skipped; a keyed emitter behind the
  // camera is skipped, in front of it drawn.
  void movingAndKeyedEmittersHaveBoundsToo() {
    scene::SceneState s = ground();
    particles::EmitterDesc trail = still("Trail", {0, 0, 1.0}, {0, 0, 0}, 0, 0.3, {1, 1, 1, 0.8});
    trail.bursts.clear();
    trail.rate = 20.0;
    trail.lifetimeMin = trail.lifetimeMax = 10.0;
    trail.space = particles::Space::World;
    addEmitters(s, {trail});
    sequencer::Binding flies;
    flies.entity = kFirstEmitter;
    sequencer::VectorTrack move;
    move.property = "transform.translation";
    sequencer::VectorKey k0, k1;
    k0.time = 0.0, k0.interpolation = sequencer::Interpolation::Linear;
    k1.time = 4.0, k1.value = {300.0, 0.0, 0.0};
    move.keys = {k0, k1};
    flies.tracks.push_back(move);
    s.sequence.bindings.push_back(flies);
    const render::RenderView view = camera({0, -6.0, 1.5}, {0, 0, 1.0});
    auto at = [&](double t) { return scene::animatedState(s, scene::compileSequence(s), t); };
    render::FrameStats stats;
    r_.render(at(3.0), view, false, &stats);  // the emitter 225 m to the side, its first particles ahead
    QCOMPARE(stats.emittersOutOfView, size_t(0));
    QVERIFY(stats.particlesDrawn > 0 && stats.particlesDrawn < 60);
    r_.render(at(20.0), view, false, &stats);  // everything alive was born at 300 m
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));

    s = ground();
    addEmitters(s, {still("Keyed", {0, 0, 1.0}, {0.5, 0.5, 0.5}, 30, 0.3, {1, 1, 1, 0.8})});
    sequencer::Binding keyed;
    keyed.entity = kFirstEmitter;
    sequencer::ScalarTrack size;
    size.property = "particles.size_m";
    sequencer::ScalarKey a, b;
    a.value = 0.3, b.time = 2.0, b.value = 0.8;
    size.keys = {a, b};
    keyed.tracks.push_back(size);
    s.sequence.bindings.push_back(keyed);
    r_.render(at(1.0), view, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(0));
    QCOMPARE(stats.particlesDrawn, size_t(30));
    r_.render(at(1.0), camera({0, -6.0, 1.5}, {0, -12.0, 1.5}), false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));
  }

  // The axis a mesh particle turns about is a unit vector from its random
  // bits, spread over the sphere (not one axis for every particle): the
  // mean of 4096 axes is within 0.05 of 0 (a uniform mean's standard
  // deviation per component is 1/sqrt(3 x 4096) = 0.009) and each octant
  // holds 1/8 within 0.03.
  void meshParticleAxesCoverTheSphere() {
    glm::dvec3 sum(0.0);
    int octants[8] = {};
    for (uint32_t k = 0; k < 4096; ++k) {
      const uint32_t variant = particles::hashKey(7, 0, k, uint32_t(particles::Attr::Variant));
      const glm::dvec3 a = render::meshParticleAxis(variant);
      QVERIFY(std::abs(glm::length(a) - 1.0) < 1e-12);
      sum += a;
      ++octants[(a.x > 0) + 2 * (a.y > 0) + 4 * (a.z > 0)];
    }
    QVERIFY2(glm::length(sum / 4096.0) < 0.05, qPrintable(QString::number(glm::length(sum / 4096.0))));
    for (int o : octants) QVERIFY2(std::abs(o / 4096.0 - 0.125) < 0.03, qPrintable(QString::number(o)));
  }

  // One mesh particle (a burst of 1, still, fixed size, a turn and a spin)
  // drawn as the hidden rock, against the same scene where a visible rock
  // entity stands at the particle's transform instead: the position, size
  // and rotation from the evaluator, the axis meshParticleAxis(variant),
  // the scale size / largest extent (1 m) and the box's centre on the
  // particle, all computed here from the box's corners. The sun casts
  // shadows on a lit ground, so the particle's shadow is compared too (and
  // a frame without shadows differs: the shadow is in view). Tolerance:
  // the instance stores its rotation as snorm16 and its scale as a half
  // (0.05 %), so a few edge pixels may flip: at most 0.5 % of the channels
  // differ by more than 2/255 and the mean difference is under 0.05/255.
  void meshParticleEqualsMeshEntityAtItsTransform() {
    scene::SceneState s = shadowedGroundWithRock();
    particles::EmitterDesc d = still("Debris", {0.2, 0.3, 1.0}, glm::dvec3(0.0), 1, 0.9, {0, 1, 0, 1});
    d.rotationMinDeg = d.rotationMaxDeg = 35.0;
    d.spinMinDegPerS = d.spinMaxDegPerS = 40.0;
    d.drawMesh = "Rock";
    const render::RenderView view = camera({1.5, -3.5, 2.2}, {0.2, 0.3, 0.6});

    // The particle as the library evaluates it.
    std::string error;
    const auto ev = particles::Evaluator::create(d, {}, error);
    QVERIFY2(ev, error.c_str());
    const particles::Frame f = ev->frame(s.time.seconds);
    QCOMPARE(f.particles.size(), size_t(1));
    const particles::Particle& p = f.particles[0];
    QCOMPARE(p.rotationDeg, 35.0 + 40.0 * 1.5);  // the spin is in it
    const uint32_t variant = particles::packFrame(f, d.origin, d.origin, d.seed)[0].variant;
    const glm::dquat turn = glm::angleAxis(glm::radians(p.rotationDeg), render::meshParticleAxis(variant));
    const double scale = p.size / 1.0;  // the box's longest side: 1.2 - 0.2
    const glm::dvec3 centre = 0.5 * (glm::dvec3(kRockLo) + glm::dvec3(kRockHi));

    addEmitters(s, {d});
    render::FrameStats particleStats;
    const Image particle = r_.render(s, view, false, &particleStats);
    QVERIFY(r_.renderer().particleErrors().empty());
    QCOMPARE(particleStats.particlesDrawn, size_t(1));
    removeEmitters(s);

    scene::Entity rock;
    rock.id = 4;
    rock.name = "Reference rock";
    rock.mesh = scene::MeshInstance{kRockAsset};
    rock.transform.translation = d.origin + p.position - turn * (scale * centre);
    rock.transform.rotation = turn;
    rock.transform.scale = glm::dvec3(scale);
    s.entities.emplace(rock.id, rock);
    s.roots.push_back(rock.id);
    render::FrameStats entityStats;
    const Image entity = r_.render(s, view, false, &entityStats);
    // The same mesh drawn once either way (12 triangles over the ground's 2).
    QCOMPARE(particleStats.trianglesDrawn, entityStats.trianglesDrawn);

    size_t over = 0;
    for (size_t i = 0; i < particle.rgba8.size(); ++i) over += std::abs(int(particle.rgba8[i]) - int(entity.rgba8[i])) > 2;
    const double overShare = double(over) / double(particle.rgba8.size());
    const int maxD = maxDiff(particle, entity);
    const double meanD = meanDiff(particle, entity);
    qInfo("mesh particle against mesh entity: max difference %d/255, mean %.4f/255, %.3f %% of channels over 2/255",
          maxD, meanD, 100.0 * overShare);
    if (overShare > 0.005 || meanD > 0.05) {
      keep("particles_mesh_particle", particle);
      keep("particles_mesh_entity", entity);
    }
    QVERIFY(overShare <= 0.005);
    QVERIFY(meanD < 0.05);
    // The comparison sees something: the rock is there (against the ground
    // alone), and its shadow is (against the same frame without shadows).
    s.entities.erase(rock.id);
    s.roots.erase(std::remove(s.roots.begin(), s.roots.end(), rock.id), s.roots.end());
    // The comparison sees something: the rock (219 pixels, 1.5 % of the
    // image, against the ground alone), its shadow (52 pixels against the
    // same frame without shadows), and its axis (the rock turned about +z
    // instead: 229 pixels apart). Bounds well under those.
    const Image bare = r_.render(s, view);
    const size_t rockPixels = pixelsApart(entity, bare, 8);
    QVERIFY2(rockPixels > 100, qPrintable(QString::number(rockPixels)));
    rock.transform.rotation = glm::angleAxis(glm::radians(p.rotationDeg), glm::dvec3(0, 0, 1));
    rock.transform.translation = d.origin + p.position - rock.transform.rotation * (scale * centre);
    s.entities.emplace(rock.id, rock);
    s.roots.push_back(rock.id);
    const size_t axisPixels = pixelsApart(entity, r_.render(s, view), 8);
    QVERIFY2(axisPixels > 20, qPrintable(QString::number(axisPixels)));
    s.entities.erase(rock.id);
    s.roots.erase(std::remove(s.roots.begin(), s.roots.end(), rock.id), s.roots.end());
    addEmitters(s, {d});
    s.entities[1000].light->castsShadows = false;
    const size_t shadowPixels = pixelsApart(particle, r_.render(s, view), 8);
    QVERIFY2(shadowPixels > 20, qPrintable(QString::number(shadowPixels)));
    qInfo("rock %zu pixels, turned about +z %zu pixels apart, shadow %zu pixels", rockPixels, axisPixels, shadowPixels);
    // Picking a mesh particle names its emitter's entity: every 8th pixel
    // the rock or its shadow changes is the emitter or the ground, and
    // some are the emitter.
    const scene::EntityId emitter = kFirstEmitter;
    QVERIFY(s.entities.count(emitter) && s.entities[emitter].particles);
    size_t onRock = 0, seen = 0;
    for (int y = 0; y < view.height; ++y)
      for (int x = 0; x < view.width; ++x) {
        const size_t i = (size_t(y) * view.width + x) * 4;
        int m = 0;
        for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(entity.rgba8[i + c]) - int(bare.rgba8[i + c])));
        if (m <= 8 || seen++ % 8) continue;
        const scene::EntityId hit = r_.renderer().pick(s, view, x, y);
        QVERIFY2(hit == emitter || hit == 1, qPrintable(QString("pixel %1,%2 picks %3").arg(x).arg(y).arg(hit)));
        onRock += hit == emitter;
      }
    QVERIFY2(onRock >= 5, qPrintable(QString::number(onRock)));
  }

  // Mesh particles cast shadows: an emitter out of every view is evaluated
  // only when its shadow can reach one (its bound swept along the sun's
  // light). High above the ground on the sun's ray through the view's
  // middle: out of view, its shadow in it: evaluated, and the shadow shows;
  // without shadows, or moved aside so its shadow misses the view too,
  // nothing is evaluated (emittersOutOfView, no particle handed over).
  void meshParticlesOutOfViewOnlyWhereTheirShadowReaches() {
    scene::SceneState s = shadowedGroundWithRock();
    // Looking steeply down: nothing higher than the camera is in view.
    const render::RenderView view = camera({0.0, -3.0, 8.0}, {0.0, 0.0, 0.0});
    const glm::dvec3 toSun = -(s.entities[1000].transform.rotation * glm::dvec3(0, 0, -1));
    QVERIFY(toSun.z > 0.1);
    // 25 m up the sun's ray from the ground the camera looks at.
    const glm::dvec3 high = toSun * (25.0 / toSun.z);
    particles::EmitterDesc d = still("Debris", high, glm::dvec3(0.5), 6, 1.5, {0, 1, 0, 1});
    d.drawMesh = "Rock";
    render::FrameStats stats;
    const Image bare = r_.render(s, view, false, &stats);
    const size_t groundInstances = stats.instancesDrawn;
    addEmitters(s, {d});
    const Image shadowed = r_.render(s, view, false, &stats);
    QVERIFY(r_.renderer().particleErrors().empty());
    QCOMPARE(stats.emittersOutOfView, size_t(0));
    QCOMPARE(stats.particlesDrawn, size_t(6));
    QCOMPARE(stats.instancesDrawn, groundInstances);  // no rock in view: only their shadows
    const size_t shade = pixelsApart(shadowed, bare, 8);
    qInfo("rocks %.0f m up the sun's ray: out of view, their shadow on %zu pixels", glm::length(high), shade);
    QVERIFY2(shade > 20, qPrintable(QString::number(shade)));
    // Without shadows: nothing it does can be seen.
    s.settings.shadows = false;
    r_.render(s, view, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));
    // With shadows, moved 200 m aside: its shadow misses the view too.
    s.settings.shadows = true;
    removeEmitters(s);
    d.origin += glm::dvec3(200.0, 0.0, 0.0);
    addEmitters(s, {d});
    r_.render(s, view, false, &stats);
    QCOMPARE(stats.emittersOutOfView, size_t(1));
    QCOMPARE(stats.particlesDrawn, size_t(0));
  }

  // A draw_mesh naming no mesh entity (an empty entity of that name, or
  // nothing at all): the frame renders, the error names the
  // emitter and the field, and the other emitters (sprites and meshes)
  // draw exactly what they draw without it.
  void missingDrawMeshIsReportedAndLosesNothingElse() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    addHiddenRock(s, 3);
    scene::Entity empty;  // a name without a mesh
    empty.id = 5;
    empty.name = "Marker";
    s.entities.emplace(empty.id, empty);
    s.roots.push_back(empty.id);
    const render::RenderView view = camera({0, -6.0, 1.5}, {0, 0, 1.0});
    particles::EmitterDesc rocks = still("Rocks", {-0.8, 0, 1.0}, {0.4, 0.4, 0.4}, 4, 0.4, {1, 1, 1, 1});
    rocks.drawMesh = "Rock";
    particles::EmitterDesc sparks = still("Sparks", {0.8, 0, 1.0}, {0.4, 0.4, 0.4}, 6, 0.3, {1, 1, 1, 0.8});
    particles::EmitterDesc marker = rocks;
    marker.name = "Debris";
    marker.drawMesh = "Marker";
    particles::EmitterDesc nowhere = rocks;
    nowhere.name = "Gravel";
    nowhere.drawMesh = "Nowhere";

    addEmitters(s, {rocks, sparks});
    render::FrameStats goodStats;
    const Image good = r_.render(s, view, false, &goodStats);
    QVERIFY(r_.renderer().particleErrors().empty());
    QCOMPARE(goodStats.particlesDrawn, size_t(10));
    QVERIFY(meanDiff(good, r_.render(ground(), view)) > 0.3);
    removeEmitters(s);

    addEmitters(s, {marker, rocks, nowhere, sparks});
    render::FrameStats stats;
    const Image img = r_.render(s, view, false, &stats);
    const std::vector<std::string> errors = r_.renderer().particleErrors();
    QCOMPARE(errors.size(), size_t(2));
    QCOMPARE(errors[0], std::string("emitter 'Debris', field 'draw_mesh': no entity 'Marker' with a mesh"));
    QCOMPARE(errors[1], std::string("emitter 'Gravel', field 'draw_mesh': no entity 'Nowhere' with a mesh"));
    QCOMPARE(stats.particlesDrawn, size_t(10));
    QCOMPARE(maxDiff(img, good), 0);
  }

  // particlesDrawn counts mesh particles (handed to the instanced source)
  // with the sprites; their triangles count as an instanced source's; the
  // GPU evaluation setting leaves mesh emitters on the CPU (same image);
  // a scene without mesh particles has no mesh particle pass or buffer.
  void particlesDrawnCountsMeshParticles() {
    scene::SceneState s = ground();
    s.time.seconds = 1.0;
    addHiddenRock(s, 3);
    const render::RenderView view = camera({0, -6.0, 1.5}, {0, 0, 1.0});
    render::FrameStats stats;
    r_.render(s, view, false, &stats);
    const size_t groundTriangles = stats.trianglesDrawn;
    particles::EmitterDesc rocks = still("Rocks", {-0.8, 0, 1.0}, {0.4, 0.4, 0.4}, 5, 0.4, {1, 1, 1, 1});
    rocks.drawMesh = "Rock";
    addEmitters(s, {rocks});
    const Image cpu = r_.render(s, view, false, &stats);
    QCOMPARE(stats.particlesDrawn, size_t(5));
    QCOMPARE(stats.trianglesDrawn, groundTriangles + 5 * 12);
    QVERIFY(passRan(stats, "particle_meshes"));
    QVERIFY(!passRan(stats, "particles_upload"));  // no sprite
    render::RenderOptions gpu;
    gpu.gpuParticles = true;
    QCOMPARE(maxDiff(r_.render(s, view, false, &stats, gpu), cpu), 0);
    QVERIFY(!passRan(stats, "particles_evaluate"));
    QCOMPARE(stats.particlesDrawn, size_t(5));

    addEmitters(s, {still("Sparks", {0.8, 0, 1.0}, {0.4, 0.4, 0.4}, 7, 0.3, {1, 1, 1, 0.8})});
    r_.render(s, view, false, &stats);
    QCOMPARE(stats.particlesDrawn, size_t(12));

    // Without them: no pass of theirs, and their buffers go back.
    removeEmitters(s);
    for (int k = 0; k < 8; ++k) r_.render(s, view, false, &stats);
    QVERIFY(!passRan(stats, "particle_meshes"));
    const std::string held = test::allocationNamed(r_.renderer(), "particle_meshes");
    QVERIFY2(held.empty(), held.c_str());
  }
};

QTEST_MAIN(TestParticleRender)
#include "test_particle_render.moc"
