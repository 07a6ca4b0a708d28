// Draw sources (render/draw_source.h, render/instanced_source.h) on a
// headless EGL context. A grid of instances of a 2k-triangle sphere, in two
// cells at UTM coordinates, is drawn three ways in the same scene: by the
// GPU-driven instanced source (a compute pass culls every view and writes
// indirect commands), by the same source culled on the CPU (instanced draws
// from CPU lists), and as ordinary document mesh entities at the same
// places (the mesh source: an independent path, other vertex maths). The
// GPU and CPU images must agree within rounding, and both must agree with
// the entities' image, in the lit opaque pass with the sun's shadow (the
// spheres shadow the ground), through the A-buffer and the K-buffer with a
// translucent material; picking at each instance's centre returns its id.
#include <QtTest>

#include <cmath>

#include "look_from.h"
#include "mesh/primitives.h"
#include "render/instanced_source.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/scene_state.h"
#include "scene_parts.h"

using namespace hs;
using render::InstancedSource;

namespace {

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);  // the scene's corner, Meteora-like
constexpr scene::AssetId kSphere = 7;
constexpr scene::EntityId kSourceEntity = 900;
constexpr int kGrid = 6;

struct Placed {
  glm::dvec3 world;
  glm::dquat rotation;
  double scale;
  uint32_t id;
};

// The scene without the instances: a ground, a sun, the sphere asset.
scene::SceneState baseScene(float opacity) {
  scene::SceneState s;
  s.settings.showGrid = false;
  s.settings.tonemap = scene::Tonemap::None;
  s.settings.antialiasing = scene::Antialiasing::None;
  s.settings.ambientIntensity = 0.3f;
  s.settings.shadows = true;
  test::addMeshAsset(s, 1, "Ground", mesh::gridPlane(40.0f, 4), {0.6f, 0.6f, 0.55f});
  test::addMeshAsset(s, kSphere, "Sphere", mesh::uvSphere(0.6f, 32, 32), {0.8f, 0.25f, 0.2f}, opacity);
  scene::Entity ground;
  ground.id = 1;
  ground.name = "Ground";
  ground.mesh = scene::MeshInstance{1};
  ground.transform.translation = kUtm + glm::dvec3(5.0, 5.0, 0.0);
  s.entities.emplace(ground.id, ground);
  s.roots.push_back(ground.id);
  test::addSun(s, 1000, {50, 0, -35}, true);
  return s;
}

// The grid: 6 x 6 spheres 2 m apart, turned and scaled, the first three
// rows in one cell, the rest in another.
std::vector<Placed> grid() {
  std::vector<Placed> out;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const int k = y * kGrid + x;
      Placed p;
      p.world = kUtm + glm::dvec3(2.0 * x, 2.0 * y, 0.7 + 0.05 * (k % 3));
      p.rotation = glm::angleAxis(0.37 * k, glm::normalize(glm::dvec3(0.2, 0.3, 1.0)));
      p.scale = 0.8 + 0.1 * (k % 5);
      p.id = uint32_t(1000 + 7 * k);  // stable ids, not indices
      out.push_back(p);
    }
  return out;
}

render::InstanceSet instanceSet(const std::vector<Placed>& placed) {
  render::InstanceSet set;
  set.types = {kSphere};
  set.cells = {kUtm, kUtm + glm::dvec3(0.0, 6.0, 0.0)};
  set.entity = kSourceEntity;
  for (const Placed& p : placed) {
    const uint16_t cell = p.world.y - kUtm.y >= 6.0 ? 1 : 0;
    set.instances.push_back(render::packInstance(glm::vec3(p.world - set.cells[cell]), glm::quat(p.rotation),
                                                 float(p.scale), 0, cell, p.id));
  }
  return set;
}

// The same instances as document entities, with the rotation the packed
// instance stores (snorm16), so both paths place the same spheres.
void addEntities(scene::SceneState& s, const std::vector<Placed>& placed, const render::InstanceSet& set) {
  for (size_t i = 0; i < placed.size(); ++i) {
    scene::Entity e;
    e.id = 2000 + i;
    e.name = "Sphere " + std::to_string(i);
    e.mesh = scene::MeshInstance{kSphere};
    e.transform.translation = placed[i].world;
    e.transform.rotation = glm::dquat(render::instanceRotation(set.instances[i]));
    e.transform.scale = glm::dvec3(placed[i].scale);
    s.entities.emplace(e.id, e);
    s.roots.push_back(e.id);
  }
}

render::RenderView camera() {
  render::RenderView v;
  v.width = 160;
  v.height = 120;
  v.fovY = glm::radians(50.0);
  v.eye = kUtm + glm::dvec3(5.0, -9.0, 9.0);
  v.orientation = test::lookFrom(v.eye, kUtm + glm::dvec3(5.0, 5.0, 0.0)).rotation;
  return v;
}

