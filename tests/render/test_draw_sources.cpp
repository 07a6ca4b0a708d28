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
//
// Levels of detail, cull distance and fade, per-axis scale, wind and
// shadowless types (instanced_source.h): the same grid with a sphere whose
// LOD chain has two coarser spheres, its errors set so that the grid spans
// all three levels, drawn by the GPU and by the CPU path (equal images and
// equal counts per level, with some instances beyond the cull distance and
// some fading), and against mesh entities with the same chain (the mesh
// source chooses each entity's level by chooseMeshLod: the images agree);
// instances beyond the cull distance leave the image exactly as without
// them; a fading instance drops its fade's share of its pixels, the same
// pixels every render; instances scaled across and along apart match
// entities with that Transform::scale; wind is a pure function of the
// time, none at response 0, and moves no vertex further than the cull
// sphere's margin; a type that casts no shadow leaves the ground lit.
#include <QtTest>

#include <algorithm>
#include <cmath>

#include "view_from.h"
#include "mesh/primitives.h"
#include "render/instanced_source.h"
#include "render/mesh_lod.h"
#include "render/offscreen_renderer.h"
#include "render/renderer.h"
#include "scene/scene_state.h"
#include "scene_parts.h"

using namespace hs;
using render::InstancedSource;

namespace {

const glm::dvec3 kUtm(500000.0, 4400000.0, 300.0);  // the scene's corner, Meteora-like
constexpr scene::AssetId kSphere = 7;
constexpr scene::AssetId kLodSphere = 8;  // kSphere's mesh with a chain of two coarser spheres
constexpr float kSphereRadius = 0.6f;
constexpr scene::EntityId kSourceEntity = 900;
constexpr int kGrid = 6;

struct Placed {
  glm::dvec3 world;
  glm::dquat rotation;
  double scale;
  uint32_t id;
  double scaleZ = 0.0;  // along the height; 0: `scale` (uniform)
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
  test::addMeshAsset(s, kSphere, "Sphere", mesh::uvSphere(kSphereRadius, 32, 32), {0.8f, 0.25f, 0.2f}, opacity);
  test::addMeshEntity(s, 1, "Ground", 1, kUtm + glm::dvec3(5.0, 5.0, 0.0));
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

// The grid with a third of it stretched along the height (x 1.5) and a
// third squashed (x 0.6): per-axis scale.
std::vector<Placed> gridXyZ() {
  std::vector<Placed> out = grid();
  for (size_t k = 0; k < out.size(); ++k)
    if (k % 3) out[k].scaleZ = out[k].scale * (k % 3 == 1 ? 1.5 : 0.6);
  return out;
}

render::InstanceSet instanceSet(const std::vector<Placed>& placed, render::InstanceType type = {kSphere}) {
  render::InstanceSet set;
  set.types = {type};
  set.cells = {kUtm, kUtm + glm::dvec3(0.0, 6.0, 0.0)};
  set.entity = kSourceEntity;
  for (const Placed& p : placed) {
    const uint16_t cell = p.world.y - kUtm.y >= 6.0 ? 1 : 0;
    const glm::vec3 at(p.world - set.cells[cell]);
    set.instances.push_back(p.scaleZ > 0.0 ? render::packInstance(at, glm::quat(p.rotation),
                                                                  glm::vec2(float(p.scale), float(p.scaleZ)), 0, cell, p.id)
                                           : render::packInstance(at, glm::quat(p.rotation), float(p.scale), 0, cell, p.id));
  }
  return set;
}

// kLodSphere: kSphere's mesh with levels 1 and 2 (spheres of 12 and 6
// segments, plainly coarser) whose errors are `errors` (metres).
void addLodSphere(scene::SceneState& s, const std::vector<double>& errors) {
  test::addMeshAsset(s, kLodSphere, "LOD sphere", mesh::uvSphere(kSphereRadius, 32, 32), {0.8f, 0.25f, 0.2f});
  scene::MeshAsset& a = s.assets.at(kLodSphere);
  for (int k = 0; k < 2; ++k) {
    mesh::MeshData m = mesh::uvSphere(kSphereRadius, k == 0 ? 12 : 6, k == 0 ? 8 : 4);
    scene::MeshLod lod;
    lod.contentHash = mesh::contentHash(m);
    lod.triangles = m.triangleCount();
    lod.hausdorff = errors[size_t(k)];
    lod.data = std::make_shared<const mesh::MeshData>(std::move(m));
    a.lods.push_back(std::move(lod));
  }
}

// The same instances as document entities (of `asset`), with the rotation
// and scale the packed instance stores (snorm16, halves), so both paths
// place the same spheres.
void addEntities(scene::SceneState& s, const std::vector<Placed>& placed, const render::InstanceSet& set,
                 scene::AssetId asset = kSphere) {
  for (size_t i = 0; i < placed.size(); ++i) {
    scene::Entity e;
    e.id = 2000 + i;
    e.name = "Sphere " + std::to_string(i);
    e.mesh = scene::MeshInstance{asset};
    e.transform.translation = placed[i].world;
    e.transform.rotation = glm::dquat(render::instanceRotation(set.instances[i]));
    e.transform.scale = glm::dvec3(render::instanceScale(set.instances[i]));
    s.entities.emplace(e.id, e);
    s.roots.push_back(e.id);
  }
}

render::RenderView camera() {
  return test::viewFrom(kUtm + glm::dvec3(5.0, -9.0, 9.0), kUtm + glm::dvec3(5.0, 5.0, 0.0), 160, 120, 50.0);
}

// Where a (stored) instance is for the choices the source makes: its
// origin and the centre of its bounding sphere (world, double), and its
// largest scale.
struct InstancePlace {
  glm::dvec3 origin, centre;
  double largestScale = 1.0;
};

InstancePlace placeOf(const render::InstanceSet& set, size_t i) {
  const render::GpuInstance& g = set.instances[i];
  const mesh::Bounds b = mesh::uvSphere(kSphereRadius, 32, 32).bounds();
  const glm::dvec3 s(render::instanceScale(g));
  InstancePlace p;
  p.origin = set.cells[g.typeAndCell >> 16] + glm::dvec3(g.position);
  p.centre = p.origin + glm::mat3_cast(glm::dquat(render::instanceRotation(g))) * (glm::dvec3(b.center()) * s);
  p.largestScale = std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
  return p;
}

double sphereBoundsRadius() { return double(mesh::uvSphere(kSphereRadius, 32, 32).bounds().radius()); }

// A threshold in the widest gap of sorted `values` within an eighth of the
// count either side of the quantile `q`: no value near it, so the GPU's
// float and the CPU's double choices agree there.
double splitNear(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size(), centre = size_t(q * double(n));
  size_t best = 0;
  double widest = -1.0;
  for (size_t k = std::max<size_t>(1, centre - std::min(centre, n / 8)); k <= std::min(n - 1, centre + n / 8); ++k)
    if (values[k] - values[k - 1] > widest) {
      widest = values[k] - values[k - 1];
      best = k;
    }
  return 0.5 * (values[best - 1] + values[best]);
}

// Errors for kLodSphere's levels 1 and 2 that split the grid's instances
// (their distances, as chooseMeshLod measures them from `view`) about a
// third each way, at the default bound of 1 pixel.
std::vector<double> lodErrorsFor(const render::InstanceSet& set, const render::RenderView& view) {
  std::vector<double> unscaled;
  for (size_t i = 0; i < set.instances.size(); ++i) {
    const InstancePlace p = placeOf(set, i);
    unscaled.push_back(std::max(0.0, glm::length(p.centre - view.eye) - sphereBoundsRadius() * p.largestScale) /
                       p.largestScale);
  }
  const double pixelsPerMetreAt1m = double(view.height) / (2.0 * std::tan(0.5 * view.fovY));
  return {splitNear(unscaled, 1.0 / 3.0) / pixelsPerMetreAt1m, splitNear(unscaled, 2.0 / 3.0) / pixelsPerMetreAt1m};
}

// The level chooseMeshLod gives a mesh entity at instance i's place.
int referenceLevel(const render::InstanceSet& set, size_t i, const std::vector<double>& errors,
                   const render::RenderView& view) {
  const InstancePlace p = placeOf(set, i);
  std::vector<double> all{0.0};
  all.insert(all.end(), errors.begin(), errors.end());
  return render::chooseMeshLod(all, p.centre - view.eye, sphereBoundsRadius(), p.largestScale, view, 1.0).level;
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
                   render::FrameStats* stats = nullptr, const render::RenderView& view = camera()) {
    if (source) r_.renderer().setDrawSources({source});
    else r_.renderer().setDrawSources({});
    Image img = r_.render(s, view, true, stats);
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

  // The GPU's choices against the CPU's (chooseMeshLod itself, in double):
  // a chain of three levels spanning the grid (a third of a non-uniformly
  // scaled grid at each), a cull distance that drops the farthest fifth and
  // a fade band holding several instances, with the sun's shadow. Equal
  // images (the same shaders; the order of instances in a list is the only
  // difference), and equal counts per level, those a mesh entity at each
  // place would draw.
  void gpuMatchesCpuWithLodsCullDistanceAndFade() {
    const std::vector<Placed> placed = gridXyZ();
    const render::RenderView view = camera();
    render::InstanceSet set = instanceSet(placed, {kLodSphere});
    const std::vector<double> errors = lodErrorsFor(set, view);
    std::vector<double> distances;
    for (size_t i = 0; i < set.instances.size(); ++i) distances.push_back(glm::length(placeOf(set, i).origin - view.eye));
    render::InstanceType& type = set.types[0];
    type.cullDistance = float(splitNear(distances, 0.8));
    type.fadeLength = type.cullDistance - float(splitNear(distances, 0.55));
    // What the frame must draw: per level, the instances within the cull distance.
    std::vector<int64_t> expected(3, 0);
    size_t fading = 0, culled = 0;
    for (size_t i = 0; i < set.instances.size(); ++i) {
      // No instance at a boundary: a thousandth either way gives the same answer.
      const int level = referenceLevel(set, i, errors, view);
      QCOMPARE(referenceLevel(set, i, {errors[0] * 1.001, errors[1] * 1.001}, view), level);
      QCOMPARE(referenceLevel(set, i, {errors[0] * 0.999, errors[1] * 0.999}, view), level);
      QVERIFY(std::abs(distances[i] / double(type.cullDistance) - 1.0) > 1e-3);
      if (distances[i] > double(type.cullDistance)) {
        ++culled;
        continue;
      }
      ++expected[size_t(level)];
      if (distances[i] > double(type.cullDistance - type.fadeLength)) ++fading;
    }
    qInfo("levels 0/1/2: %lld/%lld/%lld, %zu fading, %zu beyond the cull distance (%.2f m, fade %.2f m)",
          static_cast<long long>(expected[0]), static_cast<long long>(expected[1]),
          static_cast<long long>(expected[2]), fading, culled, double(type.cullDistance), double(type.fadeLength));
    QVERIFY(expected[0] > 0 && expected[1] > 0 && expected[2] > 0);
    QVERIFY(fading >= 3 && culled >= 3);

    scene::SceneState s = baseScene(1.0f);
    addLodSphere(s, errors);
    auto gpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    auto cpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Cpu);
    gpu->setInstances(set);
    cpu->setInstances(set);
    renderWith(s, gpu);  // the GPU's counts come back a frame later
    const Image a = renderWith(s, gpu), b = renderWith(s, cpu);
    const Difference d = compare(a, b, 1e-5);
    qInfo("GPU vs CPU culling with levels and fade: max %.3g, %.4f%% of pixels off", d.max, 100.0 * d.share);
    QVERIFY2(d.max <= 1e-4, qPrintable(QString::number(d.max)));
    QCOMPARE(cpu->lastVisibleByLevel(), expected);
    QCOMPARE(gpu->lastVisibleByLevel(), expected);
    QCOMPARE(gpu->lastVisible(), cpu->lastVisible());
    // The fade is in both: the image differs from the one without it.
    set.types[0].fadeLength = 0.0f;
    auto sharp = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    sharp->setInstances(set);
    QVERIFY(compare(a, renderWith(s, sharp), 2e-3).share > 0.001);
  }

  // The level each instance draws is the one the mesh source draws for a
  // mesh entity with the same chain at the same place (chooseMeshLod from
  // the LOD view): the images agree as level 0's do, though the coarser
  // levels alone differ plainly from level 0.
  void lodLevelsMatchMeshEntities() {
    const std::vector<Placed> placed = gridXyZ();
    const render::RenderView view = camera();
    const render::InstanceSet set = instanceSet(placed, {kLodSphere});
    const std::vector<double> errors = lodErrorsFor(set, view);
    scene::SceneState s = baseScene(1.0f);
    addLodSphere(s, errors);
    auto gpu = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    gpu->setInstances(set);
    const Image instanced = renderWith(s, gpu);
    scene::SceneState withEntities = s;
    addEntities(withEntities, placed, set, kLodSphere);
    render::FrameStats entityStats;
    const Image entities = renderWith(withEntities, nullptr, &entityStats);
    const Difference d = compare(instanced, entities, 2e-3);
    qInfo("instanced vs mesh entities with a LOD chain: max %.3g, %.4f%% of pixels off by more than 2e-3", d.max,
          100.0 * d.share);
    QVERIFY2(d.share < 0.005, qPrintable(QString::number(d.share)));
    size_t coarser = 0;
    for (size_t i = 0; i < set.instances.size(); ++i) coarser += referenceLevel(set, i, errors, view) > 0;
    QCOMPARE(entityStats.instancesAtCoarserLod, coarser);
    // Level 0 everywhere looks otherwise.
    auto full = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    full->setInstances(instanceSet(placed, {kSphere}));
    const Difference vsFull = compare(instanced, renderWith(s, full), 2e-3);
    qInfo("the chain against level 0 alone: %.3f%% of pixels differ", 100.0 * vsFull.share);
    QVERIFY(vsFull.share > 0.01);
  }