struct Difference {
  double max = 0.0;
  double share = 0.0;  // of pixels with a channel off by more than the tolerance
};

Difference compare(const Image& a, const Image& b, double tolerance) {
  Difference d;
  size_t off = 0;
  const size_t pixels = a.rgbaF.size() / 4;
  for (size_t p = 0; p < pixels; ++p) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(a.rgbaF[p * 4 + c]) - double(b.rgbaF[p * 4 + c])));
    d.max = std::max(d.max, worst);
    if (worst > tolerance) ++off;
  }
  d.share = pixels ? double(off) / double(pixels) : 1.0;
  return d;
}

}  // namespace

class TestDrawSources : public QObject {
  Q_OBJECT
  render::OffscreenRenderer r_;

  Image renderWith(const scene::SceneState& s, std::shared_ptr<InstancedSource> source,
                   render::FrameStats* stats = nullptr) {
    if (source) r_.renderer().setDrawSources({source});
    else r_.renderer().setDrawSources({});
    Image img = r_.render(s, camera(), true, stats);
    r_.renderer().setDrawSources({});
    return img;
  }

  // GPU against CPU (the same shaders: equal but for the order of
  // instances), and both against the entities (the mesh path).
  void checkThreeWays(scene::Transparency mode, float opacity) {
    const std::vector<Placed> placed = grid();
    const render::InstanceSet set = instanceSet(placed);
    scene::SceneState s = baseScene(opacity);
    s.settings.transparency = mode;
    auto gpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    auto cpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Cpu);
    gpu->setInstances(set);
    cpu->setInstances(set);
    render::FrameStats gs, cs;
    const Image a = renderWith(s, gpu, &gs);
    const Image b = renderWith(s, cpu, &cs);
    const Image none = renderWith(s, nullptr);
    // Against the entities: a translucent surface casts a hashed share of
    // its texels (shadow_depth.frag), chosen by the depth's bits, which
    // the two vertex paths round differently; so that comparison is made
    // without shadows (the instanced shadows are checked above, GPU against
    // CPU, and in instancesCastTheSunsShadow).
    scene::SceneState reference = s;
    if (opacity < 1.0f) reference.settings.shadows = false;
    const Image instanced = opacity < 1.0f ? renderWith(reference, gpu) : a;
    addEntities(reference, placed, set);
    const Image c = renderWith(reference, nullptr);
    QVERIFY(!a.rgbaF.empty() && a.rgbaF.size() == b.rgbaF.size() && a.rgbaF.size() == c.rgbaF.size());
    const Difference gpuCpu = compare(a, b, 1e-5);
    qInfo("GPU vs CPU culling: max %.3g, %.4f%% of pixels off", gpuCpu.max, 100.0 * gpuCpu.share);
    QVERIFY2(gpuCpu.max <= 1e-4, qPrintable(QString::number(gpuCpu.max)));
    const Difference vsMeshes = compare(instanced, c, 2e-3);
    qInfo("instanced vs mesh entities: max %.3g, %.4f%% of pixels off by more than 2e-3", vsMeshes.max,
          100.0 * vsMeshes.share);
    // Other vertex maths (a quaternion in the shader, a matrix formed in
    // double on the CPU): a few silhouette pixels may round the other way.
    QVERIFY2(vsMeshes.share < 0.005, qPrintable(QString::number(vsMeshes.share)));
    // The spheres and their shadows are really there: much of the image changed.
    const Difference vsNone = compare(a, none, 2e-3);
    QVERIFY2(vsNone.share > 0.05, qPrintable(QString::number(vsNone.share)));
    // Every instance is in view: each path counted them.
    QCOMPARE(cpu->lastVisible(), int64_t(placed.size()));
    QVERIFY(gs.drawCalls > 0 && cs.drawCalls > 0);
    // The GPU path culled in its compute pass, the CPU path had none; the
    // transparency passes drew the translucent spheres.
    auto ran = [](const render::FrameStats& st, const std::string& name) {
      for (const render::PassStats& p : st.passes)
        if (p.name == name) return true;
      return false;
    };
    QVERIFY(ran(gs, "spheres_cull") && !ran(cs, "spheres_cull"));
    if (opacity < 1.0f) {
      const std::string drawn = mode == scene::Transparency::KBuffer ? "oit_kbuffer_color" : "oit_capture";
      QVERIFY2(ran(gs, drawn) && ran(cs, drawn), drawn.c_str());
    }
  }

 private slots:
  void initTestCase() {
    std::string error;
    QVERIFY2(r_.initialize(error), error.c_str());
  }

  void packedInstanceIs32BytesAndKeepsItsRotation() {
    QCOMPARE(sizeof(render::GpuInstance), size_t(32));
    const glm::quat q = glm::normalize(glm::quat(0.3f, -0.5f, 0.7f, 0.2f));
    const render::GpuInstance g = render::packInstance({1, 2, 3}, q, 1.5f, 3, 9, 42);
    const glm::quat back = render::instanceRotation(g);
    QVERIFY(std::abs(std::abs(glm::dot(back, q)) - 1.0f) < 1e-8f + 2e-5f);
    QCOMPARE(g.typeAndCell & 0xFFFFu, 3u);
    QCOMPARE(g.typeAndCell >> 16, 9u);
    QCOMPARE(g.id, 42u);
  }

  void opaqueWithSunShadowMatchesCpuListAndMeshes() { checkThreeWays(scene::Transparency::ABuffer, 1.0f); }
  void abufferMatchesCpuListAndMeshes() { checkThreeWays(scene::Transparency::ABuffer, 0.5f); }
  void kbufferMatchesCpuListAndMeshes() { checkThreeWays(scene::Transparency::KBuffer, 0.5f); }

  // The sun's shadow of the instances alone: the ground where the spheres
  // shadow it is darker with the instanced source than without it, by as
  // much as the entities darken it.
  void instancesCastTheSunsShadow() {
    const std::vector<Placed> placed = grid();
    const render::InstanceSet set = instanceSet(placed);
    scene::SceneState s = baseScene(1.0f);
    auto gpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    gpu->setInstances(set);
    // Shadows on against off: only the shadow differs.
    const Image lit = renderWith(s, gpu);
    scene::SceneState noShadow = s;
    noShadow.settings.shadows = false;
    const Image unshadowed = renderWith(noShadow, gpu);
    size_t darker = 0;
    for (size_t p = 0; p < lit.rgbaF.size() / 4; ++p)
      if (lit.rgbaF[p * 4 + 1] < unshadowed.rgbaF[p * 4 + 1] - 0.02f) ++darker;
    qInfo("pixels in the instances' shadow: %zu", darker);
    QVERIFY(darker > 200);
  }

  // Instances naming a type or a cell the set does not have are drawn by
  // neither path (and read no buffer past its end): the image is the
  // valid instances' alone.
  void unknownTypesAndCellsAreNotDrawn() {
    const std::vector<Placed> placed = grid();
    const render::InstanceSet valid = instanceSet(placed);
    render::InstanceSet bad = valid;
    bad.instances.push_back(render::packInstance({1, 1, 1}, glm::quat(1, 0, 0, 0), 1.0f, 5, 0, 1));
    bad.instances.push_back(render::packInstance({1, 1, 1}, glm::quat(1, 0, 0, 0), 1.0f, 0, 99, 2));
    const scene::SceneState s = baseScene(1.0f);
    for (auto culling : {InstancedSource::Culling::Gpu, InstancedSource::Culling::Cpu}) {
      auto good = std::make_shared<InstancedSource>("spheres", culling);
      auto withBad = std::make_shared<InstancedSource>("spheres", culling);
      good->setInstances(valid);
      withBad->setInstances(bad);
      const Image a = renderWith(s, good), b = renderWith(s, withBad);
      QCOMPARE(compare(a, b, 0.0).max, 0.0);
    }
  }

  void pickingReturnsEachInstancesId() {
    const std::vector<Placed> placed = grid();
    const render::InstanceSet set = instanceSet(placed);
    scene::SceneState s = baseScene(1.0f);
    for (auto culling : {InstancedSource::Culling::Gpu, InstancedSource::Culling::Cpu}) {
      auto source = std::make_shared<InstancedSource>("spheres", culling);
      source->setInstances(set);
      r_.renderer().setDrawSources({source});
      const render::RenderView v = camera();
      r_.makeCurrent();
      int found = 0;
      for (const Placed& p : placed) {
        // The sphere's top, projected (it faces the camera above it).
        const glm::dvec3 top = p.world + glm::dvec3(0.0, 0.0, 0.3 * p.scale);
        const glm::dvec4 clip = v.projection() * glm::dmat4(v.viewRotation()) * glm::dvec4(top - v.eye, 1.0);
        const int x = int(std::floor((clip.x / clip.w * 0.5 + 0.5) * v.width));
        const int y = int(std::floor((0.5 - clip.y / clip.w * 0.5) * v.height));
        const render::PickHit hit = r_.renderer().pickSurface(s, v, x, y);
        QCOMPARE(hit.entity, kSourceEntity);
        QCOMPARE(hit.instance, p.id);
        ++found;
      }
      QCOMPARE(found, int(placed.size()));
      // The ground is not an instance.
      const render::PickHit ground = r_.renderer().pickSurface(s, v, 2, v.height - 3);
      QCOMPARE(ground.entity, scene::EntityId(1));
      QCOMPARE(ground.instance, UINT32_MAX);
      r_.renderer().setDrawSources({});
    }
  }
};

QTEST_GUILESS_MAIN(TestDrawSources)
#include "test_draw_sources.moc"