  // Beyond its type's cull distance (from the LOD eye to its origin) an
  // instance is drawn by no view: the image, shadows included, is the one
  // without it, to the bit.
  void instancesBeyondTheCullDistanceAreNotDrawn() {
    const std::vector<Placed> placed = grid();
    const render::RenderView view = camera();
    render::InstanceSet set = instanceSet(placed);
    std::vector<double> distances;
    for (size_t i = 0; i < set.instances.size(); ++i) distances.push_back(glm::length(placeOf(set, i).origin - view.eye));
    set.types[0].cullDistance = float(splitNear(distances, 0.6));
    std::vector<Placed> near;
    for (size_t i = 0; i < placed.size(); ++i)
      if (distances[i] <= double(set.types[0].cullDistance)) near.push_back(placed[i]);
    QVERIFY(near.size() > 5 && near.size() < placed.size() - 5);
    const scene::SceneState s = baseScene(1.0f);
    for (auto culling : {InstancedSource::Culling::Gpu, InstancedSource::Culling::Cpu}) {
      auto culled = std::make_shared<InstancedSource>("spheres", culling);
      auto without = std::make_shared<InstancedSource>("spheres", culling);
      auto all = std::make_shared<InstancedSource>("spheres", culling);
      culled->setInstances(set);
      without->setInstances(instanceSet(near));
      all->setInstances(instanceSet(placed));
      const Image a = renderWith(s, culled);
      QCOMPARE(compare(a, renderWith(s, without), 0.0).max, 0.0);
      QVERIFY(compare(a, renderWith(s, all), 2e-3).share > 0.01);
      if (culling == InstancedSource::Culling::Cpu) QCOMPARE(culled->lastVisible(), int64_t(near.size()));
    }
  }

  // One large instance in its fade band: the share of its pixels dropped
  // is its fade (within the 8x8 dither's rounding at the silhouette), the
  // same pixels in two renders and in both paths; its shadow thins about as
  // much.
  void fadeDropsItsShareOfPixels() {
    render::RenderView view = camera();
    view.width = 320;
    view.height = 240;
    std::vector<Placed> one{{kUtm + glm::dvec3(5.0, 5.0, 1.0), glm::dquat(1, 0, 0, 0), 3.0, 77}};
    render::InstanceSet set = instanceSet(one);
    const double distance = glm::length(placeOf(set, 0).origin - view.eye);
    scene::SceneState s = baseScene(1.0f);
    s.settings.shadows = false;
    scene::SceneState shadowed = baseScene(1.0f);
    const Image none = renderWith(s, nullptr, nullptr, view);
    const Image noneShadowed = renderWith(shadowed, nullptr, nullptr, view);
    auto full = std::make_shared<InstancedSource>("sphere", InstancedSource::Culling::Gpu);
    full->setInstances(set);
    const Image whole = renderWith(s, full, nullptr, view);
    const Image wholeShadowed = renderWith(shadowed, full, nullptr, view);
    auto covered = [&](const Image& img, size_t p) {
      for (int c = 0; c < 3; ++c)
        if (img.rgbaF[p * 4 + c] != none.rgbaF[p * 4 + c]) return true;
      return false;
    };
    // The shadow: the ground's darkening summed over the image.
    auto darkening = [&](const Image& img) {
      double sum = 0.0;
      for (size_t p = 0; p < img.rgbaF.size() / 4; ++p)
        if (!covered(whole, p)) sum += double(std::max(0.0f, noneShadowed.rgbaF[p * 4 + 1] - img.rgbaF[p * 4 + 1]));
      return sum;
    };
    const double fullShadow = darkening(wholeShadowed);
    size_t pixels = 0;
    for (size_t p = 0; p < whole.rgbaF.size() / 4; ++p) pixels += covered(whole, p);
    QVERIFY(pixels > 2000);
    QVERIFY(fullShadow > 1.0);
    for (double fade : {0.25, 0.5, 0.75}) {
      const float fadeLength = 10.0f;
      set.types[0].fadeLength = fadeLength;
      set.types[0].cullDistance = float(distance + (1.0 - fade) * double(fadeLength));
      auto gpu = std::make_shared<InstancedSource>("sphere", InstancedSource::Culling::Gpu);
      auto cpu = std::make_shared<InstancedSource>("sphere", InstancedSource::Culling::Cpu);
      gpu->setInstances(set);
      cpu->setInstances(set);
      const Image a = renderWith(s, gpu, nullptr, view), again = renderWith(s, gpu, nullptr, view);
      QCOMPARE(compare(a, again, 0.0).max, 0.0);
      QCOMPARE(compare(a, renderWith(s, cpu, nullptr, view), 0.0).max, 0.0);
      size_t dropped = 0;
      for (size_t p = 0; p < a.rgbaF.size() / 4; ++p)
        if (covered(whole, p) && !covered(a, p)) ++dropped;
      const double share = double(dropped) / double(pixels);
      const double shadowKept = darkening(renderWith(shadowed, gpu, nullptr, view)) / fullShadow;
      qInfo("fade %.2f: %.4f of %zu pixels dropped; shadow %.3f of the whole one's", fade, share, pixels, shadowKept);
      QVERIFY2(std::abs(share - fade) < 0.03, qPrintable(QString::number(share)));
      QVERIFY2(std::abs(shadowKept - (1.0 - fade)) < 0.15, qPrintable(QString::number(shadowKept)));
      if (fade != 0.5) continue;
      // Picking sees the pixels the image shows: the instance where it is
      // drawn, the ground through its dropped pixels.
      r_.renderer().setDrawSources({gpu});
      r_.makeCurrent();
      int checked = 0;
      for (int y = 0; y < view.height && checked < 48; y += 3)
        for (int x = 0; x < view.width && checked < 48; x += 5) {
          const size_t p = size_t(y) * size_t(view.width) + size_t(x);
          if (!covered(whole, p)) continue;
          const render::PickHit hit = r_.renderer().pickSurface(s, view, x, y);
          QCOMPARE(hit.instance == 77u, covered(a, p));
          ++checked;
        }
      r_.renderer().setDrawSources({});
      QCOMPARE(checked, 48);
    }
  }

  // Scaled across and along the height apart (packHalf2x16): the image of
  // mesh entities with that Transform::scale (normals by the inverse
  // transpose, and the shadows) within the tolerance of the uniform grid.
  void perAxisScaleMatchesMeshEntities() {
    const std::vector<Placed> placed = gridXyZ();
    const render::InstanceSet set = instanceSet(placed);
    const glm::vec3 s0 = render::instanceScale(set.instances[1]);
    QVERIFY(s0.x == s0.y && std::abs(s0.z / s0.x - 1.5f) < 1e-3f);
    scene::SceneState s = baseScene(1.0f);
    for (auto culling : {InstancedSource::Culling::Gpu, InstancedSource::Culling::Cpu}) {
      auto source = std::make_shared<InstancedSource>("spheres", culling);
      source->setInstances(set);
      const Image instanced = renderWith(s, source);
      scene::SceneState reference = s;
      addEntities(reference, placed, set);
      const Difference d = compare(instanced, renderWith(reference, nullptr), 2e-3);
      qInfo("per-axis scale, instanced vs mesh entities: max %.3g, %.4f%% of pixels off by more than 2e-3", d.max,
            100.0 * d.share);
      QVERIFY2(d.share < 0.005, qPrintable(QString::number(d.share)));
    }
  }

  // The packed scale: halves of (across, along), read back per axis.
  void packedScaleKeepsBothFactors() {
    const render::GpuInstance g = render::packInstance({0, 0, 0}, glm::quat(1, 0, 0, 0), glm::vec2(0.75f, 2.5f), 1, 2, 3);
    QCOMPARE(render::instanceScale(g), glm::vec3(0.75f, 0.75f, 2.5f));
    const glm::vec3 odd = render::instanceScale(render::packInstance({}, glm::quat(1, 0, 0, 0), 1.2345f, 0, 0, 0));
    QVERIFY(std::abs(odd.x - 1.2345f) <= 1.2345f * 0x1p-11f && odd.x == odd.z);
  }

  // Wind: none at response 0 (the image is the same at every time), a
  // pure function of the time otherwise (the same image twice, another at
  // another time), and no vertex moves further than the margin the cull
  // sphere grows by: in the model (every time and id sampled) and on the
  // screen (a tall stem seen from above).
  void windIsAPureFunctionOfTimeWithinTheCullMargin() {
    const std::vector<Placed> placed = grid();
    scene::SceneState s = baseScene(1.0f);
    auto at = [](scene::SceneState st, double t) {
      st.time.seconds = t;
      st.time.frame = int64_t(std::llround(t * st.time.fps));
      return st;
    };
    auto stiff = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    stiff->setInstances(instanceSet(placed));
    const Image still = renderWith(at(s, 0.0), stiff);
    QCOMPARE(compare(still, renderWith(at(s, 37.25), stiff), 0.0).max, 0.0);
    QCOMPARE(compare(still, renderWith(at(s, 86400.5), stiff), 0.0).max, 0.0);
    auto windy = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Gpu);
    windy->setInstances(instanceSet(placed, {kSphere, 0.0f, 0.0f, 3.0f}));
    const Image t0 = renderWith(at(s, 0.0), windy);
    const Image t1 = renderWith(at(s, 2.3), windy), t1again = renderWith(at(s, 2.3), windy);
    QCOMPARE(compare(t1, t1again, 0.0).max, 0.0);
    QVERIFY(compare(t0, t1, 2e-3).share > 0.001);
    auto cpuWindy = std::make_shared<InstancedSource>("spheres", InstancedSource::Culling::Cpu);
    cpuWindy->setInstances(instanceSet(placed, {kSphere, 0.0f, 0.0f, 3.0f}));
    QVERIFY(compare(t1, renderWith(at(s, 2.3), cpuWindy), 1e-5).max <= 1e-4);

    // The model's bound, sampled.
    for (float response : {0.5f, 1.0f, 10.0f}) {
      float most = 0.0f;
      for (uint32_t id = 0; id < 64; ++id)
        for (int k = 0; k < 600; ++k)
          most = std::max(most, glm::length(render::instanceWindOffset(response, 1.0f, 1.0f, 4.0f, id * 7919u,
                                                                       0.1 * k + 1e5 * (id % 3))));
      const float margin = render::instanceWindMargin(response, 4.0f);
      qInfo("wind %.1f: largest move %.4f m of a 4 m stem, margin %.4f m", double(response), double(most),
            double(margin));
      QVERIFY(most <= margin && most > 0.85f * margin);
    }

    // On the screen: a stem 3 m tall (kSphere stretched along z), seen from
    // 25 m straight above, at the strongest response. Every pixel the swayed
    // stem covers lies within the margin (projected at the tip, the nearest
    // point: the most pixels per metre) of the still stem's pixels.
    render::RenderView top;
    top.width = top.height = 200;
    top.fovY = glm::radians(40.0);
    const glm::dvec3 base = kUtm + glm::dvec3(5.0, 5.0, 0.0);
    top.eye = base + glm::dvec3(0.0, 0.0, 25.0);
    top.orientation = test::lookFrom(top.eye, base + glm::dvec3(0.0, 0.001, 0.0)).rotation;
    scene::SceneState plain = s;
    plain.settings.shadows = false;
    std::vector<Placed> stem{{base, glm::dquat(1, 0, 0, 0), 0.5, 4242, 5.0}};
    const float height = kSphereRadius * 5.0f, response = 10.0f;
    auto still1 = std::make_shared<InstancedSource>("stem", InstancedSource::Culling::Gpu);
    still1->setInstances(instanceSet(stem));
    auto swaying = std::make_shared<InstancedSource>("stem", InstancedSource::Culling::Gpu);
    swaying->setInstances(instanceSet(stem, {kSphere, 0.0f, 0.0f, response}));
    // The time the model moves the tip the most over a few seconds.
    double when = 0.0;
    float tip = 0.0f;
    for (int k = 0; k < 200; ++k) {
      const glm::vec3 o = render::instanceWindOffset(response, kSphereRadius, kSphereRadius, 5.0f, 4242, 0.05 * k);
      if (glm::length(glm::vec2(o)) > tip) tip = glm::length(glm::vec2(o)), when = 0.05 * k;
    }
    const Image ground = renderWith(at(plain, when), nullptr, nullptr, top);
    const Image upright = renderWith(at(plain, when), still1, nullptr, top);
    const Image bent = renderWith(at(plain, when), swaying, nullptr, top);
    auto mask = [&](const Image& img) {
      std::vector<glm::ivec2> px;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          const size_t p = size_t(y) * size_t(img.width) + size_t(x);
          if (std::abs(img.rgbaF[p * 4] - ground.rgbaF[p * 4]) + std::abs(img.rgbaF[p * 4 + 1] - ground.rgbaF[p * 4 + 1]) >
              0.02f)
            px.emplace_back(x, y);
        }
      return px;
    };
    const std::vector<glm::ivec2> a = mask(upright), b = mask(bent);
    QVERIFY(a.size() > 20 && b.size() > 20);
    // How far the swayed stem's pixels reach beyond the still one's, and
    // from its axis (the still footprint's centre: the tip is over it).
    glm::dvec2 axis(0.0);
    for (const glm::ivec2& q : a) axis += glm::dvec2(q) / double(a.size());
    double beyond = 0.0, fromAxis = 0.0;
    for (const glm::ivec2& q : b) {
      double nearest = 1e9;
      for (const glm::ivec2& r : a) nearest = std::min(nearest, glm::length(glm::dvec2(q - r)));
      beyond = std::max(beyond, nearest);
      fromAxis = std::max(fromAxis, glm::length(glm::dvec2(q) - axis));
    }
    const double pixelsPerMetre = double(top.height) / (2.0 * std::tan(0.5 * top.fovY)) / (25.0 - double(height));
    const double marginPixels = double(render::instanceWindMargin(response, height)) * pixelsPerMetre;
    const double tipPixels = double(tip) * pixelsPerMetre;
    qInfo("stem: pixels reach %.1f px beyond the still stem and %.1f px from its axis (model's tip %.1f px), margin "
          "%.1f px",
          beyond, fromAxis, tipPixels, marginPixels);
    QVERIFY2(beyond <= marginPixels + 1.5, qPrintable(QString::number(beyond)));
    // The shader sways as the model does: the farthest pixel is about the tip.
    QVERIFY2(std::abs(fromAxis - tipPixels) <= 2.0, qPrintable(QString::number(fromAxis)));
  }

  // A type that casts no shadow is in no shadow view: the ground under the
  // spheres is as lit as with no shadows at all, while casting types shade it.
  void typeWithoutShadowsLeavesTheGroundLit() {
    const std::vector<Placed> placed = grid();
    scene::SceneState s = baseScene(1.0f);
    scene::SceneState noShadow = s;
    noShadow.settings.shadows = false;
    for (auto culling : {InstancedSource::Culling::Gpu, InstancedSource::Culling::Cpu}) {
      render::InstanceType type{kSphere};
      type.castShadows = false;
      auto source = std::make_shared<InstancedSource>("spheres", culling);
      source->setInstances(instanceSet(placed, type));
      const Image lit = renderWith(s, source), unshadowed = renderWith(noShadow, source);
      size_t darker = 0;
      for (size_t p = 0; p < lit.rgbaF.size() / 4; ++p)
        if (lit.rgbaF[p * 4 + 1] < unshadowed.rgbaF[p * 4 + 1] - 0.02f) ++darker;
      qInfo("pixels in a shadowless type's shadow: %zu", darker);
      QCOMPARE(darker, size_t(0));
    }
  }
};

QTEST_GUILESS_MAIN(TestDrawSources)
#include "test_draw_sources.moc"
